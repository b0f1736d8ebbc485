"""Similarity of submissions, for `grade-all --similarity`: a report to read, not a verdict.

Files are compared on their optimised SPIR-V (lab.grading.spirv: dummy statements, new
names and a library function inlined by hand vanish) or, where a file does not compile or
spirv-tools is missing, on tokens in the manner of MOSS (Schleimer, Wilkerson and Aiken,
"Winnowing", SIGMOD 2003: names as one token, winnowed k-gram fingerprints). The stub's
features never count: every student starts from it.

In a short exercise every correct answer compiles to the solution's code, so closeness
alone would list a class of correct students pair after pair. The report therefore says
two things apart. (1) Each student whose file is nearly the solution or the library's
code is listed once, against it: a question for the TA (did they copy the answer? in a
short exercise, probably not), not a pair. (2) Two students are listed only for what they
share beyond every reference (solution, the correct variants kept with it, the library,
the solution with each stored mistake), each shared feature weighted by its rarity in the
class (inverse document frequency: what many students have is chance, not copying): the
shared weight must be large (MIN_SHARED features that only the two have, or the
equivalent) and most of the smaller file's remainder. A copied idiosyncratic or wrong
file passes both; a common mistake is too small and too frequent, and independent
rewrites share common idioms only. Identical wrong values on the probes that no third
student has halve the weight needed.
"""

from __future__ import annotations

import csv
import hashlib
import html
import math
import os
import re
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

from lab.grading import spirv
from lab.grading.spec import ExerciseError
from lab.models import SHADER_DIR

K = 12  # tokens per k-gram: shorter matches are common idioms (max(dot(N, L), 0.0))
WINDOW = 4  # winnowing window: a match of K + WINDOW - 1 tokens is always seen
HTML_PAIRS = 300  # pairs shown side by side (the CSV has all)
THRESHOLD = 0.6  # tokens: share of the smaller file's fingerprints found in a reference
# Share of the smaller file's SPIR-V features found in a reference file that lists the
# student against it: copies with dummy code and new names score 1.00, independent
# rewrites 0.32 to 0.65 (tests/test_similarity_spirv.py).
SPIRV_THRESHOLD = 0.8
# Pairs of students, on what is left beyond the references (tests/test_similarity_class.py):
MIN_SHARED = 11.0  # shared weight, in features only the two have (one feature: weight 1)
PAIR_SHARE = 0.75  # and this share of the smaller remainder's weight
MIN_FEATURES = 10  # fewer features than this (a stub barely touched) weigh less
TOKEN = re.compile(r"[A-Za-z_]\w*|\d+\.?\d*(?:[eE][-+]?\d+)?[fFuU]?|\.\d+(?:[eE][-+]?\d+)?|\S")
COMMENTS = re.compile(r"//[^\n]*|/\*.*?(?:\*/|\Z)", re.S)
KEEP = set(
    """attribute const uniform varying layout centroid flat smooth break continue do for while
    if else in out inout float int uint void bool true false return struct discard highp
    mediump lowp precision vec2 vec3 vec4 ivec2 ivec3 ivec4 bvec2 bvec3 bvec4 mat2 mat3 mat4
    radians degrees sin cos tan asin acos atan sinh cosh tanh pow exp log exp2 log2 sqrt
    inversesqrt abs sign floor trunc round ceil fract mod min max clamp mix step smoothstep
    isnan isinf length distance dot cross normalize reflect refract faceforward BRDF""".split()
)


@dataclass
class Document:
    """One file: its fingerprints (hash -> first line) and its text for the report."""

    owner: str
    label: str
    text: str
    prints: dict[int, int] = field(default_factory=dict)
    features: Counter | None = None  # optimised SPIR-V features, stub's removed (spirv.py)
    shapes: Counter | None = None  # the same, one operand level deep (spirv.PAIR_DEPTH)


def tokens(code: str) -> list[tuple[str, int]]:
    """(normalised token, line) pairs: comments gone, chosen names one token, numbers as values."""
    blank = COMMENTS.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), code)
    out = []
    for match in TOKEN.finditer(blank):
        word = match.group(0)
        line = blank.count("\n", 0, match.start()) + 1
        if word[0].isalpha() or word[0] == "_":
            word = word if word in KEEP else "id"
        elif word[0].isdigit() or (word[0] == "." and len(word) > 1):
            try:
                word = repr(float(word.rstrip("fFuU")))
            except ValueError:
                pass
        out.append((word, line))
    return out


def fingerprints(code: str) -> dict[int, int]:
    """Winnowed k-gram hashes of the normalised tokens -> the line each match starts on."""
    toks = tokens(code)
    grams = []
    for i in range(len(toks) - K + 1):
        text = " ".join(t for t, _ in toks[i : i + K])
        grams.append(
            (int.from_bytes(hashlib.blake2b(text.encode(), digest_size=8).digest()), toks[i][1])
        )
    chosen: dict[int, int] = {}
    for i in range(max(len(grams) - WINDOW + 1, 1 if grams else 0)):
        value, line = min(grams[i : i + WINDOW], key=lambda g: g[0])
        chosen.setdefault(value, line)
    return chosen


def document(owner: str, label: str, text: str, base: set[int]) -> Document:
    prints = {h: line for h, line in fingerprints(text).items() if h not in base}
    return Document(owner, label, text, prints)


def score(a: Document, b: Document) -> float:
    """Share of the smaller file's SPIR-V features found in the other where both have
    them, else of its token fingerprints (0 to 1)."""
    if a.features is not None and b.features is not None:
        small = min(sum(a.features.values()), sum(b.features.values()))
        if small == 0:
            return 0.0
        return sum((a.features & b.features).values()) / max(small, MIN_FEATURES)
    if not a.prints or not b.prints:
        return 0.0
    common = len(a.prints.keys() & b.prints.keys())
    return common / min(len(a.prints), len(b.prints))


def library_documents(exercise, base: set[int]) -> list[Document]:
    """The shipped shaders and the exercise's solution: copying any of them shows up."""
    docs = []
    for path in sorted(SHADER_DIR.glob("*/*.glsl")):
        if path.parent.name != "views":
            label = f"shaders/{path.parent.name}/{path.name}"
            docs.append(document("library", label, path.read_text(encoding="utf-8"), base))
    if exercise.solution.is_file():
        text = exercise.solution.read_text(encoding="utf-8")
        docs.append(document("solution", f"solutions/{exercise.name}", text, base))
    return docs


def known_answers(exercise, base: set[int]) -> list[Document]:
    """What any student may write without copying: the correct variants kept with the
    solution and the solution with each stored mistake. Never listed, only subtracted."""
    from lab.grading.mistakes import known_mistakes

    docs = []
    folder = exercise.solution.parent / "correct"
    for path in sorted(folder.glob("*.glsl")) if folder.is_dir() else []:
        docs.append(document("variant", f"correct/{path.name}", path.read_text("utf-8"), base))
    if exercise.solution.is_file():
        solution = exercise.solution.read_text(encoding="utf-8")
        try:
            mistakes = [(m.key, m.apply(solution)) for m in known_mistakes(exercise)]
        except ExerciseError:
            mistakes = []  # a stale list: the grader says so; the report goes on without it
        docs += [document("mistake", key, text, base) for key, text in mistakes]
    return docs


@dataclass
class Match:
    exercise: str
    a: Document
    b: Document
    score: float  # pairs: share of the smaller remainder's weight; references: score()
    behaviour: str = ""  # the checks failed with identical values that no third student has
    method: str = "tokens"  # "SPIR-V" where both files compiled (spirv.py)
    shared: float = 0.0  # pairs: the shared remainder's weight, in pair-unique marks
    common: frozenset = frozenset()  # pairs: fingerprints both have and no reference has

    @property
    def pair(self) -> bool:
        """Two students (else a student and a reference file)."""
        return self.b.owner not in ("library", "solution")


def wrong_values(task) -> dict[str, str]:
    """check name -> a digest of its failing values (only checks that failed on values)."""
    out = {}
    for result in task.checks():
        if result.status == "failed" and result.rows:
            out[result.name] = repr([row[-1] for row in result.rows])
    return out


def marks(doc: Document, method: str) -> set:
    """The document's features (SPIR-V) or fingerprints (tokens), the stub's already gone."""
    return set(doc.shapes or ()) if method == "SPIR-V" else set(doc.prints)


@dataclass
class Rarity:
    """What the class shares beyond the references, for one method: a mark's weight is its
    inverse document frequency over the students' remainders, scaled so that a mark only
    two students have weighs 1 (log-likelihood of copying against chance, per mark)."""

    reference: set
    weight: dict

    @classmethod
    def of(cls, students: list[set], references: list[set]) -> Rarity:
        reference = set().union(*references)
        counts: Counter = Counter()
        for own in students:
            counts.update(own - reference)
        total = len(students) + 1
        scale = math.log(max(total, 3) / 2)  # one student alone: no pair, no zero
        weight = {m: math.log(total / n) / scale for m, n in counts.items()}
        return cls(reference, weight)

    def mass(self, own: set) -> float:
        return sum(self.weight.get(m, 0.0) for m in own - self.reference)


def compare_class(students: dict[str, dict[str, tuple[str, object]]], exercises) -> list[Match]:
    """students: name -> exercise name -> (file text, graded Task or None). Listed: each
    student whose file is (nearly) a reference's, once; pairs of students who share
    enough rare code beyond every reference (solution, correct variants, library, stored
    mistakes): what any correct answer shares does not count."""
    matches = []
    for exercise in exercises:
        stub = exercise.stub.read_text(encoding="utf-8") if exercise.stub.is_file() else ""
        base = set(fingerprints(stub))
        docs, wrong = [], {}
        for name, files in students.items():
            if exercise.name in files:
                text, task = files[exercise.name]
                docs.append(document(name, f"{name}/{exercise.student_file}", text, base))
                wrong[name] = wrong_values(task) if task is not None else {}
        library = library_documents(exercise, base)
        known = known_answers(exercise, base)
        if spirv.available():
            library += spirv_library(exercise, base)
            compiled = [d for d in library if d.owner == "solution" or d.label.endswith("(SPIR-V)")]
            add_features(exercise, stub, docs + compiled + known)
        for doc in docs:
            best = max(
                filter(None, (_reference(exercise.name, doc, r) for r in library)),
                key=lambda m: (m.score, m.b.owner == "solution"),
                default=None,
            )
            if best is not None:
                matches.append(best)
        matches += _pairs(exercise.name, docs, library + known, _rare_wrongs(wrong))
    matches.sort(key=lambda m: (not m.pair, -m.shared, m.exercise, -m.score, m.a.owner))
    return matches


def _reference(exercise: str, a: Document, ref: Document) -> Match | None:
    """The student and a reference file as a Match if the student's file is nearly it."""
    both = a.features is not None and ref.features is not None
    if (a.features is None) != (ref.features is None) and ref.label.endswith("(SPIR-V)"):
        return None  # the SPIR-V-only library document means nothing to tokens
    value = score(a, ref)
    if value >= (SPIRV_THRESHOLD if both else THRESHOLD):
        return Match(exercise, a, ref, value, method="SPIR-V" if both else "tokens")
    return None


def _rare_wrongs(wrong: dict[str, dict[str, str]]) -> dict[str, dict[str, str]]:
    """Each student's identical-value failures that at most one other student shares: a
    common mistake gives the same values to many students and says nothing of copying."""
    held = Counter((check, v) for values in wrong.values() for check, v in values.items())
    return {
        name: {c: v for c, v in values.items() if held[(c, v)] == 2}
        for name, values in wrong.items()
    }


def _pairs(exercise: str, docs: list[Document], refs: list[Document], wrong) -> list[Match]:
    """Pairs of students whose shared remainder (beyond `refs`) is heavy and most of the
    smaller one's: SPIR-V where both compiled, tokens otherwise."""
    found = []
    printed = set().union(*(r.prints.keys() for r in refs))  # highlighted: what none has
    for method in ("SPIR-V", "tokens"):
        if method == "SPIR-V":
            mine = [d for d in docs if d.features is not None]
            theirs = [r for r in refs if r.features is not None]
        else:
            mine, theirs = docs, [r for r in refs if not r.label.endswith("(SPIR-V)")]
        own = {d.owner: marks(d, method) for d in mine}
        rarity = Rarity.of(list(own.values()), [marks(r, method) for r in theirs])
        rest = {d.owner: own[d.owner] - rarity.reference for d in mine}
        mass = {d.owner: rarity.mass(rest[d.owner]) for d in mine}
        for i, a in enumerate(mine):
            if not rest[a.owner]:
                continue  # all of it is in a reference: listed once, against that reference
            for b in mine[i + 1 :]:
                if method == "tokens" and a.features is not None and b.features is not None:
                    continue  # compared on SPIR-V
                common = rest[a.owner] & rest[b.owner]
                if not common:
                    continue
                shared = rarity.mass(common)
                same = sorted(c for c, v in wrong[a.owner].items() if wrong[b.owner].get(c) == v)
                bar = MIN_SHARED / 2 if same else MIN_SHARED  # identical rare values back it
                share = shared / max(min(mass[a.owner], mass[b.owner]), bar)
                if shared >= bar and share >= PAIR_SHARE:
                    prints = frozenset(a.prints.keys() & b.prints.keys() - printed)
                    found.append(
                        Match(exercise, a, b, share, ", ".join(same), method, shared, prints)
                    )
    return found


def spirv_library(exercise, base: set[int]) -> list[Document]:
    """The library's own code for what the exercise asks (its model's BRDF, the term file
    the student's replaces, or the lobe sampler), compared on SPIR-V only."""
    text = spirv.library_text(exercise)
    if text is None:
        return []
    return [Document("library", f"library's own {exercise.name} (SPIR-V)", text)]


def add_features(exercise, stub: str, docs: list[Document]) -> None:
    """Each document's SPIR-V features less the stub's; compiled in parallel (each file is
    three short processes), identical texts once."""
    texts = list(dict.fromkeys([stub, *(d.text for d in docs)]))
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        compiled = list(pool.map(lambda text: spirv.both_depths(text, exercise), texts))
    found = dict(zip(texts, compiled, strict=True))
    base = found[stub] or (Counter(), Counter())
    for doc in docs:
        if found[doc.text] is not None:
            doc.features, doc.shapes = (
                mine - theirs for mine, theirs in zip(found[doc.text], base, strict=True)
            )


def method_note() -> str:
    """How the report compares files, in words (the fallback said where it happens)."""
    rule = (
        f"two students are listed when they share, beyond the solution, its correct "
        f"variants, the library and the stored mistakes, the weight of {MIN_SHARED:.0f} "
        f"features that only they have (rarer features weigh more) and {PAIR_SHARE:.0%} of "
        "the smaller file's remainder"
    )
    if spirv.available():
        return (
            f"optimised SPIR-V (glslang, spirv-opt -O); files that do not compile are "
            f"compared on tokens. A student is listed against the solution or the library "
            f"from {SPIRV_THRESHOLD:.0%} of their instructions (tokens: {THRESHOLD:.0%}); " + rule
        )
    return (
        "tokens only (spirv-opt or glslangValidator is not installed: install Debian's "
        f"spirv-tools to see through dummy code). A student is listed against the solution "
        f"or the library from {THRESHOLD:.0%} of their fingerprints; " + rule
    )


def write_csv(matches: list[Match], path: Path) -> None:
    from lab.grading.students import cell

    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(
            [
                "exercise",
                "student",
                "other",
                "similarity",
                "shared rare code",
                "method",
                "same wrong values",
            ]
        )
        for m in matches:
            writer.writerow(
                [
                    m.exercise,
                    cell(m.a.owner),
                    cell(m.b.label),
                    f"{m.score:.2f}",
                    f"{m.shared:.1f}" if m.pair else "",
                    m.method,
                    m.behaviour,
                ]
            )


def _side(doc: Document, lines: set[int]) -> str:
    rows = []
    for number, text in enumerate(doc.text.splitlines(), start=1):
        # a shared line is marked in words too, not by its colour alone
        mark, shared = (' class="hit"', " ≡") if number in lines else ("", "")
        rows.append(f"<tr{mark}><td>{number}{shared}</td><td>{html.escape(text)}</td></tr>")
    return f"<div><h3>{html.escape(doc.label)}</h3><table>{''.join(rows)}</table></div>"


def _spans(doc: Document, common: set[int]) -> set[int]:
    """Lines covered by the shared fingerprints (each k-gram spans a few lines)."""
    return {doc.prints[h] + d for h in common for d in range(2)}


def _references(matches: list[Match]) -> str:
    """One row per student listed against a reference file, grouped by exercise."""
    if not matches:
        return ""
    rows = "".join(
        f"<tr><td>{html.escape(m.exercise)}</td><td>{html.escape(m.a.owner)}</td>"
        f"<td>{html.escape(m.b.label)}</td><td>{m.score:.0%} ({m.method})</td></tr>"
        for m in sorted(matches, key=lambda m: (m.exercise, m.a.owner))
    )
    return (
        "<h2>Students whose file is (nearly) the reference's</h2><p>Listed once each, not "
        "in pairs: being equal to the solution or the library is not copying from a "
        "classmate. In a short exercise every correct answer compiles to the solution's "
        "code and this only says the answer is right; in a longer one, read the file.</p>"
        "<table class='refs'><tr><th>exercise</th><th>student</th><th>reference</th>"
        f"<th>similarity</th></tr>{rows}</table>"
    )


def write_html(matches: list[Match], path: Path) -> None:
    """Pairs of students with the two files side by side, the code they share beyond the
    references highlighted; then the students equal to a reference, one row each."""
    pairs = [m for m in matches if m.pair]
    parts = [
        "<!doctype html><html lang='en'><meta charset='utf-8'><title>Similarity report</title>"
        "<style>"
        "body{font-family:sans-serif;margin:1em}.pair{display:flex;gap:1em;flex-wrap:wrap}"
        ".pair>div{flex:1 1 28em;overflow-x:auto}table{border-collapse:collapse;"
        "font:12px monospace}td:first-child{color:#595959;padding-right:.6em;text-align:right}"
        "td{white-space:pre}tr.hit{background:#ffe08a}h2{font-size:110%;margin-top:2em}"
        ".refs td,.refs th{padding:0 .8em;text-align:left;color:inherit}"
        f"</style><h1>Similarity report</h1><p>Compared on {html.escape(method_note())}. "
        "A pair's similarity is the share of the smaller file's remainder (what is left "
        "beyond the references) found in the other; highlighted lines are shared code "
        "that no reference has (≡ beside the line number). Similar is not proof: read the code.</p>"
    ]
    if not pairs:
        parts.append("<p>No pair of students shares enough code beyond the references.</p>")
    if len(pairs) > HTML_PAIRS:
        parts.append(
            f"<p>The {HTML_PAIRS} pairs with the most rare code in common of {len(pairs)} are "
            "shown; similarity.csv lists them all.</p>"
        )
    for m in pairs[:HTML_PAIRS]:
        common = set(m.common)
        same = f"; identical wrong values in {html.escape(m.behaviour)}" if m.behaviour else ""
        parts.append(
            f"<h2>{html.escape(m.exercise)}: {html.escape(m.a.owner)} and "
            f"{html.escape(m.b.label)} — {m.score:.0%} of the remainder, weight "
            f"{m.shared:.1f} ({m.method}){same}</h2>"
            f"<div class='pair'>{_side(m.a, _spans(m.a, common))}"
            f"{_side(m.b, _spans(m.b, common))}</div>"
        )
    parts.append(_references([m for m in matches if not m.pair]))
    path.write_text("".join(parts), encoding="utf-8")

"""Similarity of submissions, for `grade-all --similarity`: a report to read, not a verdict.

Token similarity in the manner of MOSS (Schleimer, Wilkerson and Aiken, "Winnowing: local
algorithms for document fingerprinting", SIGMOD 2003): comments and whitespace go,
identifiers the student chose become one token (renaming hides nothing), k-grams of tokens
are hashed and winnowed to fingerprints, and the stub's own fingerprints are ignored (every
student starts from it). Each student is compared with every other and with the shipped
library (shaders/) and solutions. Behavioural similarity: two submissions that fail the
same check with the same wrong values, where honest mistakes rarely coincide.

Where glslang and spirv-tools are installed, files are compared on their optimised SPIR-V
instead (lab.grading.spirv): a dummy statement between the lines of a copy, renamed
variables or a library function inlined by hand no longer hide it (tokens: 0.24 to 0.56 for
such copies; SPIR-V: 1.00), while independent rewrites stay below SPIRV_THRESHOLD. Without
the tools (macOS without spirv-tools) the report says it fell back to tokens.
"""

from __future__ import annotations

import csv
import hashlib
import html
import os
import re
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

from lab.grading import spirv
from lab.models import SHADER_DIR

K = 12  # tokens per k-gram: shorter matches are common idioms (max(dot(N, L), 0.0))
WINDOW = 4  # winnowing window: a match of K + WINDOW - 1 tokens is always seen
HTML_PAIRS = 300  # pairs shown side by side (the CSV has all)
THRESHOLD = 0.6  # share of the smaller file's fingerprints that the report lists
# Share of the smaller file's SPIR-V features found in the other: copies with dummy code and
# new names score 1.00, independent rewrites 0.32 to 0.65 (tests/test_similarity_spirv.py).
SPIRV_THRESHOLD = 0.8
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


@dataclass
class Match:
    exercise: str
    a: Document
    b: Document
    tokens: float  # the similarity, by `method`
    behaviour: str = ""  # the checks failed with identical values
    method: str = "tokens"  # "SPIR-V" where both files compiled (spirv.py)


def wrong_values(task) -> dict[str, str]:
    """check name -> a digest of its failing values (only checks that failed on values)."""
    out = {}
    for result in task.checks():
        if result.status == "failed" and result.rows:
            out[result.name] = repr([row[-1] for row in result.rows])
    return out


def compare_class(students: dict[str, dict[str, tuple[str, object]]], exercises) -> list[Match]:
    """students: name -> exercise name -> (file text, graded Task or None). Pairs listed are
    those above THRESHOLD or with identical wrong values."""
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
        if spirv.available():
            library += spirv_library(exercise, base)
            compiled = [d for d in library if d.owner == "solution" or d.label.endswith("(SPIR-V)")]
            add_features(exercise, stub, docs + compiled)
        for i, a in enumerate(docs):
            for b in docs[i + 1 :]:
                same = sorted(c for c, v in wrong[a.owner].items() if wrong[b.owner].get(c) == v)
                match = _match(exercise.name, a, b, ", ".join(same))
                if match is not None:
                    matches.append(match)
            for lib in library:
                match = _match(exercise.name, a, lib, "")
                if match is not None:
                    matches.append(match)
    matches.sort(key=lambda m: (-m.tokens, m.exercise, m.a.owner))
    return matches


def _match(exercise: str, a: Document, b: Document, same: str) -> Match | None:
    """The pair as a Match if it reaches its method's threshold or shares wrong values."""
    both = a.features is not None and b.features is not None
    if a.owner == "library" and b.owner == "library":
        return None
    if (a.features is None) != (b.features is None) and "SPIR-V" in (a.label + b.label):
        return None  # the SPIR-V-only library document means nothing to tokens
    value = score(a, b)
    if value >= (SPIRV_THRESHOLD if both else THRESHOLD) or same:
        return Match(exercise, a, b, value, same, "SPIR-V" if both else "tokens")
    return None


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
        compiled = list(pool.map(lambda text: spirv.normalised(text, exercise), texts))
    found = dict(zip(texts, compiled, strict=True))
    base = found[stub] or Counter()
    for doc in docs:
        features = found[doc.text]
        doc.features = features - base if features is not None else None


def method_note() -> str:
    """How the report compares files, in words (the fallback said where it happens)."""
    if spirv.available():
        return (
            f"optimised SPIR-V (glslang, spirv-opt -O): pairs from {SPIRV_THRESHOLD:.0%} of "
            "the smaller file's instructions are listed; files that do not compile are "
            f"compared on tokens, from {THRESHOLD:.0%}"
        )
    return (
        "tokens only (spirv-opt or glslangValidator is not installed: install Debian's "
        f"spirv-tools to see through dummy code); pairs from {THRESHOLD:.0%} are listed"
    )


def write_csv(matches: list[Match], path: Path) -> None:
    from lab.grading.students import cell

    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(
            ["exercise", "student", "other", "similarity", "method", "same wrong values"]
        )
        for m in matches:
            writer.writerow(
                [
                    m.exercise,
                    cell(m.a.owner),
                    cell(m.b.label),
                    f"{m.tokens:.2f}",
                    m.method,
                    m.behaviour,
                ]
            )


def _side(doc: Document, lines: set[int]) -> str:
    rows = []
    for number, text in enumerate(doc.text.splitlines(), start=1):
        mark = ' class="hit"' if number in lines else ""
        rows.append(f"<tr{mark}><td>{number}</td><td>{html.escape(text)}</td></tr>")
    return f"<div><h3>{html.escape(doc.label)}</h3><table>{''.join(rows)}</table></div>"


def _spans(doc: Document, common: set[int]) -> set[int]:
    """Lines covered by the shared fingerprints (each k-gram spans a few lines)."""
    return {doc.prints[h] + d for h in common for d in range(2)}


def write_html(matches: list[Match], path: Path) -> None:
    """Each listed pair with the two files side by side, shared code highlighted."""
    parts = [
        "<!doctype html><meta charset='utf-8'><title>Similarity report</title><style>"
        "body{font-family:sans-serif;margin:1em}.pair{display:flex;gap:1em;flex-wrap:wrap}"
        ".pair>div{flex:1 1 28em;overflow-x:auto}table{border-collapse:collapse;"
        "font:12px monospace}td:first-child{color:#888;padding-right:.6em;text-align:right}"
        "td{white-space:pre}tr.hit{background:#ffe08a}h2{font-size:110%;margin-top:2em}"
        f"</style><h1>Similarity report</h1><p>Compared on {html.escape(method_note())}. "
        "Similarity is the share of the smaller file's code (the stub left out) found in the "
        "other; pairs failing the same check with identical values are listed too. Similar "
        "is not proof: read the code.</p>"
    ]
    if not matches:
        parts.append("<p>No pair reaches the threshold.</p>")
    if len(matches) > HTML_PAIRS:
        parts.append(
            f"<p>The {HTML_PAIRS} most similar of {len(matches)} pairs are shown; "
            "similarity.csv lists them all.</p>"
        )
    for m in matches[:HTML_PAIRS]:
        common = m.a.prints.keys() & m.b.prints.keys()
        same = f"; identical wrong values in {html.escape(m.behaviour)}" if m.behaviour else ""
        parts.append(
            f"<h2>{html.escape(m.exercise)}: {html.escape(m.a.owner)} and "
            f"{html.escape(m.b.label)} — {m.tokens:.0%} ({m.method}){same}</h2>"
            f"<div class='pair'>{_side(m.a, _spans(m.a, common))}"
            f"{_side(m.b, _spans(m.b, common))}</div>"
        )
    path.write_text("".join(parts), encoding="utf-8")

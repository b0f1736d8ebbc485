"""Similarity of submissions, for `grade-all --similarity`: a report to read, not a verdict.

Token similarity in the manner of MOSS (Schleimer, Wilkerson and Aiken, "Winnowing: local
algorithms for document fingerprinting", SIGMOD 2003): comments and whitespace go,
identifiers the student chose become one token (renaming hides nothing), k-grams of tokens
are hashed and winnowed to fingerprints, and the stub's own fingerprints are ignored (every
student starts from it). Each student is compared with every other and with the shipped
library (shaders/) and solutions. Behavioural similarity: two submissions that fail the
same check with the same wrong values, where honest mistakes rarely coincide.
"""

from __future__ import annotations

import csv
import hashlib
import html
import re
from dataclasses import dataclass, field
from pathlib import Path

from lab.models import SHADER_DIR

K = 12  # tokens per k-gram: shorter matches are common idioms (max(dot(N, L), 0.0))
WINDOW = 4  # winnowing window: a match of K + WINDOW - 1 tokens is always seen
HTML_PAIRS = 300  # pairs shown side by side (the CSV has all)
THRESHOLD = 0.6  # share of the smaller file's fingerprints that the report lists
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
    """Share of the smaller file's fingerprints found in the other (0 to 1)."""
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
    tokens: float
    behaviour: str = ""  # the checks failed with identical values


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
        for i, a in enumerate(docs):
            for b in docs[i + 1 :]:
                same = sorted(c for c, v in wrong[a.owner].items() if wrong[b.owner].get(c) == v)
                value = score(a, b)
                if value >= THRESHOLD or same:
                    matches.append(Match(exercise.name, a, b, value, ", ".join(same)))
            for lib in library:
                value = score(a, lib)
                if value >= THRESHOLD:
                    matches.append(Match(exercise.name, a, lib, value))
    matches.sort(key=lambda m: (-m.tokens, m.exercise, m.a.owner))
    return matches


def write_csv(matches: list[Match], path: Path) -> None:
    from lab.grading.students import cell

    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(["exercise", "student", "other", "token similarity", "same wrong values"])
        for m in matches:
            writer.writerow(
                [m.exercise, cell(m.a.owner), cell(m.b.label), f"{m.tokens:.2f}", m.behaviour]
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
        "</style><h1>Similarity report</h1><p>Token similarity: share of the smaller file's "
        "fingerprints (identifiers, comments and layout normalised, the stub left out) found "
        f"in the other; pairs from {THRESHOLD:.0%} are listed, and pairs failing the same "
        "check with identical values. Similar is not proof: read the code.</p>"
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
            f"{html.escape(m.b.label)} — {m.tokens:.0%} of tokens{same}</h2>"
            f"<div class='pair'>{_side(m.a, _spans(m.a, common))}"
            f"{_side(m.b, _spans(m.b, common))}</div>"
        )
    path.write_text("".join(parts), encoding="utf-8")

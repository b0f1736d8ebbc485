"""A made-up class for the similarity report (tests/test_similarity_class.py): correct
answers written many ways, two students who make the same common mistake independently,
and an idiosyncratic file (odd helpers, a wrong normalisation) handed in by its author and
by two copiers who disguise it (new names, dead statements, comments, an operand order
swapped). Only the copiers and the author should be listed as pairs."""

from __future__ import annotations

import random
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
NAMES = ["a", "b", "c", "t", "x", "y", "cosL", "cosV", "cosH", "nl", "nv", "nh", "vh", "k"]

# Blinn-Phong: each slot's ways of writing it; {nl}, {nv}, {h}, {nh}, {s}, {d} are names.
BLINN = {
    "guard": [
        "if ({nl} <= 0.0 || {nv} <= 0.0) return vec3(0.0);",
        "if ({nl} <= 0.0 || {nv} <= 0.0) {{\n        return vec3(0.0);\n    }}",
        "if (min({nl}, {nv}) <= 0.0) return vec3(0.0);",
        "if (!({nl} > 0.0 && {nv} > 0.0)) return vec3(0.0);",
        "if ({nv} <= 0.0 || {nl} <= 0.0) return vec3(0.0);",
    ],
    "half": [
        "vec3 {h} = normalize(L + V);",
        "vec3 {h} = normalize(V + L);",
        "vec3 {h} = (L + V) / length(L + V);",
        "vec3 {h} = (L + V) * inversesqrt(dot(L + V, L + V));",
    ],
    "cos": [
        "max(dot(N, {h}), 0.0)",
        "max(0.0, dot({h}, N))",
        "clamp(dot(N, {h}), 0.0, 1.0)",
        "dot(N, {h})",
    ],
    "lobe": ["pow({nh}, ke)", "pow({nh}, ke)", "exp(ke * log({nh}))"],
    "diffuse": ["kd * INV_PI", "kd / PI", "INV_PI * kd", "kd * (1.0 / PI)"],
    "result": ["{d} + ks * {s}", "ks * {s} + {d}", "{d} + {s} * ks"],
}
BLINN_BODY = """vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {{
    float {nl} = dot(N, L);
    float {nv} = dot(N, V);
    {guard}
    {half}
    float {nh} = {cos};
    float {s} = {lobe};
    vec3 {d} = {diffuse};
    return {result};
}}
"""
# A common mistake not in mistakes.toml: the specular lobe divided by pi as well.
BLINN_MISTAKE = ("lobe", "pow({nh}, ke) / PI")
BLINN_ODD = """float sat(float x) { return clamp(x, 0.0, 1.0); }

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float a = sat(dot(N, L));
    float b = sat(dot(N, V));
    if (a * b < 1e-5) return vec3(0.0);
    vec3 mid = L + V;
    float len2 = max(dot(mid, mid), 1e-8);
    float c = sat(dot(N, mid) / sqrt(len2));
    float spec = exp2(ke * log2(c + 1e-7)) * (ke + 8.0) / (8.0 * PI);
    vec3 diffuse = kd * 0.318310;
    return diffuse + ks * spec;
}
"""

# Cook-Torrance: the stub's helpers stay; the ways of assembling the BRDF vary.
COOK = {
    "guard": BLINN["guard"],
    "half": BLINN["half"],
    "cos": ["dot(N, {h})", "dot({h}, N)"],
    "vcos": ["dot(V, {h})", "dot({h}, V)", "dot(L, {h})"],
    "diffuse": BLINN["diffuse"],
    "assemble": [
        "vec3 {s} = ks * fresnel_F({vh}) * (microfacet_D({nh}) * G_vgroove({nl}, {nv}, {nh}, "
        "{vh}) / (PI * {nl} * {nv}));\n    return {diffuse} + {s};",
        "vec3 {s} = fresnel_F({vh}) * microfacet_D({nh}) * G_vgroove({nl}, {nv}, {nh}, {vh});"
        "\n    {s} /= PI * {nl} * {nv};\n    return {diffuse} + {s} * ks;",
        "float {d} = microfacet_D({nh}) * G_vgroove({nl}, {nv}, {nh}, {vh});\n"
        "    return {diffuse} + ks * fresnel_F({vh}) * {d} / (PI * {nl} * {nv});",
        "float {d} = PI * {nl} * {nv};\n    vec3 {s} = fresnel_F({vh}) * microfacet_D({nh});\n"
        "    {s} *= G_vgroove({nl}, {nv}, {nh}, {vh}) / {d};\n    return ks * {s} + {diffuse};",
    ],
}
COOK_BODY = """vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {{
    float {nl} = dot(N, L);
    float {nv} = dot(N, V);
    {guard}
    {half}
    float {nh} = {cos};
    float {vh} = {vcos};
    {assemble}
}}
"""
# A common mistake not in mistakes.toml: the denominator without N.V.
COOK_MISTAKE = (
    "assemble",
    "vec3 {s} = fresnel_F({vh}) * microfacet_D({nh}) * G_vgroove("
    "{nl}, {nv}, {nh}, {vh}) / (PI * {nl});\n    return {diffuse} + ks * {s};",
)
COOK_ODD = """vec3 spec_term(float nl, float nv, float nh, float vh) {
    float denom = max(PI * nl * nv, 1e-6);
    float dg = microfacet_D(nh) * G_vgroove(nl, nv, nh, vh);
    return fresnel_F(vh) * min(dg / denom, 1e4);
}

vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    float nl = dot(N, L), nv = dot(N, V);
    if (nl < 1e-4 || nv < 1e-4) return vec3(0.0);
    float vh = sqrt(0.5 + 0.5 * dot(L, V));
    float nh = (nl + nv) / (2.0 * vh);
    vec3 s = spec_term(nl, nv, nh, vh);
    return kd * 0.3183099 + s * ks;
}
"""
TEMPLATES = {
    "03_blinn_phong": (BLINN, BLINN_BODY, BLINN_MISTAKE, BLINN_ODD),
    "09_cook_torrance": (COOK, COOK_BODY, COOK_MISTAKE, COOK_ODD),
}


def _helpers(stub: str) -> str:
    """The stub's comment header and helper functions: everything before BRDF."""
    return stub[: stub.index("vec3 BRDF(")]


def honest(exercise, rng: random.Random, mistake: tuple[str, str] | None = None) -> str:
    """A correct answer with each slot chosen at random and names of its own."""
    slots, body, _, _ = TEMPLATES[exercise.name]
    names = dict(zip(["nl", "nv", "h", "nh", "vh", "s", "d"], rng.sample(NAMES, 7), strict=True))
    chosen = {slot: rng.choice(ways) for slot, ways in slots.items()}
    if mistake:
        chosen[mistake[0]] = mistake[1]
    filled: dict[str, str] = {}
    for slot, way in chosen.items():  # in order: a later slot may use an earlier one
        filled[slot] = way.format(**names, **filled)
    return _helpers(exercise.stub.read_text("utf-8")) + body.format(**names, **filled)


def disguise(text: str, rng: random.Random) -> str:
    """A copy as students hide one: every local name changed, a dead statement after each
    statement, comments, and the last sum's operands swapped."""
    locals_ = set(re.findall(r"\b(?:float|vec3|bool)\s+(\w+)\s*[=,;)]", text))
    locals_ |= set(re.findall(r",\s*(\w+)\s*=", text))
    for number, name in enumerate(sorted(locals_ - {"BRDF", "L", "V", "N", "X", "Y"})):
        text = re.sub(rf"\b{name}\b", f"v{number}_{rng.randrange(100)}", text)
    last = text.rfind("return ")
    end = text.index(";", last)
    sum_ = re.fullmatch(r"return (.+?) \+ (.+)", text[last:end])
    if sum_:
        text = f"{text[:last]}return {sum_.group(2)} + {sum_.group(1)}{text[end:]}"
    out, depth = [], 0
    for number, line in enumerate(text.splitlines()):
        out.append(line)
        depth += line.count("{") - line.count("}")
        if depth > 0 and line.rstrip().endswith(";") and "return" not in line:
            out.append(f"    float tmp{number} = {number}.0 * 0.5; // my own working")
    return "// written by me\n" + "\n".join(out) + "\n"


def make_class(exercise, size: int = 27, seed: int = 1) -> tuple[dict[str, str], set]:
    """name -> file text for a class of `size`: size - 5 honest answers, two with the same
    common mistake, the idiosyncratic file and two disguised copies of it; and the pairs
    that should be listed."""
    rng = random.Random(seed)
    _, _, mistake, odd = TEMPLATES[exercise.name]
    header = _helpers(exercise.stub.read_text("utf-8"))
    files = {f"honest{n:03d}": honest(exercise, rng) for n in range(size - 5)}
    files["mistake_a"] = honest(exercise, rng, mistake)
    files["mistake_b"] = honest(exercise, rng, mistake)
    files["author"] = header + odd
    files["copier_a"] = disguise(header + odd, rng)
    files["copier_b"] = disguise(header + odd, rng)
    copies = {("author", "copier_a"), ("author", "copier_b"), ("copier_a", "copier_b")}
    return files, copies

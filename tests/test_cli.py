"""The command line: real outputs, and one clear line with exit status 2 for each bad input."""

from __future__ import annotations

import csv
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from lab import reference
from lab.cli import main


def run_cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "lab.cli", *args], capture_output=True, text=True)


def write_pairs(path, rows, header="theta_i,phi_i,theta_o,phi_o"):
    path.write_text(header + "\n" + "\n".join(",".join(map(str, r)) for r in rows) + "\n")
    return path


def read_values(path) -> np.ndarray:
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    assert rows[0] == ["r", "g", "b"]
    return np.array(rows[1:], dtype=np.float64)


def test_models_lists_parameters_and_files(capsys):
    assert main(["models"]) == 0
    out = capsys.readouterr().out
    assert "cook_torrance" in out and "shaders/brdfs/ggx.glsl" in out
    assert "ke" in out and "[1, 1000] default 50 (log)" in out
    assert "beckmann|blinn|gaussian" in out


def test_eval_gpu_and_cpu_agree(tmp_path):
    rng = np.random.default_rng(5)
    rows = np.column_stack(
        [
            rng.uniform(0, 80, 50),
            rng.uniform(0, 360, 50),
            rng.uniform(0, 80, 50),
            rng.uniform(0, 360, 50),
        ]
    )
    pairs = write_pairs(tmp_path / "pairs.csv", rows.round(6))
    settings = ["--set", "alpha=0.3", "--set", "kd=0.2,0.3,0.4"]
    assert (
        main(["eval", "ggx", *settings, "--in", str(pairs), "--out", str(tmp_path / "g.csv")]) == 0
    )
    assert (
        main(
            [
                "eval",
                "ggx",
                *settings,
                "--in",
                str(pairs),
                "--out",
                str(tmp_path / "c.csv"),
                "--cpu",
            ]
        )
        == 0
    )
    gpu, cpu = read_values(tmp_path / "g.csv"), read_values(tmp_path / "c.csv")
    assert gpu.shape == (50, 3)
    expected = reference.brdf_angles("ggx", {"alpha": 0.3, "kd": (0.2, 0.3, 0.4)}, rows.round(6))
    np.testing.assert_allclose(cpu, expected, rtol=1e-12)
    np.testing.assert_allclose(gpu, cpu, rtol=1e-4, atol=1e-7)


def test_eval_of_mirror_says_it_is_a_delta(tmp_path, capsys):
    pairs = write_pairs(tmp_path / "p.csv", [[30, 0, 30, 180]])
    assert main(["eval", "mirror", "--in", str(pairs), "--out", str(tmp_path / "o.csv")]) == 0
    assert "delta" in capsys.readouterr().err
    assert (read_values(tmp_path / "o.csv") == 0).all()


@pytest.mark.parametrize("view", ["sphere", "polar", "lobe3d", "slice", "albedo"])
def test_render_writes_a_png(tmp_path, view):
    out = tmp_path / f"{view}.png"
    assert (
        main(
            [
                "render",
                "cook_torrance",
                "--view",
                view,
                "--light",
                "60,0",
                "--size",
                "128",
                "-o",
                str(out),
            ]
        )
        == 0
    )
    image = np.asarray(Image.open(out).convert("RGB"), dtype=np.float64)
    assert image.std() > 5  # something was drawn, not a blank canvas


def test_render_sphere_pixels_follow_the_exponent(tmp_path):
    sizes = []
    for ke in ("4", "120"):
        out = tmp_path / f"p{ke}.png"
        assert (
            main(
                [
                    "render",
                    "phong",
                    "--set",
                    f"ke={ke}",
                    "--set",
                    "kd=0",
                    "--size",
                    "128",
                    "-o",
                    str(out),
                ]
            )
            == 0
        )
        lum = np.asarray(Image.open(out).convert("L"), dtype=np.float64)
        sizes.append((lum > 0.5 * lum.max()).sum())
    assert sizes[0] > 5 * sizes[1]  # a larger exponent makes a smaller highlight


def test_figures_command_writes_the_lecture_figures(tmp_path):
    assert main(["figures", str(tmp_path)]) == 0
    names = {p.name for p in tmp_path.glob("*.png")}
    assert {
        "phong_ke_4.png",
        "phong_ke_50.png",
        "phong_ke_120.png",
        "beckmann_m_0.2.png",
        "beckmann_m_0.6.png",
        "off_specular_peak.png",
        "full_lambert.png",
        "full_lommel_seeliger.png",
    } <= names
    # The full moon is a flat disc: Lommel-Seeliger lit from the eye has a uniform radiance.
    moon = np.asarray(Image.open(tmp_path / "full_lommel_seeliger.png").convert("L"), float)
    sun = np.asarray(Image.open(tmp_path / "full_lambert.png").convert("L"), float)
    c = moon.shape[0] // 2
    assert abs(moon[c, c] - moon[c, int(c * 1.9)]) <= 2
    assert sun[c, c] - sun[c, int(c * 1.9)] > 30


BRDF_EXPLORER_FILE = """analytic
# written in BRDF Explorer's format: int literals where floats are meant, its own PI
::begin parameters
float n 1 1000 20
color tint 1 .5 .25
::end parameters
::begin shader
const float PI = 3.14159265358979;
vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {
    vec3 H = normalize(L + V);
    return tint * (n + 2) / (2 * PI) * pow(max(dot(N, H), 0), n);
}
::end shader
"""


def test_render_and_eval_a_brdf_explorer_file(tmp_path):
    path = tmp_path / "lobe.brdf"
    path.write_text(BRDF_EXPLORER_FILE)
    out = tmp_path / "lobe.png"
    args = [
        "render",
        str(path),
        "--set",
        "n=50",
        "--size",
        "96",
        "--exposure",
        "-4",
        "-o",
        str(out),
    ]
    assert main(args) == 0
    image = np.asarray(Image.open(out).convert("RGB"), dtype=np.float64)
    assert image[..., 0].max() > 1.5 * image[..., 2].max() > 0  # the tint colours the highlight
    pairs = write_pairs(tmp_path / "p.csv", [[30, 0, 30, 180], [30, 0, 60, 180]])
    values = tmp_path / "v.csv"
    assert main(["eval", str(path), "--set", "n=50", "--in", str(pairs), "--out", str(values)]) == 0
    got = read_values(values)
    cos_h = np.cos(np.radians([0.0, 15.0]))
    expected = 52 / (2 * np.pi) * cos_h**50
    np.testing.assert_allclose(got[:, 0], expected, rtol=1e-4)
    np.testing.assert_allclose(got[:, 2], 0.25 * expected, rtol=1e-4)


BAD_INPUTS = [
    (["render", "phongg", "-o", "{tmp}/x.png"], "unknown model 'phongg'"),
    (["render", "phong", "--set", "shininess=3", "-o", "{tmp}/x.png"], "no parameter 'shininess'"),
    (["render", "phong", "--set", "ke=5000", "-o", "{tmp}/x.png"], "outside its range"),
    (["render", "phong", "--set", "ke", "-o", "{tmp}/x.png"], "malformed"),
    (["render", "phong", "--set", "kd=red", "-o", "{tmp}/x.png"], "needs a number"),
    (["render", "phong", "--light", "30", "-o", "{tmp}/x.png"], "--light '30' is malformed"),
    (["render", "phong", "--light", "120,0", "-o", "{tmp}/x.png"], "outside 0..90"),
    (["render", "phong", "-o", "{tmp}/missing/x.png"], "does not exist"),
    (["render", "phong", "-o", "{tmp}"], "is a directory"),
    (["render", "phong", "--size", "0", "-o", "{tmp}/x.png"], "--size 0 is outside"),
    (["render", "phong", "-o", "{tmp}/x.txt"], "must end in .png"),
    (["eval", "phong", "--table", "{tmp}/t.binary", "--in", "{tmp}/text.csv"], "measured model"),
    (["render", "phong", "--size", "100000", "-o", "{tmp}/x.png"], "--size 100000 is outside"),
    (["eval", "phong", "--in", "{tmp}/nope.csv"], "cannot read"),
    (["eval", "phong", "--in", "{tmp}/cols.csv"], "cols.csv:1: missing column(s) phi_o"),
    (["eval", "phong", "--in", "{tmp}/text.csv"], "text.csv:3: expected four numbers"),
    (["render", "{tmp}/broken.glsl", "-o", "{tmp}/x.png"], "broken.glsl:6:"),
    (
        ["render", "{tmp}/versioned.glsl", "-o", "{tmp}/x.png"],
        "versioned.glsl:2: remove the '#version'",
    ),
]


@pytest.mark.parametrize("args, message", BAD_INPUTS, ids=[m for _, m in BAD_INPUTS])
def test_bad_input_gets_one_clear_line(tmp_path, args, message):
    (tmp_path / "cols.csv").write_text("theta_i,phi_i,theta_o\n1,2,3\n")
    (tmp_path / "text.csv").write_text("theta_i,phi_i,theta_o,phi_o\n1,2,3,4\n1,2,x,4\n")
    (tmp_path / "broken.glsl").write_text(
        "// @model broken\n// @param kd color 0.5 0.5 0.5 | diffuse\n"
        "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {\n"
        "    float NoL = dot(N, L);\n    vec3 c = kd * NoL;\n    return undefined_thing * c;\n}\n"
    )
    (tmp_path / "versioned.glsl").write_text(
        "// @model versioned\n#version 330 core\n"
        "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return vec3(0.0); }\n"
    )
    result = run_cli(*[a.format(tmp=tmp_path) for a in args])
    assert result.returncode == 2, result.stderr
    assert "Traceback" not in result.stderr
    assert message in result.stderr
    assert result.stderr.startswith("brdf-lab: error:")


def test_pairs_file_with_a_byte_order_mark(tmp_path):
    """Spreadsheets save CSV with a BOM; the header must still be found."""
    pairs = tmp_path / "excel.csv"
    pairs.write_bytes("\ufefftheta_i,phi_i,theta_o,phi_o\r\n30,0,30,180\r\n".encode())
    out = tmp_path / "v.csv"
    assert (
        main(["eval", "lambert", "--set", "albedo=0.5", "--in", str(pairs), "--out", str(out)]) == 0
    )
    np.testing.assert_allclose(read_values(out), [[0.5 / np.pi] * 3], rtol=1e-6)


def test_unwritable_output(tmp_path):
    locked = tmp_path / "locked"
    locked.mkdir()
    target = locked / "out.png"
    target.write_bytes(b"")
    target.chmod(0o444)
    result = run_cli("render", "lambert", "-o", str(target))
    if result.returncode == 0:  # root ignores file permissions; use a path that cannot exist
        result = run_cli("render", "lambert", "-o", "/proc/version/out.png")
    assert result.returncode == 2 and "cannot write" in result.stderr


def test_render_several_lights_and_ambient(tmp_path):
    """`--light` repeats (with colours) and `--ambient` adds ka L_a: the slide's sum, by hand."""
    from lab.plots import to_srgb8

    out = tmp_path / "scene.png"
    args = [
        "render",
        "phong_illumination",
        "--set",
        "ka=0.2",
        "--set",
        "kd=0.1",
        "--set",
        "ks=0.3",
        "--set",
        "ke=8",
        "--light",
        "30,0,1,0.5,0.25",
        "--light",
        "50,180,0.2,0.4,0.8",
        "--ambient",
        "0.5",
        "--size",
        "65",
        "-o",
        str(out),
    ]
    assert main(args) == 0
    centre = np.asarray(Image.open(out).convert("RGB"))[32, 32].astype(int)
    N = V = np.array([0.0, 0.0, 1.0])  # the centre pixel looks along the normal
    expected = 0.2 * 0.5 * np.ones(3)
    for theta, phi, rgb in ((30, 0, (1, 0.5, 0.25)), (50, 180, (0.2, 0.4, 0.8))):
        t, p = np.radians(theta), np.radians(phi)
        L = np.array([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)])
        R = 2 * (N @ L) * N - L
        expected += np.array(rgb) * (0.1 * (N @ L) + 0.3 * max(R @ V, 0.0) ** 8)
    assert np.abs(centre - to_srgb8(expected).astype(int)).max() <= 1


def test_plot_views_honour_size(tmp_path):
    out = tmp_path / "polar.png"
    assert main(["render", "ggx", "--view", "polar", "--size", "800", "-o", str(out)]) == 0
    with Image.open(out) as image:
        assert image.size[0] == 800


def test_eval_measured_table(tmp_path):
    """`eval measured --table` looks the table up: a tabulated Lambert gives albedo / pi."""
    table = tmp_path / "lambert.binary"
    assert main(["tabulate", "lambert", "--set", "albedo=0.6", "-o", str(table)]) == 0
    pairs = write_pairs(tmp_path / "p.csv", [[30, 0, 40, 100], [10, 50, 70, 300]])
    out = tmp_path / "v.csv"
    args = ["eval", "measured", "--table", str(table), "--in", str(pairs), "--out", str(out)]
    assert main(args) == 0
    np.testing.assert_allclose(read_values(out), np.full((2, 3), 0.6 / np.pi), rtol=1e-5)

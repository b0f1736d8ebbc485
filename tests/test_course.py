"""`brdf-lab course pack/init/check` and the Classroom workflow they write: the grader is
installed from one pinned line, the definitions (solutions included, custom exercises too)
come from a private archive read with a token from an Actions secret, and grading is in
hidden mode, so editing the student's copy of the checks changes nothing."""

from __future__ import annotations

import hashlib
import http.server
import json
import os
import re
import shutil
import subprocess
import sys
import textwrap
import threading
from pathlib import Path

import pytest
from test_authoring import build_from_guide
from wheel_helpers import ROOT

from lab.cli import main
from lab.grading import course, sources

VENV_BIN = Path(sys.executable).parent
COMMIT = "3f2a9c1d" + "0" * 32
TOKEN = "github_pat_test_only"
WHEEL = "brdf_lab-0.1.0-py3-none-any.whl"
# Keys a cheating student would add to their copy of each check, by kind.
TAMPER = {
    "probe": "\nrtol = 1e9\natol = 1e9\n",
    "polar": "\nrtol = 1e9\natol = 1e9\n",
    "sphere": "\nthreshold = 1000.0\nmax_fraction = 1.0\n",
}


class Server:
    """A local web server: files by name, readable only with the token unless `public`."""

    def __init__(self) -> None:
        self.files: dict[str, bytes] = {}
        self.public = False
        self.open = {WHEEL}  # the grader's wheel is public, the definitions are not
        server = self

        class Handler(http.server.BaseHTTPRequestHandler):
            def _answer(self, body: bool) -> None:
                name = self.path.lstrip("/")
                token = self.headers.get("Authorization")
                if name.startswith("asset/") and token == f"Bearer {TOKEN}":
                    # as GitHub sends a private release asset: from a signed storage URL
                    # on another host, which refuses a request that brings a token too
                    self.send_response(302)
                    port = server.httpd.server_port
                    self.send_header("Location", f"http://localhost:{port}/signed/{name[6:]}")
                    self.end_headers()
                    return
                if name.startswith("signed/"):
                    if token:
                        self.send_error(400, "only one auth mechanism allowed")
                        return
                    name = name[7:]
                allowed = server.public or name in server.open or self.path.startswith("/signed/")
                allowed = allowed or self.headers.get("Authorization") == f"Bearer {TOKEN}"
                if name not in server.files or not allowed:
                    self.send_error(404)  # as GitHub answers for a private file
                    return
                self.send_response(200)
                self.send_header("Content-Length", str(len(server.files[name])))
                self.end_headers()
                if body:
                    self.wfile.write(server.files[name])

            def do_GET(self) -> None:  # noqa: N802
                self._answer(True)

            def do_HEAD(self) -> None:  # noqa: N802
                self._answer(False)

            def log_message(self, *args) -> None:
                pass

        self.httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        threading.Thread(target=self.httpd.serve_forever, daemon=True).start()

    def url(self, name: str) -> str:
        return f"http://127.0.0.1:{self.httpd.server_port}/{name}"


@pytest.fixture(scope="module")
def server():
    serving = Server()
    serving.files[WHEEL] = b"a wheel"
    yield serving
    serving.httpd.shutdown()
    serving.httpd.server_close()


@pytest.fixture(scope="module")
def definitions(tmp_path_factory, server) -> Path:
    """A course's private archive: exercises 01 and 02 and the guide's Oren-Nayar one."""
    source = tmp_path_factory.mktemp("definitions")
    for part in ("exercises", "solutions"):
        for name in ("01_lambert", "02_phong"):
            shutil.copytree(ROOT / part / name, source / part / name)
    custom = build_from_guide(source)
    done = subprocess.run(
        [sys.executable, "-m", "lab.cli", "grade", "--make-references", str(custom)],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    archive = source.parent / "definitions.tar.gz"
    assert main(["course", "pack", str(archive), "--from", str(source)]) == 0
    server.files["definitions.tar.gz"] = archive.read_bytes()
    return archive


@pytest.fixture(scope="module")
def repo(definitions, server, tmp_path_factory) -> Path:
    target = tmp_path_factory.mktemp("course") / "template"
    os.environ[sources.TOKEN_SECRET] = TOKEN
    try:
        assert main(["course", "init", str(target), "--exercises", "01", "phong", "11",
                     "--definitions", server.url("definitions.tar.gz"),
                     "--install", server.url(WHEEL)]) == 0  # fmt: skip
    finally:
        del os.environ[sources.TOKEN_SECRET]
    return target


def check(repo: Path, capsys, token: str | None = TOKEN, *more: str) -> tuple[int, str]:
    if token:
        os.environ[sources.TOKEN_SECRET] = token
    try:
        code = main(["course", "check", str(repo), *more])
    finally:
        os.environ.pop(sources.TOKEN_SECRET, None)
    return code, capsys.readouterr().out


def test_init_writes_a_complete_template_with_the_custom_exercise(repo, definitions, capsys):
    code, out = check(repo, capsys)
    assert code == 0 and out.strip().endswith("complete"), out
    names = sorted(p.name for p in (repo / "exercises").iterdir())
    assert names == ["01_lambert", "02_phong", "11_oren_nayar"]
    assert (repo / "exercises" / "11_oren_nayar" / "references" / "values.npz").is_file()
    assert not list(repo.rglob("solutions")) and not list(repo.rglob("mistakes.toml"))
    text = (repo / course.WORKFLOW).read_text()
    settings = course.workflow_settings(text)
    assert settings["DEFINITIONS_SHA256"] == hashlib.sha256(definitions.read_bytes()).hexdigest()
    assert settings["EXERCISES"] == "01_lambert 02_phong 11_oren_nayar"
    assert settings["BRDF_LAB_INSTALL"].startswith("brdf-lab @ http://127.0.0.1:")
    assert "DEFINITIONS_TOKEN: ${{ secrets.BRDF_LAB_DEFINITIONS_TOKEN }}" in text
    readme = (repo / "README.md").read_text()
    assert settings["BRDF_LAB_INSTALL"] in readme  # students install the same grader
    assert "definitions" not in readme.lower() and settings["DEFINITIONS_URL"] not in readme


def actionlint() -> str | None:
    found = shutil.which("actionlint") or shutil.which("actionlint", path=str(VENV_BIN))
    return found


def test_the_workflow_passes_actionlint(repo):
    tool = actionlint()
    if tool is None:
        pytest.skip("actionlint is not installed (python3 -m lab test installs it with Go)")
    done = subprocess.run([tool, str(repo / course.WORKFLOW)], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    # ... and actionlint does find faults: a misspelt expression in the same file fails.
    broken = repo.parent / "broken.yml"
    broken.write_text((repo / course.WORKFLOW).read_text().replace("secrets.", "secret."))
    assert subprocess.run([tool, str(broken)], capture_output=True).returncode == 1


def test_the_install_line_is_the_same_everywhere():
    line = sources.default_install()
    assert line.startswith("brdf-lab @ git+https://github.com/") and line.endswith("@v0.1.0")
    assert sources.install_line("0.1.0") == "brdf-lab==0.1.0"
    assert sources.install_line("git+https://x.org/a/b@v1") == "brdf-lab @ git+https://x.org/a/b@v1"
    readme = (ROOT / "README.md").read_text()
    assert f'pip install "{line}"' in readme
    assert sources.placeholder("https://api.github.com/repos/my-org/defs/releases/assets/7") == ""
    assert sources.placeholder("git+https://github.com/OWNER/brdf-lab@vX.Y.Z") == "OWNER"
    with pytest.raises(Exception, match="pin a tag or commit"):
        sources.install_line("git+https://github.com/brdf-lab/brdf-lab")


def test_check_fails_without_the_token_or_with_public_definitions(repo, server, capsys):
    code, out = check(repo, capsys, token=None)
    assert code == 1 and "set BRDF_LAB_DEFINITIONS_TOKEN" in out
    server.public = True
    try:
        code, out = check(repo, capsys)
    finally:
        server.public = False
    assert code == 1 and "anyone can download" in out and "solutions included" in out
    code, out = check(repo, capsys, None, "--offline")
    assert code == 0 and "note: not checked (--offline)" in out


@pytest.mark.parametrize(
    "edit,words",
    [
        (("BRDF_LAB_INSTALL: \"", 'BRDF_LAB_INSTALL: "brdf-lab @ git+https://github.com/OWNER/x@vX.Y.Z'),
         "has a placeholder"),
        ((WHEEL, "brdf_lab-9.9.9-py3-none-any.whl"), "cannot be downloaded"),
        (("definitions.tar.gz", "missing.tar.gz"), "cannot download the definitions"),
        ((r"[0-9a-f]{64}", "0" * 64), "is not the archive DEFINITIONS_SHA256 pins"),
        (("secrets.BRDF_LAB_DEFINITIONS_TOKEN", "env.X"), "reads no token"),
    ],
)  # fmt: skip
def test_check_fails_on_placeholder_or_unreachable_sources(repo, tmp_path, capsys, edit, words):
    broken = tmp_path / "broken"
    shutil.copytree(repo, broken)
    workflow = broken / course.WORKFLOW
    old, new = edit
    text = workflow.read_text()
    workflow.write_text(
        re.sub(old, new, text, count=1) if "{" in old else text.replace(old, new, 1)
    )
    code, out = check(broken, capsys)
    assert code == 1 and words in out, out


def test_check_names_what_is_missing_or_leaked(repo, tmp_path, capsys):
    broken = tmp_path / "broken"
    shutil.copytree(repo, broken)
    (broken / "exercises" / "02_phong" / "README.md").unlink()
    shutil.copy(
        ROOT / "solutions" / "01_lambert" / "lambert.glsl", broken / "exercises" / "01_lambert"
    )
    guide = (ROOT / "docs" / "authoring.md").read_text()
    solution = re.search(r"```glsl file=solutions/\S+\n(.*?)^```", guide, re.S | re.M)
    (broken / "notes.glsl").write_text(solution.group(1))  # the custom exercise's solution
    (broken / "solutions").mkdir()
    readme = broken / "README.md"
    readme.write_text(readme.read_text() + "\nDownload the course definitions to grade at home.\n")
    code, out = check(broken, capsys)
    assert code == 1
    assert "exercises/02_phong/README.md is missing" in out
    assert "exercises/01_lambert/lambert.glsl is a solution" in out
    assert "notes.glsl is a solution" in out  # the custom exercise's, from the definitions
    assert "solutions/ is in the repository" in out
    assert "README.md tells students where the definitions" in out


def test_init_needs_definitions_and_refuses_an_archive_without_them(tmp_path, capsys):
    assert main(["course", "init", str(tmp_path / "t")]) == 2
    assert "course pack" in capsys.readouterr().err
    fake = tmp_path / "fake.tar.gz"
    shutil.make_archive(str(tmp_path / "fake"), "gztar", ROOT, "exercises")
    assert main(["course", "init", str(tmp_path / "t"), "--definitions", str(fake)]) == 2
    assert "has no exercises/ in its top folder exercises/" in capsys.readouterr().err
    shutil.copytree(ROOT / "exercises" / "01_lambert", tmp_path / "defs" / "exercises" / "01")
    shutil.make_archive(str(tmp_path / "fake"), "gztar", tmp_path, "defs")
    assert main(["course", "init", str(tmp_path / "t"), "--definitions", str(fake)]) == 2
    assert "lacks solutions/01/lambert.glsl" in capsys.readouterr().err


def grade_step(workflow: Path) -> str:
    """The shell script of the workflow's grading step, as GitHub runs it."""
    text = workflow.read_text()
    block = text.split("- name: Grade the exercises", 1)[1].split("run: |\n", 1)[1]
    lines = []
    for line in block.splitlines():
        if line.strip() and not line.startswith(" " * 10):
            break
        lines.append(line)
    return textwrap.dedent("\n".join(lines))


def run_workflow(repo: Path, tmp: Path, archive: Path, token: str = TOKEN):
    """Run the grading step in `repo` as GitHub Actions would."""
    settings = course.workflow_settings((repo / course.WORKFLOW).read_text())
    runner_temp = tmp / "runner"
    runner_temp.mkdir(exist_ok=True)
    env = {
        **{k: v for k, v in os.environ.items() if k != "PYTHONPATH"},
        **settings,
        "DEFINITIONS_URL": archive.as_uri(),  # the private copy: the same bytes, offline
        "DEFINITIONS_TOKEN": token,
        "GITHUB_SHA": COMMIT,
        "RUNNER_TEMP": str(runner_temp),
        "PATH": f"{VENV_BIN}{os.pathsep}{os.environ['PATH']}",
    }
    (repo / "classroom-result.json").unlink(missing_ok=True)
    return subprocess.run(
        ["bash", "-e", "-c", grade_step(repo / course.WORKFLOW)],
        cwd=repo, env=env, capture_output=True, text=True, timeout=600,
    )  # fmt: skip


def result_of(done, repo: Path) -> dict[str, float]:
    assert done.returncode == 0, done.stderr[-3000:]
    assert f"seed {int(COMMIT[:7], 16)}" in done.stdout
    result = json.loads((repo / "classroom-result.json").read_text())
    return {t["name"]: t["score"] for t in result["tests"]}


def test_a_changed_archive_fails_the_checksum_and_no_token_stops(repo, tmp_path):
    student = tmp_path / "student"
    shutil.copytree(repo, student)
    other = tmp_path / "other.tar.gz"
    shutil.make_archive(str(tmp_path / "other"), "gztar", ROOT, "exercises")
    done = run_workflow(student, tmp_path, other)
    assert done.returncode != 0 and "FAILED" in done.stdout + done.stderr
    assert not (student / "classroom-result.json").exists()
    done = run_workflow(student, tmp_path, other, token="")
    assert (
        done.returncode != 0 and "the secret BRDF_LAB_DEFINITIONS_TOKEN is not set" in done.stdout
    )


def test_editing_the_students_copy_does_not_change_the_grade(repo, definitions, tmp_path):
    student = tmp_path / "student"
    shutil.copytree(repo, student)
    shutil.copy(ROOT / "solutions" / "02_phong" / "phong.glsl", student / "exercises" / "02_phong")
    honest = result_of(run_workflow(student, tmp_path, definitions), student)
    phong = [n for n in honest if "02_phong" in n]
    lambert = [n for n in honest if "01_lambert" in n]
    oren = [n for n in honest if "11_oren_nayar" in n]
    assert phong and lambert and oren
    assert all(honest[n] > 0 for n in phong)  # the solved exercise passes
    assert all(honest[n] == 0 for n in lambert)  # the stub does not

    # The cheat: tolerances widened, and a "solution" for hidden mode that is the stub.
    toml = student / "exercises" / "01_lambert" / "exercise.toml"
    tampered = re.sub(
        r'kind = "(\w+)"', lambda m: m.group(0) + TAMPER[m.group(1)], toml.read_text()
    )
    toml.write_text(tampered)
    fake = student / "solutions" / "01_lambert"
    fake.mkdir(parents=True)
    shutil.copy(student / "exercises" / "01_lambert" / "lambert.glsl", fake)
    # ... which would pay off if the student's copy were used, in either mode:
    for mode in ([], ["--seed", "5"]):
        cheat = subprocess.run(
            [str(VENV_BIN / "brdf-lab"), "grade", str(student / "exercises" / "01_lambert"), *mode],
            capture_output=True,
            text=True,
        )
        assert cheat.returncode == 0, cheat.stdout + cheat.stderr  # full marks with the stub
    shutil.rmtree(student / "solutions")
    assert result_of(run_workflow(student, tmp_path, definitions), student) == honest


def test_a_release_asset_downloads_through_its_redirect_without_the_token(definitions, server):
    """The token goes to the asset's address only, not to the storage host it redirects to."""
    url = server.url("asset/definitions.tar.gz")
    assert sources.fetch(url, TOKEN)[1] == definitions.read_bytes()
    with pytest.raises(Exception, match="cannot download the definitions"):
        sources.fetch(url)

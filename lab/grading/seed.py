"""Seeds for hidden mode where students cannot see the run: one per submission.

Gradescope: the submission's id from /autograder/submission_metadata.json (else a hash
of the submitted files). GitHub Classroom: the pushed commit. The seed is printed and
written into the results with what a student can run at home: practice mode against the
committed references (hidden mode renders the solutions live, which only the instructor
has: they can rerun the exact grade with `--seed N`).

    python -m lab.grading.seed gradescope METADATA.json SUBMISSION_DIR
    python -m lab.grading.seed commit SHA
    python -m lab.grading.seed annotate RESULTS.json SEED EXERCISES...
    python -m lab.grading.seed reproduce SEED EXERCISES...
"""

from __future__ import annotations

import hashlib
import json
import sys
from pathlib import Path

LIMIT = 2**31 - 1  # numpy's generators take any int; a short number is easier to type


def from_files(folder: Path) -> int:
    """A seed from the submitted files' names and bytes (symlinks are not followed)."""
    digest = hashlib.sha256()
    for path in sorted(p for p in folder.rglob("*") if p.is_file() and not p.is_symlink()):
        digest.update(path.relative_to(folder).as_posix().encode() + b"\0" + path.read_bytes())
    return int(digest.hexdigest()[:8], 16) % LIMIT


def from_gradescope(metadata: Path, submission: Path) -> int:
    """The submission id Gradescope gives every submission, else a hash of the files."""
    try:
        return int(json.loads(metadata.read_text(encoding="utf-8"))["id"]) % LIMIT
    except (OSError, ValueError, KeyError, TypeError):
        return from_files(submission)


def from_commit(sha: str) -> int:
    """The first 7 hex digits of a commit SHA, as GitHub shows it, read as a number."""
    text = sha.strip().lower()
    if len(text) < 7 or any(c not in "0123456789abcdef" for c in text):
        raise ValueError(f"{sha!r} is not a commit SHA (7 to 40 hex digits)")
    return int(text[:7], 16)


def reproduce_line(seed: int, exercises: list[str]) -> str:
    """The seed, what a student can run at home (practice mode: `--seed` needs solutions/,
    which students do not have), and that the instructor can rerun the exact grade."""
    names = " ".join(f"exercises/{Path(e).name}" for e in exercises) or "exercises/NN"
    return (
        f"Graded in hidden mode (random parameters and lights) with seed {seed}. "
        f"Check your files at home in practice mode, against the committed references: "
        f"brdf-lab grade {names} --from exercises (--from names the folder that holds your "
        "files, as NN_topic/FILE or FILE). The hidden grade itself renders the solutions, "
        f"which only your instructor has: they can rerun it exactly with --seed {seed}."
    )


def annotate(results: Path, seed: int, exercises: list[str]) -> None:
    """Put the seed line at the top of a Gradescope results.json's output."""
    data = json.loads(results.read_text(encoding="utf-8"))
    line = reproduce_line(seed, exercises)
    if line not in data.get("output", ""):
        data["output"] = line + ("\n\n" + data["output"] if data.get("output") else "")
    results.write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")


def main(argv: list[str]) -> int:
    usage = __doc__.split("\n\n")[-1]
    try:
        if argv[:1] == ["gradescope"] and len(argv) == 3:
            print(from_gradescope(Path(argv[1]), Path(argv[2])))
        elif argv[:1] == ["commit"] and len(argv) == 2:
            print(from_commit(argv[1]))
        elif argv[:1] == ["annotate"] and len(argv) >= 3:
            annotate(Path(argv[1]), int(argv[2]), argv[3:])
        elif argv[:1] == ["reproduce"] and len(argv) >= 2:
            print(reproduce_line(int(argv[1]), argv[2:]))
        else:
            print(f"usage:\n{usage}", file=sys.stderr)
            return 2
    except (OSError, ValueError) as err:
        print(f"brdf-lab seed: error: {err}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

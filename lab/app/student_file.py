"""An exercise's student file as `watch` shows it: found beside its exercise.toml and built
as the grader builds it (watch.py's sphere view, watch_sampler.py's sampler checks)."""

from __future__ import annotations

from pathlib import Path

from lab.models import ModelError


class StudentFile:
    """An exercise's student file as the grader sees it; a subclass says what it shows."""

    def __init__(self, path: Path):
        from lab.grading.exercise import load_exercise

        self.exercise = load_exercise(path.parent)

    def shows(self) -> bool:
        """Whether this exercise has what the view shows."""
        raise NotImplementedError

    @classmethod
    def find(cls, path: Path):
        """The view for `path` if it is the student file of an exercise the view shows."""
        from lab.grading.exercise import ExerciseError

        if not (path.parent / "exercise.toml").is_file():
            return None
        try:
            view = cls(path)
        except (ExerciseError, StopIteration, OSError):
            return None
        return view if view.exercise.student_file == path.name and view.shows() else None

    def load(self, path: Path):
        """The submission as the grader builds it (raises ModelError on a bad file)."""
        from lab.grading.exercise import SubmissionError, build_model, read_submission

        try:
            return build_model(self.exercise, path, read_submission(path))
        except SubmissionError as err:
            raise ModelError(str(err)) from None

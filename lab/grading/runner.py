"""Worker processes that render submissions, watched by a supervisor with a hard time limit.

Software rasterizers have no watchdog: a student's endless loop blocks the render call
for ever. So every render happens in a child process; the supervisor (this process,
which never creates a GL context) kills a child whose check runs past its deadline,
scores that check 0 and hands the remaining checks to a fresh child. Children are
long-lived and grade task after task, so a class of submissions pays for one context
per worker, not one per file.
"""

from __future__ import annotations

import multiprocessing
import time
import traceback
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from multiprocessing.connection import Connection, wait
from pathlib import Path

from lab.grading.checks import CheckResult, Grader
from lab.grading.exercise import Exercise, load_exercise
from lab.grading.explain import Explainer

RECYCLE_AFTER = 60  # tasks per worker: drops the programs compiled for old submissions
MAX_TIMEOUTS = 2  # per task: after this many, the remaining checks are not run


@dataclass
class Task:
    """One submission file graded against one exercise."""

    exercise: Exercise
    submission: Path
    seed: int | None = None
    key: str = ""
    root: Path | None = None  # the submission's top folder: no links below it are followed
    results: dict[str, CheckResult] = field(default_factory=dict)
    timeouts: int = 0
    started: float = 0.0
    seconds: float = 0.0

    def checks(self) -> list[CheckResult]:
        """Results in the exercise's order (every check has one once the task is done)."""
        return [self.results[c.name] for c in self.exercise.checks if c.name in self.results]

    @property
    def score(self) -> float:
        return sum(r.points for r in self.results.values())

    @property
    def max_score(self) -> float:
        return self.exercise.max_points

    @property
    def passed(self) -> bool:
        return all(r.passed for r in self.checks()) and len(self.results) == len(
            self.exercise.checks
        )

    def pending(self) -> list:
        return [c for c in self.exercise.checks if c.name not in self.results]


def _serve(conn: Connection) -> None:
    """Child: grade tasks sent over `conn`, streaming one message per check."""
    grader = Grader()
    grader.explainer = Explainer(grader)
    while True:
        try:
            job = conn.recv()
        except (EOFError, KeyboardInterrupt):
            return
        if job is None:
            return
        key, folder, submission, root, seed, skip = job
        try:
            exercise = load_exercise(folder)
            root = Path(root) if root else None
            for result in grader.run(exercise, Path(submission), seed, frozenset(skip), root):
                conn.send(("check", key, result))
            conn.send(("done", key, None))
        except Exception as err:  # the grader must report, never die: say what broke
            detail = traceback.format_exception_only(type(err), err)[-1].strip()
            conn.send(("crash", key, f"internal grader error: {detail}"))


def start_method() -> str:
    """fork (fast: the imports are inherited) unless this process already holds a GL context.

    A forked child would inherit the driver's state without its threads, so then a fork
    server, started clean, makes the workers instead.
    """
    from lab import gl

    return "forkserver" if gl.has_offscreen_context() else "fork"


class _Worker:
    def __init__(self, context) -> None:
        self.conn, child = context.Pipe()
        self.process = context.Process(target=_serve, args=(child,), daemon=True)
        self.process.start()
        child.close()
        self.task: Task | None = None
        self.deadline = 0.0
        self.done = 0

    def send(self, task: Task, timeout: float) -> None:
        self.task = task
        self.deadline = time.monotonic() + timeout
        skip = sorted(task.results)
        root = str(task.root) if task.root else ""
        exercise = str(task.exercise.folder)
        self.conn.send((task.key, exercise, str(task.submission), root, task.seed, skip))

    def stop(self, kill: bool = False) -> None:
        if kill:
            self.process.kill()
        else:
            try:
                self.conn.send(None)
            except OSError:
                self.process.kill()
        self.process.join(timeout=5)
        if self.process.is_alive():
            self.process.kill()
            self.process.join()
        self.conn.close()


class Pool:
    """Grades tasks on `workers` child processes; each check gets `timeout` seconds."""

    def __init__(self, workers: int = 1, timeout: float = 10.0) -> None:
        self.size = max(1, workers)
        self.timeout = timeout
        self.context = multiprocessing.get_context(start_method())
        if self.context.get_start_method() == "forkserver":
            self.context.set_forkserver_preload(["lab.grading.checks"])
        self.workers: list[_Worker | None] = [_Worker(self.context) for _ in range(self.size)]

    def close(self) -> None:
        for worker in self.workers:
            if worker is not None:
                worker.stop()
        self.workers = [None] * self.size

    def __enter__(self) -> Pool:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def run(self, tasks: list[Task], on_done: Callable[[Task], None] | None = None) -> list[Task]:
        """Grade every task; returns them with all their checks' results filled in."""
        queue = deque(tasks)
        for number, task in enumerate(tasks):
            task.key = task.key or str(number)
        while queue or any(w is not None and w.task is not None for w in self.workers):
            for slot, worker in enumerate(self.workers):
                if queue and (worker is None or worker.task is None):
                    if worker is None:
                        worker = self.workers[slot] = _Worker(self.context)
                    task = queue.popleft()
                    task.started = task.started or time.monotonic()
                    worker.send(task, self.timeout)
            busy = [w for w in self.workers if w is not None and w.task is not None]
            now = time.monotonic()
            ready = wait(
                [w.conn for w in busy], timeout=max(0.0, min(w.deadline for w in busy) - now)
            )
            for worker in busy:
                if worker.conn in ready:
                    self._receive(worker, queue, on_done)
                elif time.monotonic() > worker.deadline:
                    self._abandon(
                        worker,
                        queue,
                        on_done,
                        f"did not finish within {self.timeout:g} s and was stopped "
                        "(an endless or very long loop, or code too large to compile?)",
                    )
        return tasks

    def _finish(self, task: Task, on_done) -> None:
        task.seconds = time.monotonic() - task.started
        if on_done:
            on_done(task)

    def _receive(self, worker: _Worker, queue: deque, on_done) -> None:
        task = worker.task
        try:
            kind, _, payload = worker.conn.recv()
        except (EOFError, OSError):
            self._abandon(worker, queue, on_done, "crashed the renderer")
            return
        if kind == "check":
            task.results[payload.name] = payload
            worker.deadline = time.monotonic() + self.timeout
            return
        if kind == "crash":
            for check in task.pending():
                task.results[check.name] = CheckResult(
                    check.name, check.kind, check.points, status="error", message=payload
                )
        worker.task = None
        worker.done += 1
        self._finish(task, on_done)
        if worker.done >= RECYCLE_AFTER:
            worker.stop()
            self.workers[self.workers.index(worker)] = None

    def _abandon(self, worker: _Worker, queue: deque, on_done, why: str) -> None:
        """Kill a stuck or crashed worker; score its check 0 and requeue the rest."""
        task = worker.task
        worker.stop(kill=True)
        self.workers[self.workers.index(worker)] = None
        pending = task.pending()
        if pending:
            check = pending[0]
            task.results[check.name] = CheckResult(
                check.name, check.kind, check.points, status="error", message=f"the shader {why}"
            )
        task.timeouts += 1
        if task.timeouts >= MAX_TIMEOUTS:
            for check in task.pending():
                task.results[check.name] = CheckResult(
                    check.name,
                    check.kind,
                    check.points,
                    status="error",
                    message="not run: the shader was stopped on earlier checks",
                )
        if task.pending():
            queue.appendleft(task)
        else:
            self._finish(task, on_done)

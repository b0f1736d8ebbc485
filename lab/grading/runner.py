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
import os
import signal
import sys
import time
import traceback
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from multiprocessing.connection import Connection, wait
from pathlib import Path
from typing import TYPE_CHECKING

from lab.grading.result import CheckResult

if TYPE_CHECKING:
    from lab.grading.exercise import Exercise

# The supervisor imports no numpy, OpenGL or grading code here: a worker forked first
# loads them itself while the supervisor reads the exercises (two cores, both busy).

RECYCLE_AFTER = 60  # tasks per worker: drops the programs compiled for old submissions
MAX_TIMEOUTS = 2  # per task: after this many, the remaining checks are not run
MEMORY_LIMIT = 2 << 30  # bytes a worker may map beyond its own start (the GL context, Python)
MAX_CHECKS = 16  # checks of one task the CPU-time cap allows for


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
    text: str = ""  # the file's text as the worker read and graded it

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


def _address_space() -> int:
    """Bytes of address space this process maps now (Linux), or 0 where unknown."""
    try:
        with open("/proc/self/statm", encoding="ascii") as handle:
            return int(handle.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return 0


def _limit(memory: int, cpu_seconds: float) -> None:
    """Cap this worker: `memory` bytes beyond what it maps now (the driver and Python need
    their share first) and `cpu_seconds` more of CPU time (SIGXCPU ends it past that)."""
    try:
        import resource
    except ImportError:  # pragma: no cover - Windows: the supervisor's time limit remains
        return
    if memory:
        cap = _address_space() + memory  # the soft limit: the preprocessor sets its own
        resource.setrlimit(resource.RLIMIT_AS, (cap, resource.getrlimit(resource.RLIMIT_AS)[1]))
    if cpu_seconds:
        usage = resource.getrusage(resource.RUSAGE_SELF)
        used = usage.ru_utime + usage.ru_stime
        hard = resource.getrlimit(resource.RLIMIT_CPU)[1]
        soft = int(used + cpu_seconds) + 1
        if hard != resource.RLIM_INFINITY:
            soft = min(soft, hard)
        resource.setrlimit(resource.RLIMIT_CPU, (soft, hard))


def _prepare(job: tuple):
    """Read the job's exercise and file, and preprocess it (no GL: runs beside the context)."""
    from lab.grading.checks import prepare
    from lab.grading.exercise import load_exercise

    _, folder, submission, root, _, _, _ = job
    exercise = load_exercise(folder)
    return exercise, prepare(exercise, Path(submission), Path(root) if root else None)


def _serve(conn: Connection, memory: int = 0, cpu_seconds: float = 0.0) -> None:
    """Child: grade tasks sent over `conn`, streaming one message per check.

    The GL context is made first; then the worker's memory is capped, and before each task
    its CPU time, so a compile bomb or a huge array ends this process, not the machine.
    A first job already waiting is read and preprocessed (glslang) while the context is made.
    """
    from concurrent.futures import ThreadPoolExecutor

    from lab.grading import kinds
    from lab.grading.checks import Grader
    from lab.grading.exercise import load_exercise
    from lab.grading.explain import Explainer

    early, pending = None, ()  # () : no job read ahead
    try:
        if conn.poll(0):
            pending = conn.recv()
    except (EOFError, KeyboardInterrupt):
        return
    if pending:
        kinds.use_packages(pending[6])
        if cpu_seconds:
            _limit(0, cpu_seconds)
        executor = ThreadPoolExecutor(max_workers=1)
        early = executor.submit(_prepare, pending)
        executor.shutdown(wait=False)
    grader = Grader()
    grader.explainer = Explainer(grader)
    try:
        grader.renderer  # noqa: B018 - the context, before the cap
    except Exception as err:  # noqa: BLE001 - no GL: every task reports it
        detail = traceback.format_exception_only(type(err), err)[-1].strip()
        grader = None
    if memory:
        _limit(memory, 0.0)
    while True:
        if pending == ():
            try:
                job = conn.recv()
            except (EOFError, KeyboardInterrupt):
                return
        else:
            job, pending = pending, ()
        if job is None:
            return
        key, folder, submission, root, seed, skip, packages = job
        kinds.use_packages(packages)  # check kinds registered in the supervisor (plug-ins)
        if grader is None:
            conn.send(("crash", key, f"internal grader error: no OpenGL context ({detail})"))
            early = None
            continue
        try:
            if early is not None:
                exercise, prepared = early.result()
            else:
                if cpu_seconds:
                    _limit(0, cpu_seconds)
                exercise, prepared = load_exercise(folder), None
            early = None
            root = Path(root) if root else None
            results = grader.run(exercise, Path(submission), seed, frozenset(skip), root, prepared)
            for result in results:
                conn.send(("check", key, result))
            if grader.reading is not None:  # the text graded, for the similarity report
                conn.send(("read", key, grader.reading.code))
            conn.send(("done", key, None))
        except MemoryError:
            conn.send(("crash", key, f"the shader needs more than the {memory >> 20} MB allowed"))
        except Exception as err:  # the grader must report, never die: say what broke
            early = None
            detail = traceback.format_exception_only(type(err), err)[-1].strip()
            conn.send(("crash", key, f"internal grader error: {detail}"))


def start_method() -> str:
    """fork (fast: the imports are inherited) unless this process already holds a GL context.

    A forked child would inherit the driver's state without its threads, so then a fork
    server, started clean, makes the workers instead.
    """
    gl = sys.modules.get("lab.gl")  # not imported: no context here (and no import cost)
    return "forkserver" if gl is not None and gl.has_offscreen_context() else "fork"


class _Worker:
    def __init__(self, context, memory: int = 0, cpu_seconds: float = 0.0) -> None:
        self.conn, child = context.Pipe()
        self.process = context.Process(
            target=_serve, args=(child, memory, cpu_seconds), daemon=True
        )
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
        from lab.grading import kinds

        job = (task.key, exercise, str(task.submission), root, task.seed, skip, kinds.packages())
        self.conn.send(job)

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
    """Grades tasks on `workers` child processes; each check gets `timeout` seconds of wall
    time, each task `timeout` x checks of CPU time, each worker `memory` bytes (0: no cap)."""

    def __init__(self, workers: int = 1, timeout: float = 10.0, memory: int = MEMORY_LIMIT) -> None:
        self.size = max(1, workers)
        self.timeout = timeout
        self.memory = memory
        self.context = multiprocessing.get_context(start_method())
        if self.context.get_start_method() == "forkserver":
            self.context.set_forkserver_preload(["lab.grading.checks"])
        self.workers: list[_Worker | None] = [self._start() for _ in range(self.size)]

    def _start(self) -> _Worker:
        # CPU time per task: every check's time limit, plus the compiles and the context
        cpu = self.timeout * (MAX_CHECKS + 2)
        return _Worker(self.context, self.memory, cpu)

    def close(self) -> None:
        for worker in self.workers:
            if worker is not None:
                worker.stop()
        self.workers = [None] * self.size

    def __enter__(self) -> Pool:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def run(
        self,
        tasks: list[Task],
        on_done: Callable[[Task], None] | None = None,
        meanwhile: Callable[[], object] | None = None,
    ) -> list[Task]:
        """Grade every task; returns them with all their checks' results filled in.

        `meanwhile` runs once the first tasks are sent (this process would only wait)."""
        queue = deque(tasks)
        for number, task in enumerate(tasks):
            task.key = task.key or str(number)
        while queue or any(w is not None and w.task is not None for w in self.workers):
            for slot, worker in enumerate(self.workers):
                if queue and (worker is None or worker.task is None):
                    if worker is None:
                        worker = self.workers[slot] = self._start()
                    task = queue.popleft()
                    task.started = task.started or time.monotonic()
                    worker.send(task, self.timeout)
            if meanwhile is not None:
                meanwhile, later = None, meanwhile
                later()
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
                        "(an endless or very long loop, a huge array, or code too large "
                        "to compile?)",
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
            self._abandon(worker, queue, on_done, self._why_ended(worker))
            return
        if kind == "read":
            task.text = payload
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

    def _why_ended(self, worker: _Worker) -> str:
        """Why a worker died, from its exit status, in words for the student."""
        worker.process.join(timeout=5)
        code = worker.process.exitcode
        if code == -signal.SIGXCPU:
            return (
                "used up its CPU time and was stopped (an endless loop, or code too large "
                "to compile?)"
            )
        limit = f"{self.memory >> 20} MB" if self.memory else "the machine's memory"
        return (
            f"crashed the renderer (exit status {code}), most likely by running out of "
            f"memory ({limit} allowed): a huge array, or macros that expand too far?"
        )

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

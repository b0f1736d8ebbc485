"""The outcome of one check: what every report (terminal, HTML, JSON, CSV) shows."""

from __future__ import annotations

from dataclasses import dataclass, field

from lab.grading.spec import Check


@dataclass
class CheckResult:
    """The outcome of one check, with everything the reports show."""

    name: str
    kind: str
    max_points: float
    points: float = 0.0
    status: str = "failed"  # passed | failed | error
    message: str = ""
    rows: list[tuple] = field(
        default_factory=list
    )  # probe: theta_i, phi_i, theta_o, phi_o, exp, got
    images: dict[str, bytes] = field(default_factory=dict)  # reference, student, diff (PNG)
    flip: float | None = None
    curve: dict | None = None  # polar: theta_o, expected, got (luminance)
    errors: list[str] = field(default_factory=list)  # compile errors, file:line: message
    diagnosis: str = ""  # "Likely: ..." (also the end of the message), or ""
    failing: list[int] = field(default_factory=list)  # polar: indices of failing points
    setting: dict | None = None  # hidden mode: the seed and parameter values used
    threshold: float = 0.0  # sphere: the per-pixel threshold (1/255) of the difference image
    loop_line: int = 0  # the student's line of a loop the guard stopped (0: none did)
    warnings: list[str] = field(default_factory=list)  # not scored: e.g. the web lab rejects
    extra: dict = field(default_factory=dict)  # what a kind adds for its own report section

    @property
    def passed(self) -> bool:
        return self.status == "passed"


def failed(check: Check, message: str, status: str = "failed", **extra) -> CheckResult:
    return CheckResult(
        check.name, check.kind, check.points, status=status, message=message, **extra
    )


def passed(check: Check, message: str, **extra) -> CheckResult:
    return CheckResult(
        check.name, check.kind, check.points, check.points, "passed", message, **extra
    )

"""Grading results in every format: terminal, HTML, Gradescope, GitHub Classroom, CSV."""

from __future__ import annotations

import base64
import csv
import html
import json
import os
import sys
from pathlib import Path

from lab.grading.kinds import kind_of
from lab.grading.result import CheckResult
from lab.grading.runner import Task

ROW_HEADER = ("theta_i", "phi_i", "theta_o", "phi_o", "expected", "got")


def points(value: float) -> str:
    return f"{value:g}"


def check_text(result: CheckResult) -> str:
    """The message of a check with its failing rows and compile errors, as plain text."""
    lines = [result.message, *(f"warning: {w}" for w in result.warnings)]
    if result.setting:
        lines.append(_setting_text(result.setting))
    if result.rows and not result.passed:
        lines.append("  ".join(ROW_HEADER))
        lines += ["  ".join(str(v) for v in row) for row in result.rows]
    if len(result.errors) > 1:
        lines += result.errors[1:]
    return "\n".join(lines)


def test_name(task: Task, result: CheckResult) -> str:
    return f"{task.exercise.name}.{result.name}"


def terminal_lines(tasks: list[Task]) -> list[list[tuple[str, str]]]:
    """The terminal report as lines of (text, style) spans: one line per check with its
    points, then the total."""
    lines: list[list[tuple[str, str]]] = []
    for task in tasks:
        lines.append(
            [
                (task.exercise.name, "bold"),
                (f" {task.exercise.title}  ", ""),
                (str(task.submission), "dim"),
            ]
        )
        for result in task.checks():
            mark = (
                ("PASS", "green")
                if result.passed
                else (("FAIL", "red") if result.status == "failed" else ("ERROR", "magenta"))
            )
            score = f"{points(result.points):>4}/{points(result.max_points):<4}"
            lines.append([("  ", ""), mark, (f" {result.name:28s} {score} {result.message}", "")])
            for warning in result.warnings:
                lines.append([("       ", ""), ("warning:", "yellow"), (" " + warning, "")])
            if result.setting:
                lines.append([("       ", ""), (_setting_text(result.setting), "dim")])
            for row in result.rows[:3] if not result.passed else []:
                cells = ", ".join(f"{h}={v}" for h, v in zip(ROW_HEADER, row, strict=True))
                lines.append([("       " + cells, "")])
            for error in result.errors[1:4]:
                lines.append([("       " + error, "")])
    score = sum(t.score for t in tasks)
    total = sum(t.max_score for t in tasks)
    lines.append([(f"total {points(score)}/{points(total)}", "bold")])
    return lines


def terminal(tasks: list[Task], console=None) -> None:
    """Print the report: in colour on a terminal (rich), as plain lines elsewhere (logs,
    CI, pipes), where rich would print the same text and costs a tenth of a second to load."""
    lines = terminal_lines(tasks)
    if console is None and not sys.stdout.isatty():
        for spans in lines:
            print("".join(text for text, _ in spans))
        return
    from rich.console import Console
    from rich.markup import escape

    console = console or Console(highlight=False, soft_wrap=True)
    for spans in lines:
        console.print(
            "".join(
                f"[{style}]{escape(text)}[/]" if style else escape(text) for text, style in spans
            ),
            emoji=False,
        )


def gradescope(tasks: list[Task], seconds: float) -> dict:
    """results.json as the Gradescope autograder specification describes it."""
    tests = []
    for task in tasks:
        for result in task.checks():
            tests.append(
                {
                    "name": test_name(task, result),
                    "score": result.points,
                    "max_score": result.max_points,
                    "status": "passed" if result.passed else "failed",
                    "output": check_text(result),
                    "visibility": "visible",
                }
            )
    passed = sum(1 for t in tests if t["status"] == "passed")
    return {
        "score": sum(t.score for t in tasks),
        "execution_time": round(seconds, 3),
        "output": f"{passed} of {len(tests)} checks passed",
        "visibility": "visible",
        "stdout_visibility": "visible",
        "tests": tests,
    }


def classroom(tasks: list[Task]) -> dict:
    """The result that classroom-resources/autograding-grading-reporter reads."""
    tests = []
    for task in tasks:
        for result in task.checks():
            tests.append(
                {
                    "name": test_name(task, result),
                    "status": "pass"
                    if result.passed
                    else ("error" if result.status == "error" else "fail"),
                    "score": result.points,
                    "max_score": result.max_points,
                    "message": check_text(result),
                    "filename": str(task.submission),
                    "execution_time": f"{task.seconds:.2f}s",
                }
            )
    status = "pass" if all(t["status"] == "pass" for t in tests) else "fail"
    return {
        "version": 1,
        "status": status,
        "max_score": sum(t.max_score for t in tasks),
        "tests": tests,
    }


def write_github_output(result: dict, name: str = "result") -> bool:
    """In GitHub Actions, append NAME=<base64 JSON> to $GITHUB_OUTPUT for the reporter."""
    target = os.environ.get("GITHUB_OUTPUT")
    if not os.environ.get("GITHUB_ACTIONS") or not target:
        return False
    encoded = base64.b64encode(json.dumps(result).encode()).decode()
    with open(target, "a", encoding="utf-8") as handle:
        handle.write(f"{name}={encoded}\n")
    return True


def write_json(data: dict, path: Path) -> None:
    path.write_text(json.dumps(data, indent=2), encoding="utf-8")


# -- HTML -------------------------------------------------------------------------------------
STYLE = """
body { font-family: system-ui, sans-serif; margin: 1.5em; color: #222; max-width: 70em; }
h2 { border-bottom: 1px solid #ccc; margin-top: 2em; }
.check { margin: 1em 0; padding: 0.5em 1em; border-left: 6px solid #c33; background: #fafafa; }
.check p, .check pre { overflow-wrap: anywhere; }
.check.passed { border-color: #3a3; }
.check.error { border-color: #a3a; }
.check p { margin: 0.3em 0; }
.likely { background: #fff4d6; border: 1px solid #e8c760; padding: 0.3em 0.6em; }
.setting { color: #555; font-size: 90%; }
.figures { display: flex; flex-wrap: wrap; gap: 0.8em; align-items: flex-start; margin: 0.5em 0; }
.figures figure { margin: 0; text-align: center; font-size: 85%; max-width: 100%; }
.figures img { width: 160px; height: 160px; image-rendering: pixelated; display: block; }
.figures svg.polar { max-width: 100%; height: auto; display: block; }
.caption { font-size: 85%; color: #444; max-width: 420px; text-align: left; }
.legend { width: 200px; max-width: 100%; font-size: 80%; color: #444; text-align: left; }
.legend .bar { height: 10px; border: 1px solid #bbb; }
.legend .ticks { display: flex; justify-content: space-between; }
.scroll { overflow-x: auto; }
table { border-collapse: collapse; font-family: monospace; font-size: 90%; }
td, th { border: 1px solid #ccc; padding: 0.15em 0.5em; text-align: right;
  white-space: nowrap; }
pre { background: #fee; padding: 0.5em; white-space: pre-wrap; }
"""


def _setting_text(setting: dict) -> str:
    """Hidden mode: the seed and the values this check drew."""
    values = ", ".join(
        f"{k}={'(' + ', '.join(f'{c:.3g}' for c in v) + ')' if isinstance(v, tuple) else v}"
        if not isinstance(v, float)
        else f"{k}={v:.4g}"
        for k, v in setting.get("params", {}).items()
    )
    lights = "; ".join(f"θ = {t:.1f}°, φ = {p:.1f}°" for t, p in setting.get("lights", []))
    return (
        f"hidden mode: seed {setting['seed']}; parameters {values or 'the defaults'}; "
        f"light at θi = {setting.get('theta_i', 0):.1f}°"
        + (f"; sphere lights {lights}" if lights else "")
        + (f"; a table of {setting['table']}" if setting.get("table") else "")
        + f" (reproduce with: brdf-lab grade EXERCISE --submission FILE --seed {setting['seed']})"
    )


def _check_html(result: CheckResult) -> str:
    e = html.escape
    message = result.message
    if result.diagnosis and message.endswith(result.diagnosis):
        message = message[: -len(result.diagnosis)].rstrip(" .") + "."
    parts = [
        f'<div class="check {e(result.status)}"><b>{e(result.name)}</b> '
        f"{points(result.points)}/{points(result.max_points)}"
        f'<p class="message">{e(message)}</p>'
    ]
    if result.diagnosis:
        parts.append(f'<p class="likely">{e(result.diagnosis)}</p>')
    if result.setting:
        parts.append(f'<p class="setting">{e(_setting_text(result.setting))}</p>')
    if result.errors:
        parts.append("<pre>" + e("\n".join(result.errors)) + "</pre>")
    figures = kind_of(result).figures(result)  # the kind's own section: images, curves...
    if figures:
        parts.append('<div class="figures">' + "".join(figures) + "</div>")
    if result.rows:
        header = "".join(f"<th>{h}</th>" for h in ROW_HEADER)
        body = "".join(
            "<tr>" + "".join(f"<td>{e(str(v))}</td>" for v in row) + "</tr>" for row in result.rows
        )
        caption = (
            "the rows nearest the tolerance (all within it)" if result.passed else "the worst rows"
        )
        parts.append(
            f'<div class="scroll"><table><caption>{caption}</caption><tr>{header}</tr>{body}'
            "</table></div>"
        )
    parts.append("</div>")
    return "".join(parts)


def html_report(tasks: list[Task], title: str = "Grading report") -> str:
    """A self-contained page: images inline as base64, no external files."""
    e = html.escape
    score = sum(t.score for t in tasks)
    total = sum(t.max_score for t in tasks)
    body = [f"<h1>{e(title)}</h1><p>Total: <b>{points(score)} / {points(total)}</b></p>"]
    for task in tasks:
        body.append(
            f"<h2>{e(task.exercise.name)}: {e(task.exercise.title)} - "
            f"{points(task.score)} / {points(task.max_score)}</h2>"
            f"<p>File: <code>{e(str(task.submission))}</code></p>"
        )
        body += [_check_html(r) for r in task.checks()]
    return (
        f'<!DOCTYPE html><html lang="en"><head><meta charset="utf-8">'
        '<meta name="viewport" content="width=device-width, initial-scale=1">'
        f"<title>{e(title)}</title>"
        f"<style>{STYLE}</style></head><body>{''.join(body)}</body></html>"
    )


def gradebook(rows: list[tuple[str, list[Task]]], exercises: list[str], path: Path) -> None:
    """CSV: one line per student, one column per exercise, then the total and maximum,
    the student's report file and why a student was not graded. Names keep their real
    text, escaped so that no cell is read as a formula."""
    from lab.grading.students import cell, file_stem

    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(["student", *exercises, "total", "max", "report", "note"])
        for student, tasks in rows:
            by_name = {t.exercise.name: t for t in tasks}
            refused = {r.message for t in tasks for r in t.results.values() if not t.key}
            writer.writerow(
                [
                    cell(student),
                    *(points(by_name[n].score) for n in exercises),
                    points(sum(t.score for t in tasks)),
                    points(sum(t.max_score for t in tasks)),
                    f"reports/{file_stem(student)}.html",
                    cell("; ".join(sorted(refused))),
                ]
            )

"""`brdf-lab web-bench`'s report: the figures it prints and how it judges them."""

from __future__ import annotations

from lab.web.bench import WebBench


def bench(first, full, frames, offscreen=()) -> WebBench:
    return WebBench(512, "phong", first, frames, "SwiftShader", "lobe3d,sh", offscreen, full)


def test_report_prints_first_and_full_quality_and_judges_the_first():
    report = bench([250.0, 320.0, 280.0], [700.0, 650.0, 690.0], [10.0] * 95 + [40.0] * 5)
    lines = report.report().splitlines()
    assert lines[0].endswith("views sphere, polar, lobe3d, sh:")
    assert "every view drawn, the costly ones coarse): median 280 ms over 3 loads" in lines[1]
    assert "(max 320 ms); target <= 300 ms: ok" in lines[1]
    assert lines[2] == "  every view at full quality: median 690 ms after load"
    # p95 of 100 frames: the 95th smallest (index 94 of 0..99, rounded) is still 10 ms.
    assert "p50 10.0 ms, p95 10.0 ms over 100 frames; target p95 <= 33 ms: ok" in lines[3]


def test_report_says_missed_and_what_was_off_screen():
    report = bench([900.0], [], [50.0] * 20, offscreen=("object",)).report()
    assert "median 900 ms over 1 loads (max 900 ms); target <= 300 ms: MISSED" in report
    assert "full quality" not in report
    assert "p95 50.0 ms over 20 frames; target p95 <= 33 ms: MISSED" in report
    assert report.endswith("NOT all visible (off screen: object)")


def test_comparison_prints_both_medians_and_the_difference():
    report = bench([300.0, 340.0, 320.0], [500.0], [10.0] * 20)
    report.compared = ("/tmp/before", [400.0, 380.0, 390.0], [640.0])
    last = report.report().splitlines()[-1]
    assert last.startswith("  compared with /tmp/before (loads in turn, one browser)")
    assert "first render median 390 ms there, 320 ms here (-70 ms)" in last
    assert last.endswith("full quality 640 ms there, 500 ms here (-140 ms)")


def test_compare_with_a_directory_that_is_no_site_says_what_to_give(tmp_path, capsys):
    from lab.cli import main

    assert main(["web-bench", "--compare", str(tmp_path), "--loads", "1"]) != 0
    err = capsys.readouterr().err
    assert f"{tmp_path}: no index.html there" in err
    assert "brdf-lab web-export DIR" in err


def test_floor_line_says_what_the_other_views_add():
    report = bench([420.0, 400.0, 410.0], [600.0], [10.0] * 20)
    report.floor_ms = [300.0, 320.0, 310.0]
    lines = report.report().splitlines()
    assert lines[2] == (
        "  sphere and polar plot alone (this machine's floor): median 310 ms; "
        "the other views add +100 ms"
    )
    assert lines[3].startswith("  every view at full quality")

"""`brdf-lab web-bench`'s report: the figures it prints, the ratios to the floor page and
how it judges them."""

from __future__ import annotations

from lab.web.bench import WebBench, all_views


def bench(first, full, frames, offscreen=()) -> WebBench:
    return WebBench(512, "phong", first, frames, "SwiftShader", "lobe3d,sh", offscreen, full)


def test_every_view_of_the_registry_is_benched():
    from lab import views

    names = all_views().split(",")
    assert "ibl" in names and "lobe3d" in names
    assert names == [v.name for v in views.all_views() if v.name in names]  # registry order
    assert "sphere" not in names and "polar" not in names  # every panel draws those itself


def test_report_prints_the_ratios_to_the_floor_page_and_judges_them():
    report = bench([330.0, 320.0, 310.0], [700.0, 650.0, 690.0], [10.0] * 95 + [40.0] * 5)
    report.floor_ms = [300.0, 290.0, 310.0]
    report.views_ms = [400.0, 450.0, 420.0]
    report.floor_frame_ms = [9.0] * 100
    lines = report.report().splitlines()
    assert lines[0].endswith("in a 1400x900 window, views sphere, polar, lobe3d, sh:")
    assert "median 320 ms after navigation over 3 loads (max 330 ms)" in lines[1]
    # Each load against the floor page's load of its turn (330/300, 320/290, 310/310), the
    # median of those: 1.10; the ratio of the medians (320/300 = 1.07) would be another.
    assert lines[2].endswith(
        "median 300 ms; first picture / floor = 1.10 (loads 1.00-1.10) (target <= 1.1): ok"
    )
    assert lines[3].endswith("median 420 ms; / floor = 1.35 (loads 1.33-1.55) (target <= 1.4): ok")
    assert lines[4] == "  every view at full quality: median 690 ms after load"
    # p95 of 100 frames: the 95th smallest (index 94 of 0..99, rounded) is still 10 ms.
    assert "p50 10.0 ms, p95 10.0 ms over 100 frames; floor page p50 9.0 ms, p95 9.0 ms" in lines[5]
    assert lines[5].endswith("p95 / floor = 1.11 (target <= 1.3): ok")


def test_report_says_missed_and_what_waited_out_of_the_window():
    report = bench([900.0], [], [50.0] * 20, offscreen=("object",))
    report.floor_ms = [300.0]
    report.views_ms = [1000.0]
    report.floor_frame_ms = [20.0] * 20
    text = report.report()
    assert "first picture / floor = 3.00 (target <= 1.1): MISSED" in text  # one load: no range
    assert "/ floor = 3.33 (target <= 1.4): MISSED" in text
    assert "p95 / floor = 2.50 (target <= 1.3): MISSED" in text
    assert "full quality" not in text
    assert text.endswith("out of the window (drawn when scrolled to or idle): object")
    report.offscreen = ("3D lobe", "spherical harmonics")  # both views of "lobe3d,sh"
    assert report.report().endswith("(a smaller --size brings views into sight)")


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

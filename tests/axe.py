"""axe-core (npm, slides/package-lock.json) run in a Playwright page: WCAG 2.0/2.1 A and AA.

`python -m tests.axe [DECK]` prints the violation counts per page state (the issue's table);
the tests (tests/test_a11y_axe.py) use `violations` on the same states.
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
AXE = ROOT / "slides" / "node_modules" / "axe-core" / "axe.min.js"
TAGS = ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa"]
VIEWS = "lobe3d,sh,terms,slice,albedo,object,ibl"


def ensure_axe() -> Path:
    """axe.min.js, installed by `npm ci` in slides/ when missing."""
    if not AXE.is_file():
        from lab.web.slides import install

        install()
    return AXE


def violations(page, frame=None) -> list[dict]:
    """axe's violations in `page` (or one of its frames): [{id, impact, nodes: [html...]}]."""
    target = frame or page
    if not target.evaluate("typeof window.axe !== 'undefined'"):
        target.add_script_tag(path=str(ensure_axe()))
    found = target.evaluate(
        """tags => axe.run(document, { runOnly: { type: "tag", values: tags },
             resultTypes: ["violations"] })
           .then(r => r.violations.map(v => ({ id: v.id, impact: v.impact,
             nodes: v.nodes.map(n => n.html.slice(0, 160)) })))""",
        TAGS,
    )
    return found


def summary(found: list[dict]) -> tuple[dict[str, int], dict[str, int]]:
    """Node counts by impact and by rule."""
    impacts: dict[str, int] = {}
    rules: dict[str, int] = {}
    for v in found:
        impacts[v["impact"]] = impacts.get(v["impact"], 0) + len(v["nodes"])
        rules[v["id"]] = rules.get(v["id"], 0) + len(v["nodes"])
    return impacts, rules


def open_lab(browser, url: str, address: str, width: int = 1300, height: int = 900):
    page = browser.new_page(viewport={"width": width, "height": height})
    page.goto(f"{url}index.html#{address}")
    page.evaluate("window.brdfLab.ready")
    page.evaluate("brdfLab.renderNow()")
    return page


def wrong_submission(page) -> None:
    """Exercise mode after a wrong practice run (Lambert: the albedo without 1/pi)."""
    page.evaluate("n => brdfLab.openExercise(n)", "01_lambert")
    page.wait_for_function("brdfLab.exercises && brdfLab.exercises.runs > 0", timeout=60_000)
    runs = page.evaluate("brdfLab.exercises.runs")
    text = page.evaluate("brdfLab.editor.editor.text")
    wrong = text.replace("return vec3(1.0, 0.0, 1.0);", "return albedo;")
    page.evaluate("t => brdfLab.editor.editor.setText(t)", wrong)
    page.wait_for_function(f"brdfLab.exercises.runs > {runs}", timeout=60_000)


def lab_states(browser, url: str):
    """(name, page) for each state of the lab page the issue audits."""
    page = open_lab(browser, url, "model=phong")
    yield "lab page, default", page
    page.close()
    page = open_lab(browser, url, f"model=cook_torrance&model=ggx&views={VIEWS}")
    yield "lab page, every view", page
    page.close()
    page = open_lab(browser, url, "model=phong&size=96")
    wrong_submission(page)
    yield "exercise mode after a wrong submission", page
    page.close()


def deck_states(browser, url: str):
    """(name, page, frame) for each slide of the built deck; a demo slide's frame is audited
    once its lab is ready."""
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    page.goto(f"{url}index.html")
    page.wait_for_function("window.Reveal && Reveal.isReady()")
    count = page.evaluate("Reveal.getTotalSlides()")
    for index in range(count):
        page.evaluate("i => Reveal.slide(i)", index)
        frame = None
        handle = page.query_selector(".present iframe.demo, .present iframe.ibl-demo")
        if handle is not None:
            page.wait_for_function(
                "() => { const f = document.querySelector('.present iframe');"
                " const w = f && f.contentWindow;"
                " return w && w.document.readyState === 'complete' &&"
                " (f.classList.contains('ibl-demo')"
                " || (w.brdfLab && w.brdfLab.state.firstRenderMs !== null)); }",
                timeout=60_000,
            )
            page.wait_for_timeout(500)  # the page's accessibility module attaches after a frame
            frame = handle.content_frame()
        yield f"slide {index + 1}", page, frame
    page.close()


def main(argv: list[str]) -> int:
    import tempfile

    from lab.web.browser import chromium
    from lab.web.site import export, serving

    rows = []
    with tempfile.TemporaryDirectory() as tmp, chromium() as browser:
        site = export(Path(tmp) / "site").parent
        with serving(site) as url:
            for name, page in lab_states(browser, url):
                rows.append((name, summary(violations(page))))
        if argv:
            with serving(Path(argv[0])) as url:
                for name, page, frame in deck_states(browser, url):
                    rows.append((name, summary(violations(page))))
                    if frame is not None:
                        rows.append((f"{name} (live demo frame)", summary(violations(page, frame))))
    print("| page | critical | serious | moderate | minor | rules |")
    print("|---|---|---|---|---|---|")
    for name, (impacts, rules) in rows:
        counts = " | ".join(
            str(impacts.get(k, 0)) for k in ("critical", "serious", "moderate", "minor")
        )
        rule_text = ", ".join(f"{k} {n}" for k, n in sorted(rules.items())) or "-"
        print(f"| {name} | {counts} | {rule_text} |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

"""`contactwave reproduce all --quick` renders in a real browser.

Opens the generated `report.html` in headless Chromium (Debian's `chromium` package,
driven by Playwright through `executable_path`; no browser download) and checks that:

- every `<figure>` holds an `<svg>` with a non-zero rendered size, and there are as many
  figures as `figures/*.svg` files (at least one);
- the page logs no console error and raises no page error;
- no request leaves the file: the only request is `report.html` itself (`file://`).

The report is the one the reference check wrote when CONTACTWAVE_REPORT_DIR names its folder
(scripts/test.sh: target/ci-out/reproduce, `reproduce all --quick` run by
scripts/reference_outputs.py at this commit, with this binary); otherwise the test runs
`reproduce all --quick` itself.

A screenshot of the first screen is kept as a test artefact at
`<target>/report-screenshot.png` (CARGO_TARGET_DIR or `<repo>/target`).

Skipped, with the reason, when Chromium or Playwright is missing, unless
CONTACTWAVE_REQUIRE_BROWSER is set (scripts/test.sh sets it and installs both).
"""

import os
import shutil
from pathlib import Path

import pytest

from conftest import ROOT, run_cli

CHROMIUM_CANDIDATES = ("chromium", "chromium-browser", "google-chrome")


def _chromium():
    exe = os.environ.get("CONTACTWAVE_CHROMIUM")
    if exe:
        return exe
    for name in CHROMIUM_CANDIDATES:
        path = shutil.which(name)
        if path:
            return path
    return None


def _require_or_skip(reason: str):
    if os.environ.get("CONTACTWAVE_REQUIRE_BROWSER"):
        pytest.fail(f"{reason} (CONTACTWAVE_REQUIRE_BROWSER is set)")
    pytest.skip(reason)


def _artefact_dir() -> Path:
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    target.mkdir(parents=True, exist_ok=True)
    return target


def test_report_renders_in_chromium(cli, tmp_path):
    chromium = _chromium()
    if chromium is None:
        _require_or_skip("chromium not found (Debian: apt-get install chromium)")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        _require_or_skip("playwright not installed (pip install playwright)")

    given = os.environ.get("CONTACTWAVE_REPORT_DIR")
    if given:
        out = Path(given)
        assert (out / "report.html").is_file(), f"CONTACTWAVE_REPORT_DIR={given}: no report.html"
    else:
        out = tmp_path / "reproduce"
        run_cli(cli, "reproduce", "all", "--quick", "--out", out)
    report = out / "report.html"
    assert report.is_file()
    svgs = sorted((out / "figures").glob("*.svg"))
    assert len(svgs) >= 1, "the report has no figure"
    url = report.resolve().as_uri()

    requests, console_errors, page_errors = [], [], []
    with sync_playwright() as p:
        browser = p.chromium.launch(
            executable_path=chromium,
            headless=True,
            args=["--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage"],
        )
        try:
            context = browser.new_context(viewport={"width": 1280, "height": 900})
            page = context.new_page()
            page.on("request", lambda r: requests.append(r.url))
            page.on(
                "console",
                lambda m: console_errors.append(m.text) if m.type == "error" else None,
            )
            page.on("pageerror", lambda e: page_errors.append(str(e)))
            page.goto(url, wait_until="load")
            figures = page.evaluate(
                """() => Array.from(document.querySelectorAll('figure')).map(f => {
                    const s = f.querySelector('svg');
                    if (!s) return {id: f.id, w: 0, h: 0, svg: false};
                    const r = s.getBoundingClientRect();
                    return {id: f.id, w: r.width, h: r.height, svg: true};
                })"""
            )
            shot = _artefact_dir() / "report-screenshot.png"
            page.screenshot(path=str(shot))
            print(f"report screenshot: {shot}")
        finally:
            browser.close()

    assert len(figures) == len(svgs), (len(figures), [s.name for s in svgs])
    for f in figures:
        assert f["svg"], f"figure {f['id']} has no <svg>"
        assert f["w"] > 0 and f["h"] > 0, f"figure {f['id']} renders empty: {f}"
    ids = {f["id"] for f in figures}
    assert ids == {s.stem for s in svgs}, ids ^ {s.stem for s in svgs}
    assert not console_errors, console_errors
    assert not page_errors, page_errors
    assert requests, "no request recorded"
    assert all(r == url for r in requests), [r for r in requests if r != url]
    assert shot.is_file() and shot.stat().st_size > 0

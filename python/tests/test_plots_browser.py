"""The CLI's plots, seen the way a person sees them: rendered by headless Chromium.

Renders a run's `spectrum.svg` (examples/rccm_1.6MPa.toml), a `sweep.svg` with 22 curves
(C_N x 22 values of xi), a bar-stack run's `frf.svg` (examples/tribobrake.toml) and
`shear_loop.svg` of examples/shear/clipping.toml, and checks in the rendered page that:

- the figure has a non-zero size, and no two text labels overlap (tick labels, axis
  labels, legend entries, marker labels);
- no label is a raw long number (`940000000000`): ticks use SI prefixes or scaled units;
- the axis labels name quantities, not dotted keys (`static pressure`, not
  `interface.static_pressure`);
- a 22-curve sweep draws its legend right of the data area with 22 entries.

PNG screenshots are kept as CI artefacts under `<target>/screenshots/` (CARGO_TARGET_DIR
or `<repo>/target`). Skipped like test_report_browser.py when Chromium or Playwright is
missing (unless CONTACTWAVE_REQUIRE_BROWSER is set).
"""

import re

import pytest

from conftest import ROOT, run_cli
from test_report_browser import _artefact_dir, _chromium, _require_or_skip

SWEEP_22 = f"""
base = "{(ROOT / 'examples' / 'rccm_0.82MPa.toml').as_posix()}"
[[axis]]
parameter = "interface.traction.stiffness"
logspace = [9, 16, 8]
[[axis]]
parameter = "incident.xi"
linspace = [0.05, 1.0, 22]
"""

# text boxes of every <text> of the page's SVG, in CSS pixels
TEXTS_JS = """() => Array.from(document.querySelectorAll('text')).map(t => {
    const r = t.getBoundingClientRect();
    return {s: t.textContent.trim(), x0: r.left, y0: r.top, x1: r.right, y1: r.bottom};
})"""


def _overlaps(texts):
    out = []
    for i, a in enumerate(texts):
        for b in texts[i + 1 :]:
            w = min(a["x1"], b["x1"]) - max(a["x0"], b["x0"])
            h = min(a["y1"], b["y1"]) - max(a["y0"], b["y0"])
            # a shared pixel of anti-aliasing is no overlap
            if w > 1.5 and h > 1.5:
                out.append((a["s"], b["s"]))
    return out


@pytest.fixture(scope="module")
def outputs(cli, tmp_path_factory):
    d = tmp_path_factory.mktemp("plots")
    run_cli(cli, "run", ROOT / "examples/rccm_1.6MPa.toml", "--out", d / "run")
    run_cli(cli, "run", ROOT / "examples/tribobrake.toml", "--out", d / "bar")
    run_cli(cli, "run", ROOT / "examples/shear/clipping.toml", "--out", d / "shear")
    sweep = d / "grid22.toml"
    sweep.write_text(SWEEP_22)
    run_cli(cli, "sweep", sweep, "--out", d / "sweep", "--threads", "2")
    return {
        "spectrum": d / "run" / "spectrum.svg",
        "frf": d / "bar" / "frf.svg",
        "shear_loop": d / "shear" / "shear_loop.svg",
        "sweep_22_curves": d / "sweep" / "sweep.svg",
    }


def test_plots_read_in_chromium(outputs):
    chromium = _chromium()
    if chromium is None:
        _require_or_skip("chromium not found (Debian: apt-get install chromium)")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        _require_or_skip("playwright not installed (pip install playwright)")

    shots = _artefact_dir() / "screenshots"
    shots.mkdir(parents=True, exist_ok=True)
    seen = {}
    with sync_playwright() as p:
        browser = p.chromium.launch(
            executable_path=chromium,
            headless=True,
            args=["--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage"],
        )
        try:
            page = browser.new_page(viewport={"width": 1300, "height": 900})
            for name, svg in outputs.items():
                assert svg.is_file(), svg
                # inlined in a page, as report.html holds its figures
                page.set_content(
                    "<!DOCTYPE html><html><body style='margin:0'>"
                    + svg.read_text(encoding="utf-8")
                    + "</body></html>"
                )
                fig = page.locator("svg").first
                box = fig.bounding_box()
                size = (box["width"], box["height"]) if box else (0, 0)
                seen[name] = (size, page.evaluate(TEXTS_JS))
                fig.screenshot(path=str(shots / f"{name}.png"))
        finally:
            browser.close()

    for name, (size, texts) in seen.items():
        assert size[0] > 0 and size[1] > 0, name
        assert texts, f"{name}: no text"
        strings = [t["s"] for t in texts]
        assert not _overlaps(texts), f"{name}: overlapping labels {_overlaps(texts)[:5]}"
        long_numbers = [s for s in strings if re.search(r"\d{7,}", s)]
        assert not long_numbers, f"{name}: raw long numbers {long_numbers}"
        dotted = [s for s in strings if re.search(r"[a-z]\.[a-z]", s)]
        assert not dotted, f"{name}: dotted keys as labels {dotted}"
        assert (shots / f"{name}.png").stat().st_size > 0
    # the 22 curves: 22 legend entries (twice: one legend per panel), right of the data
    _, texts = seen["sweep_22_curves"]
    legend = [t for t in texts if t["s"].startswith("xi = ")]
    assert len(legend) == 2 * 22, [t["s"] for t in legend]
    ticks_right = max(t["x1"] for t in texts if re.fullmatch(r"[\d.]+[a-zµ]*[A-Z]?", t["s"]))
    assert min(t["x0"] for t in legend) >= ticks_right - 1.0
    assert any("traction stiffness" in s for s in (t["s"] for t in texts))
    # harmonic markers on the spectrum: f0 ... 6f0 labelled
    _, texts = seen["spectrum"]
    assert {"f0", "2f0", "3f0"} <= {t["s"] for t in texts}

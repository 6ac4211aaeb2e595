"""The HTML report in a real headless browser: Debian's Chromium driven by Playwright.

Each report (the demo's, a grid × Monte-Carlo batch with diverged runs, the IMO check of the
KVLCC2, a sweep store) is opened from ``file://`` with every other request refused: the page
must load with no network, log no console error, draw traces in every plot container, and (the
IMO check) show the criteria table's rows; a screenshot must not be blank.

At 1,280 px (the viewport of every test here) no column is off-screen: every table *fits* --
it is no wider than its container (``div.table``), which does not scroll, and the page has no
horizontal scroll bar (measured, :data:`FIT_JS`). The report builds its tables to fit (a
large batch's per-run table has a bounded number of columns, its further metrics in a table
below it); the container's scrolling stays in the page's style only as a fallback. Every
column of a table is filled in some row (an empty one is omitted).

Playwright is pointed at the system browser (``/usr/bin/chromium``); it never downloads one.
Without Chromium or Playwright these tests are skipped with the reason (``.ci/run`` installs
Chromium when it is missing).
"""

from __future__ import annotations

import io
import shutil
from pathlib import Path

import numpy as np
import pytest

CHROMIUM = shutil.which("chromium") or ("/usr/bin/chromium" if Path("/usr/bin/chromium").exists()
                                        else None)
#: Headless, and nothing in the background: this network refuses Chromium's own connections.
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                 "--no-first-run", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync"]

pytestmark = pytest.mark.skipif(
    CHROMIUM is None, reason="no Chromium at /usr/bin/chromium (apt-get install chromium; "
                             ".ci/run installs it)")


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    """One headless Chromium for the module (a fresh, empty profile)."""
    sync_api = pytest.importorskip(
        "playwright.sync_api", reason="playwright is not installed (pip install 'seahelm[test]')")
    profile = tmp_path_factory.mktemp("chromium-profile")
    with sync_api.sync_playwright() as pw:
        context = pw.chromium.launch_persistent_context(
            str(profile), executable_path=CHROMIUM, headless=True, args=CHROMIUM_ARGS,
            viewport={"width": 1280, "height": 900})
        try:
            yield context
        finally:
            context.close()


def open_report(context, path: Path) -> tuple[object, dict]:
    """Open ``path`` with every non-file request refused; returns the page and what was
    seen: console errors, page errors, refused requests."""
    seen: dict[str, list[str]] = {"errors": [], "refused": []}
    page = context.new_page()

    def route(r):
        if r.request.url.startswith("file://"):
            r.continue_()
        else:
            seen["refused"].append(r.request.url)
            r.abort()

    page.route("**/*", route)
    page.on("console", lambda m: m.type == "error" and seen["errors"].append(m.text))
    page.on("pageerror", lambda e: seen["errors"].append(str(e)))
    page.goto(path.resolve().as_uri(), wait_until="load")
    page.wait_for_function("() => Array.from(document.querySelectorAll('.plotly-graph-div'))"
                           ".every(d => d._fullLayout !== undefined)", timeout=30_000)
    return page, seen


#: Per plot container: its id, traces in its data, traces drawn (SVG groups) and the SVG paths
#: drawn in them (lines, bars) that are not empty.
PLOTS_JS = """() => Array.from(document.querySelectorAll('.plotly-graph-div')).map(d => ({
    id: d.id, data: (d.data || []).length,
    drawn: d.querySelectorAll('g.trace').length,
    paths: Array.from(d.querySelectorAll('g.trace path'))
        .filter(p => (p.getAttribute('d') || '').length > 10).length}))"""


#: The page's width and scroll width, and per table: its right edge, its container's right
#: edge and whether the container scrolls, its headings, and the headings of the columns that
#: are blank ("" or "—") in every row.
FIT_JS = """() => ({
  width: document.documentElement.clientWidth,
  scroll: document.documentElement.scrollWidth,
  tables: Array.from(document.querySelectorAll('table')).map(t => {
    const box = t.closest('div.table');
    const rows = Array.from(t.querySelectorAll('tbody tr'));
    const heads = Array.from(t.querySelectorAll('thead th')).map(h => h.innerText.trim());
    return {cls: t.className, section: (t.closest('section') || {}).id || '',
      right: t.getBoundingClientRect().right, box: box.getBoundingClientRect().right,
      scrolls: box.scrollWidth > box.clientWidth, heads: heads,
      blank: heads.filter((h, k) => rows.length > 0 && rows.every(r => {
        const c = r.children[k]; return !c || ['', '\u2014'].includes(c.innerText.trim());
      }))};
  })})"""


def check_fit(page) -> dict:
    """Every table fits its container and the page at 1,280 px, and has no blank column."""
    seen = page.evaluate(FIT_JS)
    assert 1250 <= seen["width"] <= 1280  # (the viewport, less a vertical scroll bar)
    assert seen["scroll"] <= seen["width"], "the page scrolls sideways"
    for t in seen["tables"]:
        where = (t["section"], t["cls"], t["heads"])
        assert t["right"] <= t["box"] + 0.5 and not t["scrolls"], where
        assert t["right"] <= seen["width"], where
        assert t["blank"] == [], where
    return seen


def not_blank(png: bytes) -> float:
    """The share of pixels that are not the page's white."""
    import matplotlib.image as mpimg

    img = mpimg.imread(io.BytesIO(png), format="png")[..., :3]
    return float(np.mean(np.any(img < 0.94, axis=-1)))


def check_page(context, path: Path, n_plots: int, shot: Path) -> object:
    page, seen = open_report(context, path)
    assert seen["errors"] == [] and seen["refused"] == []
    plots = page.evaluate(PLOTS_JS)
    assert len(plots) == n_plots, plots
    for plot in plots:
        assert plot["data"] > 0 and plot["drawn"] > 0 and plot["paths"] > 0, plot
    check_fit(page)
    png = page.screenshot(full_page=True)
    shot.write_bytes(png)
    assert not_blank(png) > 0.03
    return page


def test_demo_report_in_the_browser(browser, report_demo_dir):
    page = check_page(browser, report_demo_dir / "report.html", 2,
                      report_demo_dir / "report.png")
    assert page.title() == "Mariner: 20 degree course change under PID"
    # the track figure: the run's line and its hull outlines
    traces = page.evaluate("() => document.querySelector('#track .plotly-graph-div').data"
                           ".map(t => t.name)")
    assert traces == ["run 0", "run 0 hull"]
    page.close()


def test_batch_report_in_the_browser(browser, report_batch_dir):
    # the drawn inputs' and the metrics' histograms, the track and the time series
    page = check_page(browser, report_batch_dir / "report.html", 4,
                      report_batch_dir / "report.png")
    rows = page.locator("table.diverged tbody tr")
    assert rows.count() == 5 and "state out of bounds" in rows.first.inner_text()
    heads = page.locator("table.summary thead th").all_inner_texts()
    assert "vessel.params.gain [1/s]" in " ".join(h.replace("\n", "") for h in heads)
    page.close()


def test_a_large_monte_carlo_report_fits_at_1280_px(browser, tmp_path_factory):
    """The page that pushed a column off-screen: 200 runs of the Mariner Monte-Carlo example
    (three drawn inputs, every metric), its per-run table summarised, its drawn inputs drawn."""
    from typer.testing import CliRunner

    from seahelm.cli.main import app

    where = tmp_path_factory.mktemp("report-mc")
    example = Path(__file__).resolve().parents[1] / "examples" / "mariner_monte_carlo.toml"
    scenario = where / "mc.toml"
    scenario.write_text(example.read_text().replace("record_every = 10", "record_every = 50"))
    res = CliRunner().invoke(app, ["run", str(scenario), "--out", str(where), "--no-plot",
                                   "--report"])
    assert res.exit_code == 0, res.output
    page = check_page(browser, where / "report.html", 4, where / "report.png")
    seen = check_fit(page)
    summary = [t for t in seen["tables"] if t["cls"] == "summary"]
    assert summary and page.locator("table.summary").first.locator("tbody tr").count() == 20
    drawn = [t for t in seen["tables"] if t["cls"] == "statistics drawn"]
    assert len(drawn) == 1 and page.locator("table.drawn tbody tr").count() == 3
    page.close()


def test_imo_report_in_the_browser(browser, report_imo_dir):
    page = check_page(browser, report_imo_dir / "report.html", 6,
                      report_imo_dir / "report.png")
    rows = page.locator("table.imo tbody tr")
    assert rows.count() == 13
    cells = [rows.nth(i).locator("td").all_inner_texts() for i in range(13)]
    assert [c[:3] for c in cells[:3]] == [["turning", "advance", "starboard"],
                                          ["turning", "tactical diameter", "starboard"],
                                          ["initial turning", "distance to 10 deg heading change",
                                           "starboard"]]
    assert [c[7] for c in cells] == ["pass"] * 13
    assert cells[-1][:2] == ["stopping", "track reach (full astern)"]
    assert "PASSES the evaluated criteria" in page.locator("#imo").inner_text()
    # a run is selectable: its legend entry hides it in every panel of the time series
    figure = "#timeseries-zigzag .plotly-graph-div"
    page.locator(f"{figure} .legend .traces .legendtoggle").first.click(force=True)
    visible = f"""() => document.querySelector('{figure}').data
        .filter(t => t.legendgroup === '0').map(t => t.visible)"""
    # (plotly applies a single click after its double-click delay)
    page.wait_for_function(f"() => ({visible})().every(v => v === 'legendonly')",
                           timeout=5_000)
    assert page.evaluate(visible) == ["legendonly"] * 4  # heading, rudder, yaw rate, speed
    page.close()


def test_sweep_store_report_in_the_browser(browser, report_sweep_dir):
    # the drawn inputs' and the metrics' histograms, the track and the time series of its runs
    page = check_page(browser, report_sweep_dir / "report.html", 4,
                      report_sweep_dir / "report.png")
    assert page.title().startswith("Sweep: report test batch")
    text = page.locator("#sweep").inner_text()
    assert "complete" in text and "10 ok, 0 failed of 10 runs" not in text  # 5 diverge
    rows = page.locator("#sweep table.statistics tbody tr")
    assert rows.count() >= 3
    page.close()

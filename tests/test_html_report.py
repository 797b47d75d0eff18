"""``index.html`` of ``ddg-oracle check --report`` in a real headless Chromium.

Debian's ``chromium`` and ``chromium-driver`` (installed by ``.ci/run``), driven
with Selenium, at 1400 and 1024 px: the page loads from the file system with no
console error, names the run, leads with the root causes and the failures, its columns
sort and filter (a click right after typing a catalog ID selects), a clicked failure
shows its statement, values, finding, replay snippet and a drawing of its mesh with one
scale on both axes, and a mesh file's failure shows the faces around its element.
Screenshots go to ``$DDG_TEST_ARTIFACTS`` (``.ci/run`` sets it) or the test's temporary
directory.  Skipped where Chromium is not installed (a developer's machine without it);
``.ci/run`` installs it, so CI always runs this.
"""

from __future__ import annotations

import json
import os
import shutil
import textwrap
from pathlib import Path

import numpy as np
import pytest

from ddg_oracle.application.cli import main

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
DRIVER = shutil.which("chromedriver")
pytestmark = pytest.mark.skipif(not (CHROMIUM and DRIVER),
                                reason="needs Debian's chromium and chromium-driver")
# columns of the results table
ID, IMPL, STATUS, MESSAGE, EXAMPLES, FINDING = range(6)


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """A report with a failure in R^3 (libigl's boundary loops on a Moebius strip,
    F-libigl-1), a planted sign error of the cotan Laplacian (one root cause, several
    properties: D3.1 and L3.8, which reference and libigl pass in a fraction of a second
    where T3.6 took 8 s) and passes."""
    pytest.importorskip("igl")
    d = tmp_path_factory.mktemp("html") / "report"
    rc = main(["check", "--impl", "reference", "--impl", "libigl", "--impl",
               "examples.numpy_cotan:SignError", "--only", "R1.6", "D1.6", "D3.1", "L3.8",
               "--profile", "ci", "--workers", "1", "--report", str(d)])
    assert rc == 1 and (d / "index.html").is_file()
    return d


@pytest.fixture(scope="module")
def mesh_report(tmp_path_factory):
    """A mesh-file failure on a mesh too large to draw whole: an implementation whose
    angle defect is wrong at one vertex of a subdivided icosahedron."""
    d = tmp_path_factory.mktemp("html-mesh")
    from ddg_oracle.application.meshfiles import write_obj
    from ddg_oracle.reference import surfaces
    t = surfaces.icosahedron()
    V, F = t.to_arrays()
    V, F = np.asarray(V, float), np.asarray(F)
    for _ in range(3):                                     # 20 * 4**3 = 1280 faces ...
        V, F = _subdivide(V, F)
    V, F = _subdivide(V, F)                                # ... then 5120: not drawn whole
    write_obj(d / "sphere.obj", V.tolist(), F.tolist())
    (d / "offbyone.py").write_text(textwrap.dedent("""\
        from ddg_oracle.oracles.exact_reference import ReferenceImplementation
        class OffAtOne(ReferenceImplementation):
            name = "off-at-one"
            def angle_defects(self, V, F):
                K = super().angle_defects(V, F)
                K[1000] += 0.01
                return K
        """))
    import sys
    sys.path.insert(0, str(d))
    try:
        rc = main(["check", "--impl", "offbyone:OffAtOne", "--mesh", str(d / "sphere.obj"),
                   "--only", "D2.2", "--workers", "1", "--report", str(d / "report")])
    finally:
        sys.path.remove(str(d))
    assert rc == 1
    return d / "report"


def _subdivide(V, F):
    mids, out, V = {}, [], list(map(tuple, V))

    def mid(a, b):
        key = (min(a, b), max(a, b))
        if key not in mids:
            p = (np.asarray(V[a]) + np.asarray(V[b])) / 2
            mids[key] = len(V)
            V.append(tuple(p / np.linalg.norm(p)))
        return mids[key]
    for a, b, c in F:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        out += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    return np.array(V), np.array(out)


def _artifacts(tmp_path) -> Path:
    d = Path(os.environ.get("DDG_TEST_ARTIFACTS") or tmp_path)
    d.mkdir(parents=True, exist_ok=True)
    return d


def _browser(width: int):
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-quic",
                 "--no-first-run", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", f"--window-size={width},1000"):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service(DRIVER), options=options)


@pytest.fixture(scope="module", params=[1400, 1024], ids=lambda w: f"{w}px")
def browser(request):
    driver = _browser(request.param)
    driver.width = request.param
    yield driver
    driver.quit()


def _rows(driver):
    from selenium.webdriver.common.by import By
    return [r for r in driver.find_elements(By.CSS_SELECTOR, "tr.result") if r.is_displayed()]


def _cells(row):
    from selenium.webdriver.common.by import By
    return [td.text for td in row.find_elements(By.TAG_NAME, "td")]


def _canvas_pixels(driver) -> np.ndarray:
    data = driver.execute_script(
        "const c = document.getElementById('canvas');"
        "return Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data);")
    return np.array(data, dtype=np.uint8).reshape(-1, 4)


def test_the_page_names_the_run_and_leads_with_causes_and_failures(report, browser, tmp_path):
    from selenium.webdriver.common.by import By

    browser.get((report / "index.html").as_uri())
    errors = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
    assert errors == [] and browser.find_element(By.ID, "errors").text == ""
    run = browser.find_element(By.ID, "run").text
    assert "profile ci" in run and "libigl" in run and "command: ddg-oracle check" in run
    causes = [li.text for li in browser.find_elements(By.CSS_SELECTOR, "#causes li")]
    assert any("cotan_laplacian wrong" in c and "at entry" in c for c in causes), causes
    rows = _rows(browser)
    statuses = [_cells(r)[STATUS] for r in rows]
    # failures first, then the passes (every row applicable here)
    assert statuses[0] == "FAILED" and statuses == sorted(statuses, key=lambda s: s != "FAILED")
    # the status and message columns are on screen at this width
    right = browser.execute_script("return window.innerWidth")
    status_cell = rows[0].find_elements(By.TAG_NAME, "td")[STATUS]
    assert status_cell.rect["x"] + status_cell.rect["width"] <= right
    assert _cells(rows[0])[MESSAGE]
    # the heatmap has a cell per result
    assert len(browser.find_elements(By.CSS_SELECTOR, "#grid td.cell")) == len(
        browser.find_elements(By.CSS_SELECTOR, "tr.result"))
    browser.save_screenshot(str(_artifacts(tmp_path) / f"html-report-{browser.width}.png"))


def test_columns_sort_and_filters_filter(report, browser):
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import Select

    browser.get((report / "index.html").as_uri())
    header = browser.find_elements(By.CSS_SELECTOR, "table.results th")[IMPL]
    header.click()
    impls = [_cells(r)[IMPL] for r in _rows(browser)]
    assert impls == sorted(impls)
    header.click()
    assert [_cells(r)[IMPL] for r in _rows(browser)] == sorted(impls, reverse=True)
    Select(browser.find_element(By.ID, "f-status")).select_by_value("FAILED")
    assert {_cells(r)[STATUS] for r in _rows(browser)} == {"FAILED"}


def test_a_click_right_after_typing_an_id_selects_the_row(report, browser):
    # regression: the typed filter's "change" (fired by the blur of that click) rebuilt the
    # rows between mousedown and click, and the first click was swallowed
    from selenium.webdriver.common.by import By

    browser.get((report / "index.html").as_uri())
    box = browser.find_element(By.ID, "f-id")
    box.send_keys("R1")
    rows = _rows(browser)
    assert rows and all(_cells(r)[ID].startswith("R1") for r in rows)
    target = next(r for r in rows if _cells(r)[STATUS] == "FAILED")
    target.click()
    assert browser.find_element(By.ID, "view").is_displayed()
    assert "[R1.6] libigl: FAILED" in browser.find_element(By.ID, "v-title").text


def test_a_failure_shows_statement_values_finding_snippet_and_mesh(report, browser, tmp_path):
    from selenium.webdriver.common.by import By

    browser.get((report / "index.html").as_uri())
    assert _canvas_pixels(browser)[:, 3].max() == 0             # nothing drawn yet
    failed = next(r for r in _rows(browser) if _cells(r)[IMPL] == "libigl"
                  and _cells(r)[STATUS] == "FAILED")
    failed.click()
    assert "[R1.6] libigl: FAILED" in browser.find_element(By.ID, "v-title").text
    assert "R1.6 (the notes)" in browser.find_element(By.ID, "v-statement").text
    values = browser.find_element(By.ID, "v-values").text
    assert "expected: 1, observed: 4" in values
    assert "documented finding F-libigl-1" in browser.find_element(By.ID, "v-finding").text
    assert _cells(failed)[FINDING] == "F-libigl-1"
    snippet = browser.find_element(By.ID, "v-snippet").text
    assert "replay('R1.6'" in snippet and "load_implementation('libigl')" in snippet
    assert browser.find_element(By.ID, "copy").is_displayed()
    pixels = _canvas_pixels(browser)
    drawn = pixels[pixels[:, 3] > 0]
    assert len(drawn) > 0.05 * len(pixels)                      # the strip, not a blank canvas
    orange = (np.abs(drawn[:, :3].astype(int) - [240, 140, 0]).sum(axis=1) < 30).sum()
    assert orange > 200                                         # the boundary edges
    # one scale on both axes: the drawing buffer has the canvas's own shape
    w, h, cw, ch = browser.execute_script(
        "const c = document.getElementById('canvas'); const b = c.getBoundingClientRect();"
        "return [c.width, c.height, b.width, b.height];")
    assert abs(w / cw - h / ch) < 0.02, (w, h, cw, ch)
    browser.save_screenshot(str(_artifacts(tmp_path) / f"html-counterexample-{browser.width}.png"))


def test_an_error_line_without_a_numeric_error_is_not_broken(tmp_path, browser):
    # regression: "error - = - x the derived bound" for a failure with a bound but no error
    from ddg_oracle.application.html_report import write_html
    from selenium.webdriver.common.by import By
    record = {"property_id": "L4.3 / P4.4", "property_name": "p", "statement": "s",
              "implementation": "x", "spec": "x", "source": "generated", "status": "FAILED",
              "ok": False, "examples": 1, "wanted": 25, "ties": 0, "note": None, "crash": None,
              "also": [], "files": None, "replay": None, "diagnosis": None,
              "mesh": {"V": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "F": [[0, 1, 2]]},
              "failure": {"message": "not Delaunay", "element": None, "element_ids": None,
                          "expected": "<= 0", "observed": 10.0, "error": None, "bound": 0.0016,
                          "error_in_bounds": None}}
    doc = {"schema": 3, "command": {"profile": "ci", "implementations": ["x"]},
           "counts": {"FAILED": 1}, "results": [record], "interrupted": False}
    write_html(tmp_path, json.dumps(doc))
    browser.get((tmp_path / "index.html").as_uri())
    _rows(browser)[0].click()
    values = browser.find_element(By.ID, "v-values").text
    assert "error -" not in values and "derived bound 0.0016" in values


def test_a_mesh_file_failure_shows_the_faces_around_its_vertex(mesh_report, browser, tmp_path):
    from selenium.webdriver.common.by import By

    browser.get((mesh_report / "index.html").as_uri())
    failed = next(r for r in _rows(browser) if _cells(r)[STATUS] == "FAILED")
    failed.click()
    assert browser.find_element(By.ID, "v-legend").text != "no mesh for this result"
    text = browser.find_element(By.ID, "v-text").text
    assert "rings around the failing element" in text
    pixels = _canvas_pixels(browser)
    drawn = pixels[pixels[:, 3] > 0]
    assert len(drawn) > 0.05 * len(pixels)
    red = (np.abs(drawn[:, :3].astype(int) - [221, 0, 0]).sum(axis=1) < 40).sum()
    assert red > 20                                             # the failing vertex
    browser.save_screenshot(str(_artifacts(tmp_path) / f"html-mesh-file-{browser.width}.png"))

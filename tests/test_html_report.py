"""``index.html`` of ``ddg-oracle check --report`` in a real headless Chromium.

Debian's ``chromium`` and ``chromium-driver`` (installed by ``.ci/run``), driven
with Selenium: the page loads from the file system with no console error, its
table has a row per applicable result, filters work, clicking a failing result
shows its mesh (the canvas is drawn, not blank), and a screenshot is saved.
Skipped where Chromium is not installed (a developer's machine without it);
``.ci/run`` installs it, so CI always runs this.
"""

from __future__ import annotations

import shutil
import numpy as np
import pytest

from ddg_oracle.cli import main

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
DRIVER = shutil.which("chromedriver")
pytestmark = pytest.mark.skipif(not (CHROMIUM and DRIVER),
                                reason="needs Debian's chromium and chromium-driver")


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """A report with a failure in R^3 (libigl's boundary loops on a Moebius strip, F-libigl-1) and a
    planar one (an implementation whose Delaunay flips stop one flip short)."""
    pytest.importorskip("igl")
    d = tmp_path_factory.mktemp("html") / "report"
    rc = main(["check", "--impl", "reference", "--impl", "libigl", "--only", "R1.6", "D1.6",
               "--profile", "ci", "--workers", "1", "--report", str(d)])
    assert rc == 1 and (d / "index.html").is_file()
    return d


@pytest.fixture(scope="module")
def browser():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-quic",
                 "--no-first-run", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--window-size=1400,1000"):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service(DRIVER), options=options)
    yield driver
    driver.quit()


def _canvas_pixels(driver) -> np.ndarray:
    data = driver.execute_script(
        "const c = document.getElementById('canvas');"
        "return Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data);")
    return np.array(data, dtype=np.uint8).reshape(-1, 4)


def test_the_page_loads_without_errors_and_lists_the_results(report, browser):
    from selenium.webdriver.common.by import By

    browser.get((report / "index.html").as_uri())
    errors = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
    assert errors == []
    assert browser.find_element(By.ID, "errors").text == ""
    rows = browser.find_elements(By.CSS_SELECTOR, "tr.result")
    # 2 properties x 2 implementations, all applicable
    assert len(rows) == 4
    statuses = sorted(r.find_elements(By.TAG_NAME, "td")[3].text for r in rows)
    assert statuses == ["FAILED", "passed", "passed", "passed"]
    # filtering by status leaves the failure only
    from selenium.webdriver.support.ui import Select
    Select(browser.find_element(By.ID, "f-status")).select_by_value("FAILED")
    rows = browser.find_elements(By.CSS_SELECTOR, "tr.result")
    assert [r.find_elements(By.TAG_NAME, "td")[2].text for r in rows] == ["libigl"]


def test_clicking_a_failure_shows_its_mesh(report, browser, tmp_path):
    from selenium.webdriver.common.by import By

    browser.get((report / "index.html").as_uri())
    assert _canvas_pixels(browser)[:, 3].max() == 0             # nothing drawn yet
    failed = [r for r in browser.find_elements(By.CSS_SELECTOR, "tr.result")
              if r.find_elements(By.TAG_NAME, "td")[3].text == "FAILED"]
    failed[0].click()
    assert browser.find_element(By.ID, "view").is_displayed()
    assert "[R1.6] libigl: FAILED" in browser.find_element(By.ID, "v-title").text
    assert "expected: 1, observed: 4" in browser.find_element(By.ID, "v-values").text
    # the documented finding it is (docs/findings.md), in the view and in the table
    assert "documented finding F-libigl-1" in browser.find_element(By.ID, "v-values").text
    assert failed[0].find_elements(By.TAG_NAME, "td")[5].text == "F-libigl-1"
    pixels = _canvas_pixels(browser)
    drawn = pixels[pixels[:, 3] > 0]
    assert len(drawn) > 0.05 * len(pixels)                      # the strip, not a blank canvas
    # the boundary edges are drawn in orange (#f08c00): what R1.6 counts
    orange = (np.abs(drawn[:, :3].astype(int) - [240, 140, 0]).sum(axis=1) < 30).sum()
    assert orange > 200
    shot = tmp_path / "counterexample.png"
    browser.save_screenshot(str(shot))
    assert shot.stat().st_size > 20_000

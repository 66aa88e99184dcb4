#!/usr/bin/env python3
"""The report of a real run, in a real browser (Debian's Chromium, headless, through chromedriver).

    report_browser_test.py --xshade build/xshade --source . --work DIR

Renders two fixed scenes with the real xshade, one of them changed so that it fails against its
golden (the toon's colour moved a little) and one that passes, then opens the report from disk as
a reviewer would: the index (failures first, a thumbnail per scene and lane that loads, the
verdict filter), the failing scene's page by its link, every viewer mode, the pixel values under
the worst pixel read off the page against results.json (exact float32 values and steps), and the
passing scene's page. Fails on any console error or warning in any page. Exits 77 (CTest's skip)
with a message when Chromium, chromedriver or selenium is not installed.
"""

import argparse
import json
import shutil
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from browser_available import skip_unless_browser  # noqa: E402

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)
    return condition


def render(xshade, source, work):
    """A failing and a passing scene on every lane; returns the report folder."""
    shutil.rmtree(work, ignore_errors=True)
    scenes, golden, report = work / "scenes", work / "golden", work / "report"
    scenes.mkdir(parents=True)
    shutil.copytree(source / "golden", golden)
    for name in ("toon_shadow_texture", "white_furnace"):
        shutil.copy(source / "scenes" / (name + ".toml"), scenes)
    toon = scenes / "toon_shadow_texture.toml"
    text = toon.read_text()
    colour = "_Color = [0.3, 0.6, 0.9, 1]"
    assert colour in text, "the toon scene's colour moved; update this test"
    # Decided by FLIP, whose heat map and legend the page then shows beside the per-pixel layer's.
    toon.write_text(text.replace(colour, "_Color = [0.3, 0.62, 0.9, 1]") +
                    '\n[compare]\nmetric = "flip"\nmetric_threshold = 0.0001\nreason = "the page shows a metric"\n')
    run = subprocess.run([str(xshade), "run", "toon_shadow_texture", "white_furnace", "--scenes", str(scenes),
                          "--golden", str(golden), "--no-project", "--report", str(report), "--no-cache"],
                         capture_output=True, text=True)
    check(run.returncode == 1, "xshade run should fail (exit 1) on the changed scene, gave %d:\n%s%s"
          % (run.returncode, run.stdout, run.stderr))
    return report


def console_clean(browser, page):
    problems = browser.console_problems()
    check(not problems, "%s: console errors or warnings: %s" % (page, [p["message"] for p in problems]))
    browser.clear_log()


def check_index(browser, report, results):
    from viewer_driver import By
    browser.driver.get((report / "index.html").as_uri())
    console_clean(browser, "index.html")
    rows = browser.driver.find_elements(By.CSS_SELECTOR, "table.index tbody tr:not(.separator)")
    names = [row.find_element(By.CSS_SELECTOR, "td.scene a").text for row in rows]
    check(names == ["toon_shadow_texture", "white_furnace"], "index: failures first, got %s" % names)
    decides = [row.find_element(By.CSS_SELECTOR, "td.scene .decides").text for row in rows]
    check(decides == ["compared by FLIP mean ≤ 0.0001", "compared by per pixel ±1 sRGB step"],
          "index: what decides each scene, got %s" % decides)
    thumbs = browser.driver.find_elements(By.CSS_SELECTOR, "img.thumb")
    lanes = sum(len(s["lanes"]) for s in results["scenes"])
    check(len(thumbs) >= lanes, "index: %d thumbnails for %d lanes" % (len(thumbs), lanes))
    unloaded = [t.get_attribute("src") for t in thumbs
                if not browser.js("return arguments[0].complete && arguments[0].naturalWidth > 0;", t)]
    check(not unloaded, "index: thumbnails that did not load: %s" % unloaded)
    # The filter: "did not pass" leaves the failing scene alone, "all" brings the other back.
    browser.driver.find_element(By.CSS_SELECTOR, 'p.filter button[data-show="problem"]').click()
    shown = [row.find_element(By.CSS_SELECTOR, "td.scene a").text for row in rows if row.is_displayed()]
    check(shown == ["toon_shadow_texture"], "filter 'did not pass' shows %s" % shown)
    browser.driver.find_element(By.CSS_SELECTOR, 'p.filter button[data-show="all"]').click()
    shown = [row.find_element(By.CSS_SELECTOR, "td.scene a").text for row in rows if row.is_displayed()]
    check(shown == names, "filter 'all' shows %s" % shown)
    console_clean(browser, "index.html, filtered")
    # Follow the failure: the failing scene's first lane cell links to its page.
    link = rows[0].find_element(By.CSS_SELECTOR, "td.cell.v-fail a[href*='#lane-']")
    link.click()
    check(browser.driver.current_url.split("#")[0].endswith("/toon_shadow_texture.html"),
          "the failing lane's link leads to %s" % browser.driver.current_url)


def check_failing_page(browser, report, results):
    from viewer_driver import By, same_float32
    browser.open(report / "toon_shadow_texture.html")
    console_clean(browser, "toon_shadow_texture.html")
    scene = next(s for s in results["scenes"] if s["scene"] == "toon_shadow_texture")
    page = browser.scene()
    check(page["groups"], "the failing page has no viewer group")
    first = page["groups"][0]
    lane = next(l for l in scene["lanes"] if l["lane"] == first["lanes"][0])
    check(lane["verdict"] == "fail", "the first group's lane %s did not fail" % lane["lane"])

    # Every mode, by its button.
    for mode in ("flip", "swipe", "onion", "side"):
        browser.button(0, 'button[data-xv-mode="%s"]' % mode).click()
        root = browser.group(0)
        pressed = [b.get_attribute("data-xv-mode") for b in root.find_elements(By.CSS_SELECTOR, "button[data-xv-mode]")
                   if b.get_attribute("aria-pressed") == "true"]
        check(root.get_attribute("data-mode") == mode and pressed == [mode],
              "mode %s: data-mode %s, pressed %s" % (mode, root.get_attribute("data-mode"), pressed))
    console_clean(browser, "toon_shadow_texture.html, modes")

    # The worst pixel, as results.json has it, under the real mouse in the output view.
    steps = lane["against_golden"]["steps"]
    x, y = steps["worst_x"], steps["worst_y"]
    check(first["worst"] == {"x": x, "y": y, "steps": steps["worst"]},
          "the viewer's worst pixel %s is not results.json's (%d, %d), %d steps" % (first["worst"], x, y, steps["worst"]))
    browser.click_pixel(0, "output", x, y)
    shown = browser.readout(0)
    check(shown["pinned"], "clicking the worst pixel did not pin it")
    check((shown.get("x"), shown.get("y")) == (str(x), str(y)), "readout at (%s, %s), clicked (%d, %d)"
          % (shown.get("x"), shown.get("y"), x, y))
    for field, key in (("output", "worst_test"), ("golden", "worst_reference")):
        values = shown.get(field, "").split(", ")
        want = [float("nan") if w is None else w for w in steps[key]]
        check(len(values) == 4 and all(same_float32(v, w) for v, w in zip(values, want)),
              "%s at the worst pixel: page shows %s, results.json has %s" % (field, shown.get(field), want))
    step_values = [abs(int(v)) for v in shown.get("steps", "").split(", ") if v.strip().lstrip("-").isdigit()]
    check(step_values and max(step_values) == steps["worst"],
          "steps at the worst pixel: page shows %s, results.json has %d" % (shown.get("steps"), steps["worst"]))
    # The scene's metric: its heat map loaded beside the others in the side mode, its legend, and
    # how to accept the new image.
    browser.button(0, 'button[data-xv-mode="side"]').click()
    metric_images = browser.group(0).find_elements(By.CSS_SELECTOR, '[data-xv-view="metric"] img')
    check(metric_images and all(browser.js("return arguments[0].complete && arguments[0].naturalWidth > 0;", i)
                                for i in metric_images), "the FLIP heat map did not load")
    check(lane["against_golden"]["metric"]["name"] == "flip", "results.json has no FLIP for the lane")
    caption = browser.group(0).find_element(By.CSS_SELECTOR, '[data-xv-view="metric"] .xv-caption').text
    check(caption.startswith("FLIP: ") and "(≤ 0.0001)" in caption, "the metric view's caption: %s" % caption)
    legends = browser.group(0).find_elements(By.CSS_SELECTOR, '.xv-metric-legend[data-metric="flip"]')
    check(len(legends) == 1, "the FLIP legend: %d found" % len(legends))
    check("xshade bless toon_shadow_texture" in browser.driver.page_source, "the page does not name the bless command")
    # The mask counts what the per-pixel layer counted.
    browser.button(0, 'button[data-xv-action="mask"]').click()
    count = browser.field(0, "mask-count").replace(",", "")
    check(count == str(steps["failing_pixels"]), "mask count %s, results.json %d" % (count, steps["failing_pixels"]))
    console_clean(browser, "toon_shadow_texture.html, readout")


def check_passing_page(browser, report):
    browser.open(report / "white_furnace.html")
    console_clean(browser, "white_furnace.html")
    page = browser.scene()
    # The furnace renders bit-identically on every lane: one group for all three.
    check([g["lanes"] for g in page["groups"]] == [["gl", "vk", "vk-hlsl"]],
          "white_furnace's groups: %s" % [g["lanes"] for g in page["groups"]])
    check(page["cross_lane"] == [], "identical lanes have no cross-lane heat map: %s" % page["cross_lane"])


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--xshade", required=True, type=Path)
    parser.add_argument("--source", required=True, type=Path)
    parser.add_argument("--work", required=True, type=Path)
    parser.add_argument("--shots", type=Path, help="save a screenshot of each page here")
    args = parser.parse_args()
    skip_unless_browser()
    from viewer_driver import Browser

    report = render(args.xshade, args.source, args.work)
    results = json.loads((report / "results.json").read_text())
    with Browser() as browser:
        check_index(browser, report, results)
        check_failing_page(browser, report, results)
        if args.shots:
            args.shots.mkdir(parents=True, exist_ok=True)
            browser.driver.save_screenshot(str(args.shots / "failing_scene.png"))
        check_passing_page(browser, report)
    if failures:
        print("%d checks failed" % len(failures))
        return 1
    print("the report reads right in Chromium: index, filter, failing and passing pages, every mode, the worst pixel")
    return 0


if __name__ == "__main__":
    sys.exit(main())

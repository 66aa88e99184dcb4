#!/usr/bin/env python3
"""Smoke test of the image-diff viewer in headless Chromium, on the fixture of make_viewer_fixture.py:

    python3 tests/report/make_viewer_fixture.py /tmp/viewer_fixture
    python3 tests/report/viewer_smoke.py /tmp/viewer_fixture [--shots /tmp/viewer_shots]

Checks: no console errors or warnings; the four modes by button and key; the readout of hovered,
clicked and keyboard-moved pixels against the page's own float data (exact float32 values, 8-bit
codes, steps); pin and unpin; the worst-pixel marker's place and "go to worst"; the mask and its
count; zoom by wheel and keys around the cursor; synchronised pan; flip, blink, swipe and onion;
a page without golden, one without float data and one wider than the window. Saves a screenshot
of each mode. Exits 1 listing every failed check.
"""

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from browser_available import skip_unless_browser  # noqa: E402

if __name__ == "__main__":
    skip_unless_browser()
from viewer_driver import (Browser, By, expected_readout, failing_pixels, load_pixels,  # noqa: E402
                           readout_mismatches)

ZOOM_STEPS = [0.5, 1, 2, 3, 4, 6, 8, 12, 16, 24, 32]  # viewer.js ZOOM_STEPS
failures = []


def zoom_value(text):
    return 0.5 if text == "1/2×" else float(text.rstrip("×"))


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)
    return condition


def check_readout(browser, scene, images, group, x, y, context):
    problems = readout_mismatches(browser.readout(group), expected_readout(scene, group, images, x, y))
    check(not problems, "%s: readout of (%d, %d): %s" % (context, x, y, "; ".join(problems)))


def no_console_problems(browser, page):
    problems = browser.console_problems()
    check(not problems, "%s: console errors or warnings: %s" % (page, [p["message"] for p in problems]))
    browser.clear_log()


def mode_state(browser, group):
    root = browser.group(group)
    pressed = [b.get_attribute("data-xv-mode") for b in root.find_elements(By.CSS_SELECTOR, "button[data-xv-mode]")
               if b.get_attribute("aria-pressed") == "true"]
    shown = [v.get_attribute("data-xv-view") for v in root.find_elements(By.CSS_SELECTOR, ".xv-view") if v.is_displayed()]
    return root.get_attribute("data-mode"), pressed, shown


def check_mode(browser, group, mode, how):
    expected_views = ["golden", "output", "difference"] if mode == "side" else ["single"]
    got = mode_state(browser, group)
    check(got == (mode, [mode], expected_views), "%s: mode %s: got (data-mode, pressed, views) %s" % (how, mode, got))


def centre_of(browser, element):
    r = browser.js("const r = arguments[0].getBoundingClientRect(); return [r.left + r.width / 2, r.top + r.height / 2];",
                   element)
    return r


def worst_marker(browser, group, view):
    root = browser.group(group).find_element(By.CSS_SELECTOR, '.xv-view[data-xv-view="%s"]' % view)
    return root.find_element(By.CSS_SELECTOR, ".xv-worst")


def check_worst_marker(browser, group, view, worst, context):
    marker = worst_marker(browser, group, view)
    where = browser.pixel_to_client(group, view, worst["x"], worst["y"])
    cx, cy = centre_of(browser, marker)
    shown = browser.js("return !arguments[0].hidden && !!arguments[0].offsetParent;", marker)
    check(shown and abs(cx - where["clientX"]) <= 0.51 and abs(cy - where["clientY"]) <= 0.51,
          "%s: worst marker in %s at (%.1f, %.1f), pixel (%d, %d) centre at (%.1f, %.1f)"
          % (context, view, cx, cy, worst["x"], worst["y"], where["clientX"], where["clientY"]))


def mask_shown(browser, group):
    return [m.is_displayed() for m in browser.group(group).find_elements(By.CSS_SELECTOR, "img.xv-layer-mask")
            if m.find_element(By.XPATH, "ancestor::div[@data-xv-view]").is_displayed()]


def shot(browser, shots, name, group=0):
    if not shots:
        return
    browser.js("arguments[0].scrollIntoView({block: 'start'}); window.scrollBy(0, -8);", browser.group(group))
    path = shots / (name + ".png")
    browser.driver.save_screenshot(str(path))
    print("screenshot", path)


def fail_page(browser, fixture, shots):
    page = fixture / "fixture_fail.html"
    browser.open(page)
    scene = browser.scene()
    images = load_pixels(fixture / "pixels" / "fixture_fail.js")
    group = scene["groups"][0]
    worst, first = group["worst"], group["first_failing"]
    check(browser.group(0).get_attribute("data-lanes") == "gl,vk", "data-lanes of group 0")
    check(browser.group(1).get_attribute("data-lanes") == "vk-hlsl", "data-lanes of group 1")
    check_mode(browser, 0, "side", "initial")
    check(browser.field(0, "data-status") == "float values decoded", "float data decoded: " + browser.field(0, "data-status"))

    # Readout under the pointer at 1:1, in each side-by-side view: a blob pixel, the alpha
    # pixel, NaN, a value above 1, one within tolerance and an identical one.
    probes = [(40, 18), (41, 20), (8, 40), (55, 30), (45, 20), (0, 0), (63, 47)]
    for view in ("golden", "output", "difference"):
        for x, y in probes:
            browser.move_to_pixel(0, view, x, y)
            check_readout(browser, scene, images, 0, x, y, "hover in %s at 1:1" % view)
    check(browser.readout(0)["pinned"] is False, "hovering does not pin")

    # The worst pixel's marker, at 1:1 in every view.
    for view in ("golden", "output", "difference"):
        check_worst_marker(browser, 0, view, worst, "1:1")

    # Mask: count from the float data equals the report's; toggled by button and key.
    count = browser.field(0, "mask-count")
    check(count == str(group["failing_pixels"]) == str(failing_pixels(scene, 0, images)),
          "mask count %s, report %d, recomputed %d" % (count, group["failing_pixels"], failing_pixels(scene, 0, images)))
    check(browser.field(1, "mask-count") == str(scene["groups"][1]["failing_pixels"]), "group 1 mask count")
    mask = browser.button(0, 'button[data-xv-action="mask"]')
    check(mask.get_attribute("aria-pressed") == "false" and not any(mask_shown(browser, 0)), "mask off at first")
    mask.click()
    check(mask.get_attribute("aria-pressed") == "true" and all(mask_shown(browser, 0)) and mask_shown(browser, 0),
          "mask button shows the mask: %s" % mask_shown(browser, 0))
    shot(browser, shots, "side_mask")
    browser.press("m")
    check(mask.get_attribute("aria-pressed") == "false" and not any(mask_shown(browser, 0)), "M hides the mask")
    browser.press("M")
    check(all(mask_shown(browser, 0)), "M shows the mask again")
    browser.press("m")

    # Pin by click; the readout stays while the pointer moves; click again or Esc unpins.
    browser.click_pixel(0, "output", 40, 18)
    browser.move_to_pixel(0, "output", 10, 10)
    shown = browser.readout(0)
    check(shown["pinned"] and (shown["x"], shown["y"]) == ("40", "18"), "click pins (40, 18): %s" % shown)
    check_readout(browser, scene, images, 0, 40, 18, "pinned")
    pin_marks = [m for m in browser.group(0).find_elements(By.CSS_SELECTOR, ".xv-pin") if m.is_displayed()]
    check(len(pin_marks) == 3, "a pin marker in each of the 3 views, got %d" % len(pin_marks))
    browser.click_pixel(0, "golden", 40, 18)
    shown = browser.readout(0)
    check(not shown["pinned"] and (shown["x"], shown["y"]) == ("40", "18"), "clicking the pinned pixel unpins: %s" % shown)
    browser.click_pixel(0, "difference", 41, 20)
    browser.press("\ue00c")  # Escape
    check(not browser.readout(0)["pinned"], "Esc unpins")
    browser.click_pixel(0, "golden", 41, 20)
    browser.press("\ue014")  # ArrowRight
    browser.move_to_pixel(0, "golden", 3, 3)
    check_readout(browser, scene, images, 0, 42, 20, "ArrowRight moves the pin")
    browser.press("\ue00c")

    # Zoom by wheel around the cursor, keys, reset: from the default zoom up and down the steps.
    zoom = lambda: browser.field(0, "zoom")
    default = zoom()
    steps = [z for z in ZOOM_STEPS if z > zoom_value(default)]
    label = lambda z: "%g×" % z
    browser.move_to_pixel(0, "golden", 20, 20)
    point = browser.pixel_point(0, "golden", 20, 20)
    browser.wheel_at(point, -100)
    check(zoom() == label(steps[0]), "wheel up zooms from %s to %s: %s" % (default, label(steps[0]), zoom()))
    shown = browser.readout(0)
    check((shown["x"], shown["y"]) == ("20", "20"), "the pixel under the wheel stays under it: %s" % shown)
    browser.wheel_at(point, -100)
    check(zoom() == label(steps[1]), "wheel up again: %s, got %s" % (label(steps[1]), zoom()))
    browser.press("+")
    check(zoom() == label(steps[2]), "+ zooms to %s: %s" % (label(steps[2]), zoom()))
    shown = browser.readout(0)
    check((shown["x"], shown["y"]) == ("20", "20"), "+ zooms around the cursor: %s" % shown)
    browser.press("-")
    check(zoom() == label(steps[1]), "- zooms out: %s" % zoom())
    browser.wheel_at(point, 100)
    check(zoom() == label(steps[0]), "wheel down zooms out: %s" % zoom())
    for view in ("golden", "output", "difference"):
        check_worst_marker(browser, 0, view, worst, zoom())
    browser.press("0")
    check(zoom() == default, "0 resets to %s: %s" % (default, zoom()))
    browser.press("+")
    browser.press("+")
    check(zoom() == label(steps[1]), "two + from %s: %s, got %s" % (default, label(steps[1]), zoom()))

    # Pan: a drag moves every view the same way and pins nothing.
    before = {v: browser.pixel_to_client(0, v, 10, 10) for v in ("golden", "output", "difference")}
    browser.drag(browser.viewport_centre(0, "golden"), (20, 12))
    after = {v: browser.pixel_to_client(0, v, 10, 10) for v in ("golden", "output", "difference")}
    moves = {v: (round(after[v]["clientX"] - before[v]["clientX"]), round(after[v]["clientY"] - before[v]["clientY"]))
             for v in before}
    check(all(m == (20, 12) for m in moves.values()), "drag pans all views by (20, 12): %s" % moves)
    check(not browser.readout(0)["pinned"], "a drag does not pin")
    browser.move_to(browser.viewport_centre(0, "output"))
    shown = browser.readout(0)
    x, y = int(shown["x"]), int(shown["y"])
    where = browser.pixel_to_client(0, "output", x, y)
    cx, cy = browser.viewport_centre(0, "output")
    check(where["left"] <= cx < where["left"] + where["size"] and where["top"] <= cy < where["top"] + where["size"],
          "the hovered pixel (%d, %d) is the one under the pointer" % (x, y))
    check_readout(browser, scene, images, 0, x, y, "hover after zoom and pan")
    browser.press("0")

    # Go to worst / first failing: 8×, centred, pinned.
    browser.button(0, 'button[data-xv-action="worst"]').click()
    shown = browser.readout(0)
    check(zoom() == "8×" and shown["pinned"] and (shown["x"], shown["y"]) == (str(worst["x"]), str(worst["y"])),
          "go to worst: zoom %s, readout %s" % (zoom(), shown))
    check_readout(browser, scene, images, 0, worst["x"], worst["y"], "go to worst")
    for view in ("golden", "output", "difference"):
        check_worst_marker(browser, 0, view, worst, "8×")
    viewport = browser.group(0).find_element(By.CSS_SELECTOR, '.xv-view[data-xv-view="golden"] .xv-viewport')
    vc = browser.js("const r = arguments[0].getBoundingClientRect(), e = arguments[0];"
                    "return [r.left + e.clientLeft + e.clientWidth / 2, r.top + e.clientTop + e.clientHeight / 2];", viewport)
    wc = browser.pixel_to_client(0, "golden", worst["x"], worst["y"])
    check(abs(wc["clientX"] - vc[0]) <= 1 and abs(wc["clientY"] - vc[1]) <= 1,
          "worst pixel centred: pixel at (%.1f, %.1f), viewport centre (%.1f, %.1f)" % (wc["clientX"], wc["clientY"], *vc))
    browser.move_to_pixel(0, "output", worst["x"] - 1, worst["y"])
    check(browser.readout(0)["x"] == str(worst["x"]), "pinned readout stays on the worst pixel while hovering")
    shot(browser, shots, "side_worst_8x")
    browser.button(0, 'button[data-xv-action="first"]').click()
    shown = browser.readout(0)
    check((shown["x"], shown["y"]) == (str(first["x"]), str(first["y"])) and shown["pinned"], "go to first failing: %s" % shown)
    browser.press("\ue00c")
    browser.press("0")
    shot(browser, shots, "side")

    # Modes by button and by key.
    for mode in ("flip", "swipe", "onion", "side"):
        browser.button(0, 'button[data-xv-mode="%s"]' % mode).click()
        check_mode(browser, 0, mode, "button")
    for key, mode in (("2", "flip"), ("3", "swipe"), ("4", "onion"), ("1", "side")):
        browser.press(key)
        check_mode(browser, 0, mode, "key " + key)
    check_mode(browser, 1, "side", "group 1 untouched by group 0's keys")
    browser.move_to_pixel(1, "golden", 5, 5)  # keys follow the group under the pointer
    browser.press("3")
    check_mode(browser, 1, "swipe", "key 3 over group 1")
    check_mode(browser, 0, "side", "group 0 untouched by group 1's keys")
    browser.press("1")
    browser.move_to_pixel(0, "golden", 5, 5)

    # Flip: F and Space toggle; the label and the output layer agree.
    def showing():
        visible = browser.js("return getComputedStyle(arguments[0].querySelector('.xv-clip')).visibility;",
                             browser.group(0))
        return browser.field(0, "showing"), visible
    browser.press("2")
    first_state = showing()
    check(first_state in (("output", "visible"), ("golden", "hidden")), "flip label agrees with the layers: %s" % (first_state,))
    browser.press("f")
    second_state = showing()
    check(second_state != first_state and second_state in (("output", "visible"), ("golden", "hidden")),
          "F flips: %s -> %s" % (first_state, second_state))
    scroll = browser.js("return window.scrollY;")
    browser.press(" ")
    check(showing() == first_state, "Space flips back: %s" % (showing(),))
    check(browser.js("return window.scrollY;") == scroll, "Space does not scroll the page")
    browser.move_to_pixel(0, "single", 41, 20)
    check_readout(browser, scene, images, 0, 41, 20, "hover in flip view")
    browser.press("f")
    shot(browser, shots, "flip")
    # Blink: alternates at ~2 Hz until B again.
    blink = browser.button(0, 'button[data-xv-action="blink"]')
    browser.press("b")
    last, changes = None, 0
    for _ in range(16):
        state = browser.field(0, "showing")
        changes += last is not None and state != last
        last = state
        time.sleep(0.1)
    check(blink.get_attribute("aria-pressed") == "true" and changes >= 2, "blink alternates: %d changes in 1.6 s" % changes)
    browser.press("b")
    stable = browser.field(0, "showing")
    time.sleep(1.1)
    check(blink.get_attribute("aria-pressed") == "false" and browser.field(0, "showing") == stable, "B stops blinking")

    # Swipe: the divider splits at the middle; dragging it moves the split.
    browser.press("3")
    clip = lambda: browser.js("return arguments[0].querySelector('.xv-clip').style.clipPath;", browser.group(0))
    width = browser.js("return arguments[0].querySelector('.xv-view[data-xv-view=single] .xv-viewport').clientWidth;",
                       browser.group(0))
    check(clip() == "inset(0px 0px 0px %dpx)" % round(width / 2), "swipe splits in the middle: %s, width %d" % (clip(), width))
    divider = browser.group(0).find_element(By.CSS_SELECTOR, ".xv-divider")
    check(divider.is_displayed(), "swipe divider shown")
    dx, dy = centre_of(browser, divider)
    browser.drag((round(dx), round(dy)), (-width // 4, 0))
    slider = browser.group(0).find_element(By.CSS_SELECTOR, 'input[data-xv-control="swipe"]')
    value = int(slider.get_attribute("value"))
    check(200 <= value <= 300 and clip() != "inset(0px 0px 0px %dpx)" % round(width / 2),
          "dragging the divider moves the split: slider %d, %s" % (value, clip()))
    check_mode(browser, 0, "swipe", "after dragging the divider")
    browser.move_to_pixel(0, "single", 55, 30)
    check_readout(browser, scene, images, 0, 55, 30, "hover in swipe view")
    shot(browser, shots, "swipe")

    # Onion: the slider sets the output's opacity; keys typed into it are not the viewer's.
    browser.press("4")
    onion = browser.group(0).find_element(By.CSS_SELECTOR, 'input[data-xv-control="onion"]')
    opacity = lambda: browser.js("return arguments[0].querySelector('.xv-clip').style.opacity;", browser.group(0))
    check(opacity() == "0.5", "onion starts at 50%%: %s" % opacity())
    onion.click()
    onion.send_keys("\ue012" * 20 + "1")  # ArrowLeft x 20, then "1", which must not switch modes
    check(opacity() == "0.3" and browser.field(0, "onion") == "30%", "onion slider to 30%%: %s" % opacity())
    check_mode(browser, 0, "onion", "keys inside the slider are ignored")
    browser.js("document.activeElement.blur();")
    shot(browser, shots, "onion")
    browser.press("1")

    no_console_problems(browser, "fixture_fail")


def pass_page(browser, fixture, shots):
    browser.open(fixture / "fixture_pass.html")
    scene = browser.scene()
    images = load_pixels(fixture / "pixels" / "fixture_pass.js")
    check(browser.group(0).get_attribute("data-lanes") == "gl,vk", "pass page: group 0 lanes")
    check(browser.field(0, "mask-count") == "0" == str(scene["groups"][0]["failing_pixels"]), "pass page: no failing pixels")
    browser.move_to_pixel(0, "output", 22, 11)
    check_readout(browser, scene, images, 0, 22, 11, "pass page")
    check(browser.readout(0)["steps"] == "0, 1, 0, 0", "pass page: 1 step in green: %s" % browser.readout(0)["steps"])
    check_worst_marker(browser, 0, "golden", scene["groups"][0]["worst"], "pass page")
    # A group without golden: the output alone, its readout, no modes.
    root = browser.group(1)
    check(root.get_attribute("data-lanes") == "vk-hlsl" and not root.find_elements(By.CSS_SELECTOR, "button[data-xv-mode]"),
          "no-golden group has no mode buttons")
    browser.move_to_pixel(1, "single", 5, 4)
    check_readout(browser, scene, images, 1, 5, 4, "no-golden group")
    check(browser.readout(1)["golden"] == "no golden image", "no-golden readout says so: %s" % browser.readout(1)["golden"])
    pairs = [p.get_attribute("data-pair") for p in browser.driver.find_elements(By.CSS_SELECTOR, ".xv-pair")]
    check(pairs == ["gl,vk-hlsl"], "cross-lane pairs: %s" % pairs)
    shot(browser, shots, "pass_page")
    no_console_problems(browser, "fixture_pass")


def nopixels_page(browser, fixture, shots):
    browser.open(fixture / "fixture_nopixels.html")
    scene = browser.scene()
    browser.move_to_pixel(0, "golden", 40, 18)
    shown = browser.readout(0)
    check((shown["x"], shown["y"]) == ("40", "18") and shown["golden"] == shown["output"] == "float values not available",
          "no pixel data: readout says float values not available: %s" % shown)
    check(browser.button(0, 'button[data-xv-action="mask"]').get_attribute("disabled") is not None,
          "no pixel data: mask button disabled")
    check(browser.field(0, "mask-count") == str(scene["groups"][0]["failing_pixels"]), "no pixel data: the report's count")
    check_worst_marker(browser, 0, "output", scene["groups"][0]["worst"], "no pixel data")
    shot(browser, shots, "no_pixel_data")
    no_console_problems(browser, "fixture_nopixels")


def nopng_page(browser, fixture, shots):
    browser.open(fixture / "fixture_nopng.html")
    scene = browser.scene()
    images = load_pixels(fixture / "pixels" / "fixture_fail.js")
    sources = browser.js("return [...arguments[0].querySelectorAll('img.xv-layer')].map(i => i.src);", browser.group(0))
    check(sources and all(src.startswith("blob:") for src in sources),
          "no PNGs: every layer drawn from the floats: %s" % sorted(set(s[:5] for s in sources)))
    loaded = browser.js("return [...arguments[0].querySelectorAll('img.xv-layer')].every(i => i.complete && i.naturalWidth > 0);",
                        browser.group(0))
    check(loaded, "no PNGs: the drawn layers load")
    browser.move_to_pixel(0, "difference", 8, 40)
    check_readout(browser, scene, images, 0, 8, 40, "no PNGs")
    shot(browser, shots, "no_png_drawn_from_floats")
    no_console_problems(browser, "fixture_nopng")


def badkey_page(browser, fixture, shots):
    browser.open(fixture / "fixture_badkey.html")
    problems = browser.console_problems()
    check(len(problems) == 1 and problems[0]["level"] == "WARNING" and "no pixel data" in problems[0]["message"],
          "a missing pixels key is one console warning: %s" % [(p["level"], p["message"]) for p in problems])
    browser.clear_log()
    browser.move_to_pixel(0, "golden", 40, 18)
    shown = browser.readout(0)
    check(shown["output"] == "float values not available" and shown["x"] == "40",
          "missing key: float values not available: %s" % shown)
    no_console_problems(browser, "fixture_badkey")


def wide_page(browser, fixture, shots):
    browser.open(fixture / "fixture_wide.html")
    scene = browser.scene()
    images = load_pixels(fixture / "pixels" / "fixture_wide.js")
    zoom = browser.field(0, "zoom")
    check(zoom.endswith("×") and float(zoom.rstrip("×")) < 1, "wide image fits the width: zoom %s" % zoom)
    views = browser.js("const g = arguments[0], r = g.getBoundingClientRect();"
                       "return [...g.querySelectorAll('.xv-viewport')].every(v => v.getBoundingClientRect().right <= r.right);",
                       browser.group(0))
    check(views, "wide image: viewports inside the group")
    browser.move_to(browser.viewport_centre(0, "golden"))
    browser.press("+")
    check(browser.field(0, "zoom") == "1×", "from fit, + goes to 1×: %s" % browser.field(0, "zoom"))
    browser.press("+")
    x = int(browser.readout(0)["x"])
    browser.move_to_pixel(0, "output", x + 3, 21)
    check_readout(browser, scene, images, 0, x + 3, 21, "wide page zoomed")
    browser.press("0")
    check(browser.field(0, "zoom") == zoom, "0 returns to fit: %s" % browser.field(0, "zoom"))
    shot(browser, shots, "wide_fit")
    no_console_problems(browser, "fixture_wide")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("fixture", type=Path, help="folder written by make_viewer_fixture.py")
    # A string, not a Path: Path("") is ".", which would write the screenshots where the test runs.
    parser.add_argument("--shots", default="/tmp/viewer_shots", help="screenshot folder ('' for none)")
    parser.add_argument("--make", action="store_true", help="write the fixture into FIXTURE first")
    args = parser.parse_args()
    if args.make:
        from make_viewer_fixture import write_fixture
        write_fixture(args.fixture)
    shots = Path(args.shots) if args.shots else None
    if shots:
        shots.mkdir(parents=True, exist_ok=True)
    with Browser() as browser:
        for test in (fail_page, pass_page, nopixels_page, nopng_page, badkey_page, wide_page):
            try:
                test(browser, args.fixture, shots)
            except Exception as error:  # one page's crash is a failure, the others still run
                check(False, "%s raised %s: %s" % (test.__name__, type(error).__name__, error))
    if failures:
        print("\n%d check(s) failed" % len(failures))
        sys.exit(1)
    print("viewer smoke test passed")


if __name__ == "__main__":
    main()

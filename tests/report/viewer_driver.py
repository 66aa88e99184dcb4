"""Selenium helpers for the image-diff viewer of the HTML report (harness/report/viewer/viewer.js).

Shared by viewer_smoke.py (on the synthetic fixture) and tests over a real report: start headless
Chromium, open a page and wait for the viewer, collect console problems, move the real mouse to a
pixel of a view, click it, read the readout, and compute what the readout should say from the
page's own data (its scene JSON and pixels/*.js).

Needs Debian's python3-selenium and chromium-driver:
    apt-get install -y --no-install-recommends chromium chromium-driver python3-selenium
"""

import base64
import bisect
import json
import math
import re
import shutil
import struct
import sys
import tempfile
import zlib
from pathlib import Path

try:
    import selenium  # noqa: F401
except ImportError:  # a pyenv or venv python: Debian's package is in the system site-packages
    sys.path.append("/usr/lib/python3/dist-packages")
from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.actions.action_builder import ActionBuilder
from selenium.webdriver.common.actions.wheel_input import ScrollOrigin
from selenium.webdriver.common.by import By

CHROMIUM_ARGS = ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 "--no-first-run"]
# A pointer move takes no time (Selenium's default is 250 ms a move): the viewer reacts to the events,
# not to how long the pointer took between them, and the smoke test makes about eighty moves.
MOVE_MS = 0
READOUT_FIELDS = ["x", "y", "golden", "output", "difference", "golden-srgb", "output-srgb", "steps"]


class Browser:
    """Headless Chromium with a fresh profile, deleted on close; use as a context manager."""

    def __init__(self, width=1400, height=1000):
        self.profile = tempfile.mkdtemp(prefix="xv-chromium-")
        options = webdriver.ChromeOptions()
        for arg in CHROMIUM_ARGS + ["--user-data-dir=" + self.profile, "--window-size=%d,%d" % (width, height)]:
            options.add_argument(arg)
        if Path("/usr/bin/chromium").exists():
            options.binary_location = "/usr/bin/chromium"
        options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
        driver_path = shutil.which("chromedriver") or "/usr/bin/chromedriver"
        self.driver = webdriver.Chrome(service=Service(driver_path), options=options)
        self.driver.set_script_timeout(30)
        self.log = []  # every browser console entry seen so far

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        try:
            self.driver.quit()
        finally:
            shutil.rmtree(self.profile, ignore_errors=True)

    def open(self, page):
        """Opens a page (a path) and waits until every group's pixel data is decoded or failed."""
        self.driver.get(Path(page).resolve().as_uri())
        self.driver.execute_async_script(
            "const done = arguments[0];"
            "(window.xshadeViewer ? window.xshadeViewer.ready : Promise.reject('no window.xshadeViewer'))"
            ".then(() => done(true), (e) => done(String(e)));")
        self.collect_log()

    def collect_log(self):
        self.log.extend(self.driver.get_log("browser"))
        return self.log

    def console_problems(self, levels=("SEVERE", "WARNING")):
        """Console entries at the given levels: errors (SEVERE, including failed loads) and warnings."""
        return [entry for entry in self.collect_log() if entry.get("level") in levels]

    def clear_log(self):
        self.collect_log()
        self.log = []

    # -------------------------------------------------------------- the page

    def groups(self):
        return self.driver.find_elements(By.CSS_SELECTOR, "section.xv-group")

    def group(self, index):
        return self.groups()[index]

    def scene(self):
        """The scene JSON the page was written with."""
        return json.loads(self.driver.execute_script(
            "return document.getElementById('xshade-viewer-data').textContent;"))

    def js(self, script, *args):
        return self.driver.execute_script(script, *args)

    def pixel_to_client(self, group, view, x, y):
        return self.js("return window.xshadeViewer.pixelToClient(arguments[0], arguments[1], arguments[2], arguments[3]);",
                       group, view, x, y)

    def pixel_point(self, group, view, x, y):
        """An integer viewport point inside pixel (x, y) of the view, nearest its centre.

        Pointer actions take whole pixels and the viewport may sit at a fractional position, so the
        centre itself may round into a neighbour at 1:1."""
        where = self.pixel_to_client(group, view, x, y)
        inner = self.js("return [window.innerWidth, window.innerHeight];")
        if not (0 <= where["clientX"] < inner[0] and 0 <= where["clientY"] < inner[1]):
            # Pointer actions only reach the window: bring the view into sight first.
            self.js("window.xshadeViewer.groups[arguments[0]].viewNamed(arguments[1]).viewport"
                    ".scrollIntoView({block: 'center', inline: 'center'});", group, view)
            where = self.pixel_to_client(group, view, x, y)
        left, top, size = where["left"], where["top"], where["size"]

        def inside(start, centre):
            for candidate in (round(centre), math.ceil(start), math.floor(centre)):
                if start <= candidate < start + size:
                    return int(candidate)
            raise AssertionError("pixel (%d, %d) of %s is smaller than a screen pixel at zoom %g" % (x, y, view, size))
        return inside(left, where["clientX"]), inside(top, where["clientY"])

    def viewport_centre(self, group, view):
        """The integer viewport point at the middle of a view's image area."""
        self.js("window.xshadeViewer.groups[arguments[0]].viewNamed(arguments[1]).viewport"
                ".scrollIntoView({block: 'nearest', inline: 'nearest'});", group, view)
        return tuple(self.js(
            "const v = arguments[0].querySelector('.xv-view[data-xv-view=' + arguments[1] + '] .xv-viewport'),"
            " r = v.getBoundingClientRect();"
            "return [Math.round(r.left + v.clientLeft + v.clientWidth / 2), Math.round(r.top + v.clientTop + v.clientHeight / 2)];",
            self.group(group), view))

    def move_to(self, point):
        actions = ActionBuilder(self.driver, duration=MOVE_MS)
        actions.pointer_action.move_to_location(*point)
        actions.perform()

    def move_to_pixel(self, group, view, x, y):
        px, py = self.pixel_point(group, view, x, y)
        actions = ActionBuilder(self.driver, duration=MOVE_MS)
        actions.pointer_action.move_to_location(px, py)
        actions.perform()

    def click_pixel(self, group, view, x, y):
        px, py = self.pixel_point(group, view, x, y)
        actions = ActionBuilder(self.driver, duration=MOVE_MS)
        actions.pointer_action.move_to_location(px, py).click()
        actions.perform()

    def drag(self, start, delta, steps=5):
        """Presses at viewport point start, moves by delta in a few steps, releases."""
        actions = ActionBuilder(self.driver, duration=MOVE_MS)
        actions.pointer_action.move_to_location(*start).pointer_down()
        for i in range(1, steps + 1):
            actions.pointer_action.move_to_location(start[0] + delta[0] * i // steps, start[1] + delta[1] * i // steps)
        actions.pointer_action.pointer_up()
        actions.perform()

    def wheel_at(self, point, delta_y):
        ActionChains(self.driver, duration=MOVE_MS).scroll_from_origin(ScrollOrigin.from_viewport(*point), 0, delta_y).perform()

    def press(self, keys):
        """Keys sent to the page (the body has focus), as a user typing with nothing focused."""
        ActionChains(self.driver, duration=MOVE_MS).send_keys(keys).perform()

    def readout(self, group):
        """The readout's fields as text, and whether it is pinned."""
        root = self.group(group).find_element(By.CSS_SELECTOR, ".xv-readout")
        values = self.js(
            "const r = arguments[0], out = {};"
            "for (const e of r.querySelectorAll('[data-xv-field]')) out[e.dataset.xvField] = e.textContent;"
            "return out;", root)
        values["pinned"] = root.get_attribute("data-pinned") == "true"
        return values

    def button(self, group, selector):
        return self.group(group).find_element(By.CSS_SELECTOR, selector)

    def field(self, group, name):
        return self.group(group).find_element(By.CSS_SELECTOR, '[data-xv-field="%s"]' % name).text


# ------------------------------------------------------------------ expected values, from the page's data


def load_pixels(js_path):
    """pixels/SCENE.js as {key: (width, height, floats)}; floats is a flat RGBA tuple."""
    images = {}
    line = re.compile(r'\(window\.XSHADE_PIXELS = window\.XSHADE_PIXELS \|\| \{\}\)\[(".*?")\] = (\{.*\});\s*$')
    for text in Path(js_path).read_text(encoding="ascii").splitlines():
        match = line.match(text)
        if not match:
            continue
        key, entry = json.loads(match.group(1)), json.loads(match.group(2))
        assert entry["encoding"] == "deflate-f32le-rgba", entry["encoding"]
        raw = zlib.decompress(base64.b64decode(entry["data"]))
        count = entry["width"] * entry["height"] * 4
        assert len(raw) == count * 4, (key, len(raw))
        images[key] = (entry["width"], entry["height"], struct.unpack("<%df" % count, raw))
    return images


def f32(value):
    return struct.unpack("<f", struct.pack("<f", value))[0]


class Codes:
    """8-bit codes as the viewer (and write_png) compute them, from the scene's srgb_code_starts."""

    def __init__(self, starts):
        self.starts = [f32(s) for s in starts]

    def colour(self, value):
        if not value > 0.0:
            return 0
        if value >= self.starts[255]:
            return 255
        return bisect.bisect_right(self.starts, value) - 1

    @staticmethod
    def alpha(value):
        return int(math.floor(f32(min(value, 1.0) * 255.0) + 0.5)) if value > 0.0 else 0

    def pixel(self, rgba):
        return [self.colour(rgba[0]), self.colour(rgba[1]), self.colour(rgba[2]), self.alpha(rgba[3])]


def pixel_of(image, x, y):
    width, _, floats = image
    i = (y * width + x) * 4
    return list(floats[i:i + 4])


def expected_readout(scene, group_index, images, x, y):
    """What the readout's fields hold for pixel (x, y): floats as values, codes as ints."""
    group = scene["groups"][group_index]
    codes = Codes(scene["srgb_code_starts"])
    output = pixel_of(images[group["output"]["pixels"]], x, y)
    out = {"x": x, "y": y, "output": output, "output-srgb": codes.pixel(output)}
    if group.get("golden"):
        golden = pixel_of(images[group["golden"]["pixels"]], x, y)
        out["golden"] = golden
        out["golden-srgb"] = codes.pixel(golden)
        out["difference"] = [f32(o - g) if not (math.isnan(o) or math.isnan(g)) else float("nan")
                             for o, g in zip(output, golden)]
        out["steps"] = [o - g for o, g in zip(out["output-srgb"], out["golden-srgb"])]
    return out


def failing_pixels(scene, group_index, images):
    """Pixels whose largest channel difference exceeds the tolerance, counted from the float data."""
    group = scene["groups"][group_index]
    codes = Codes(scene["srgb_code_starts"])
    width, height, output = images[group["output"]["pixels"]]
    golden = images[group["golden"]["pixels"]][2]
    count = 0
    for p in range(width * height):
        a = codes.pixel(output[p * 4:p * 4 + 4])
        b = codes.pixel(golden[p * 4:p * 4 + 4])
        count += max(abs(u - v) for u, v in zip(a, b)) > group["channel_tolerance"]
    return count


def parse_number(text):
    text = text.strip()
    return {"NaN": float("nan"), "Infinity": float("inf"), "-Infinity": float("-inf")}.get(text) \
        if text in ("NaN", "Infinity", "-Infinity") else float(text)


def same_float32(shown, expected):
    """Whether a readout number reads back as exactly the float32 expected, in at most 9 digits."""
    if math.isnan(expected):
        return shown.strip() == "NaN"
    digits = re.sub(r"e.*$", "", shown.strip()).lstrip("-").replace(".", "").lstrip("0")
    value = parse_number(shown)
    same_sign = math.copysign(1, value) == math.copysign(1, expected)
    return len(digits) <= 9 and f32(value) == expected and same_sign


def readout_mismatches(shown, expected):
    """Differences between a readout (Browser.readout) and expected_readout, as messages."""
    problems = []
    for name, want in expected.items():
        got = shown.get(name)
        if got is None:
            problems.append("no field %s" % name)
        elif isinstance(want, int):
            if got.strip() != str(want):
                problems.append("%s: %r, expected %d" % (name, got, want))
        else:
            parts = [p for p in got.split(", ")]
            if len(parts) != 4:
                problems.append("%s: %r is not 4 values" % (name, got))
            elif name.endswith("srgb") or name == "steps":
                if [int(p) for p in parts] != want:
                    problems.append("%s: %r, expected %s" % (name, got, want))
            elif not all(same_float32(p, w) for p, w in zip(parts, want)):
                problems.append("%s: %r, expected %s" % (name, got, ", ".join(repr(w) for w in want)))
    return problems

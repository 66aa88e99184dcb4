#!/usr/bin/env python3
"""Writes scene pages in the format report_html.cpp emits, with synthetic float images, so that the
image-diff viewer (harness/report/viewer/) can be developed and tested without the C++ side.

    python3 tests/report/make_viewer_fixture.py OUT_DIR

OUT_DIR gets:
  fixture_fail.html      64x48: golden gradient; gl = vk differ in a blob by 3 sRGB steps (a ring of
                         1 step around it, within tolerance), one NaN, one value above 1.0, one alpha
                         of 0.98; vk-hlsl differs less and has no NaN; one cross-lane pair.
  fixture_pass.html      40x30: gl = vk within tolerance of the golden (pass); vk-hlsl has no golden.
  fixture_nopixels.html  fixture_fail without its pixels script: no float values.
  fixture_nopng.html     fixture_fail with every PNG null: images drawn from the float data.
  fixture_badkey.html    a pixels key that the pixels file lacks: one console warning, by design.
  fixture_wide.html      1500x40, wider than the page: fit to width; identical images.
  index.html, pixels/*.js, golden/, gl/, vk-hlsl/, cross/ PNGs.

Everything the C++ computes (8-bit codes, failing pixels, worst pixel, heat maps) is computed here
the same way (harness/image/image_compare.cpp, srgb8_encoder.cpp), except the heat palette's
colours, which approximate matplotlib's inferno from nine samples. Standard library only.
"""

import base64
import bisect
import json
import math
import re
import struct
import sys
import zlib
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
VIEWER = REPO / "harness" / "report" / "viewer"


def f32(value):
    """value rounded to float32 (as a Python float); NaN and infinities pass through."""
    return struct.unpack("<f", struct.pack("<f", value))[0]


# ------------------------------------------------------------------ sRGB codes, as the C++ does


def linear_to_srgb8(linear):
    """harness/image/image_io.cpp linear_to_srgb8: glibc pow in double, lround."""
    if not linear > 0.0:
        return 0
    if linear >= 1.0:
        return 255
    c = 12.92 * linear if linear <= 0.0031308 else 1.055 * math.pow(linear, 1.0 / 2.4) - 0.055
    return int(math.floor(c * 255.0 + 0.5))


def code_starts():
    """srgb8_encoder.cpp build_table: per code the smallest float encoding as it, by bisecting bit patterns."""
    one = struct.unpack("<I", struct.pack("<f", 1.0))[0]
    as_float = lambda bits: struct.unpack("<f", struct.pack("<I", bits))[0]
    starts = [0.0]
    for code in range(1, 256):
        low, high = 0, one
        while high - low > 1:
            middle = low + (high - low) // 2
            if linear_to_srgb8(as_float(middle)) >= code:
                high = middle
            else:
                low = middle
        starts.append(as_float(high))
    return starts


STARTS = code_starts()


def encode(value):
    """linear_to_srgb8_by_table: the largest k with value >= STARTS[k]."""
    if not value > 0.0:
        return 0
    if value >= STARTS[255]:
        return 255
    return bisect.bisect_right(STARTS, value) - 1


def alpha8(value):
    return int(math.floor(f32(min(value, 1.0) * 255.0) + 0.5)) if value > 0.0 else 0


def encode_pixel(rgba):
    return [encode(rgba[0]), encode(rgba[1]), encode(rgba[2]), alpha8(rgba[3])]


# ------------------------------------------------------------------ images


class Image:
    def __init__(self, width, height, fill):
        self.width, self.height = width, height
        self.rgba = [f32(v) for y in range(height) for x in range(width) for v in fill(x, y)]

    def copy(self):
        return Image(self.width, self.height, lambda x, y: self.get(x, y))

    def get(self, x, y):
        i = (y * self.width + x) * 4
        return self.rgba[i:i + 4]

    def set(self, x, y, channel, value):
        self.rgba[(y * self.width + x) * 4 + channel] = f32(value)

    def floats_le(self):
        return struct.pack("<%df" % len(self.rgba), *self.rgba)

    def bytes8(self):
        return bytes(b for p in range(self.width * self.height) for b in encode_pixel(self.rgba[p * 4:p * 4 + 4]))


def shift_code(value, steps):
    """The smallest float whose code is `steps` above value's: a difference of exactly `steps`."""
    return STARTS[min(255, encode(value) + steps)]


def compare(test, reference, tolerance):
    """image_compare.cpp compare_pixels: per pixel the largest channel difference in 8-bit steps."""
    steps = []
    for p in range(test.width * test.height):
        a = encode_pixel(test.rgba[p * 4:p * 4 + 4])
        b = encode_pixel(reference.rgba[p * 4:p * 4 + 4])
        steps.append(max(abs(u - v) for u, v in zip(a, b)))
    failing = [p for p, s in enumerate(steps) if s > tolerance]
    worst = max(steps)
    worst_pixel = steps.index(worst)  # the first of the largest, as the C++ (strict >)
    w = test.width
    return {
        "steps": steps,
        "failing": len(failing),
        "first_failing": {"x": failing[0] % w, "y": failing[0] // w} if failing else None,
        "worst": {"x": worst_pixel % w, "y": worst_pixel // w, "steps": worst} if worst else None,
        "verdict": "fail" if failing else "pass",
    }


# ------------------------------------------------------------------ heat palette, as image_compare.cpp


def heat_position(steps, tolerance):
    if steps == 0:
        return 0.0
    if steps <= tolerance:
        return 0.05 + 0.25 * steps / tolerance
    span = 255 - tolerance
    if span < 2:
        return 0.5
    return 0.5 + 0.5 * math.log(steps - tolerance) / math.log(span)


# matplotlib's inferno at 0, 1/8, ..., 1 (sRGB); the C++ gets the full map from OpenImageIO.
INFERNO = [(0, 0, 4), (31, 12, 72), (85, 15, 109), (136, 34, 106), (186, 54, 85),
           (227, 89, 51), (249, 142, 9), (246, 215, 70), (252, 255, 164)]


def inferno(position):
    scaled = min(max(position, 0.0), 1.0) * (len(INFERNO) - 1)
    i = min(int(scaled), len(INFERNO) - 2)
    t = scaled - i
    return tuple(round(a + (b - a) * t) for a, b in zip(INFERNO[i], INFERNO[i + 1]))


def heat_palette(tolerance):
    colours = [(0, 0, 0)] + [inferno(heat_position(s, tolerance)) for s in range(1, 256)]
    return ["#%02x%02x%02x" % c for c in colours]


def heat_map_bytes(steps, palette):
    rgb = [tuple(int(c[i:i + 2], 16) for i in (1, 3, 5)) for c in palette]
    return bytes(b for s in steps for b in (*rgb[s], 255))


# ------------------------------------------------------------------ files


def write_png(path, width, height, rgba):
    """An 8-bit RGBA PNG, rows top to bottom."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    stride = width * 4
    raw = b"".join(b"\x00" + rgba[y * stride:(y + 1) * stride] for y in range(height))
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
                     + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def pixels_line(key, image):
    entry = {"width": image.width, "height": image.height, "encoding": "deflate-f32le-rgba",
             "data": base64.b64encode(zlib.compress(image.floats_le(), 9)).decode("ascii")}
    return "(window.XSHADE_PIXELS = window.XSHADE_PIXELS || {})[%s] = %s;\n" % (json.dumps(key), json.dumps(entry))


def page_style():
    """The report page's own CSS (report_html.cpp kStyle), so that the fixture tests coexistence."""
    source = (REPO / "harness" / "report" / "report_html.cpp").read_text(encoding="utf-8")
    found = re.search(r'kStyle = R"css\((.*?)\)css"', source, re.S)
    return found.group(1) if found else "body { font: 14px/1.45 system-ui, sans-serif; margin: 0 24px 48px; }"


def write_page(out, stem, scene, with_pixels_script=True, pixels_stem=None):
    data = json.dumps(scene, separators=(",", ":")).replace("</", "<\\/")
    css = (VIEWER / "viewer.css").read_text(encoding="utf-8")
    js = (VIEWER / "viewer.js").read_text(encoding="utf-8")
    failing = any(g["verdict"] != "pass" for g in scene["groups"])
    pixels = '<script src="pixels/%s.js"></script>\n' % (pixels_stem or stem) if with_pixels_script else ""
    html = (
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
        "<title>%(scene)s - xshade viewer fixture</title>\n<style>%(page_css)s</style>\n</head>\n<body>\n"
        "<header class=\"v-%(verdict)s\"><h1>%(scene)s</h1><p>Viewer fixture written by "
        "tests/report/make_viewer_fixture.py. <a href=\"index.html\">All fixtures</a></p></header>\n"
        "<h2>Images</h2>\n"
        "<div id=\"xshade-viewer\"></div>\n"
        "<script id=\"xshade-viewer-data\" type=\"application/json\">%(data)s</script>\n"
        "%(pixels)s<style>%(css)s</style>\n<script>%(js)s</script>\n</body>\n</html>\n"
    ) % {"scene": scene["scene"], "page_css": page_style(), "verdict": "fail" if failing else "pass",
         "data": data, "pixels": pixels, "css": css, "js": js}
    (out / (stem + ".html")).write_text(html, encoding="utf-8")


class Scene:
    """Collects a scene's images, PNGs and JSON while it is written."""

    def __init__(self, out, name, golden, tolerance=1):
        self.out, self.name, self.golden, self.tolerance = out, name, golden, tolerance
        self.palette = heat_palette(tolerance)
        self.lines = [pixels_line(name + "/golden", golden)]
        write_png(out / "golden" / (name + ".png"), golden.width, golden.height, golden.bytes8())
        self.json = {"scene": name, "width": golden.width, "height": golden.height,
                     "srgb_code_starts": STARTS, "heat_palette": self.palette,
                     "channel_tolerance": tolerance, "groups": [], "cross_lane": []}
        self.outputs = {}

    def group(self, lanes, output, with_golden=True, verdict=None):
        lane = lanes[0]
        key = "%s/%s" % (self.name, lane)
        self.lines.append(pixels_line(key, output))
        png = "%s/%s.png" % (lane, self.name)
        write_png(self.out / png, output.width, output.height, output.bytes8())
        for each in lanes:
            self.outputs[each] = output
        group = {"lanes": lanes, "output": {"pixels": key, "png": png}, "golden": None, "heat_map": None,
                 "heat_palette": self.palette, "channel_tolerance": self.tolerance, "worst": None,
                 "first_failing": None, "failing_pixels": 0, "verdict": verdict or "fail"}
        if with_golden:
            result = compare(output, self.golden, self.tolerance)
            heat = "%s/%s.diff.png" % (lane, self.name)
            write_png(self.out / heat, output.width, output.height, heat_map_bytes(result["steps"], self.palette))
            group.update({"golden": {"pixels": self.name + "/golden", "png": "golden/%s.png" % self.name},
                          "heat_map": heat, "worst": result["worst"], "first_failing": result["first_failing"],
                          "failing_pixels": result["failing"], "verdict": verdict or result["verdict"]})
        self.json["groups"].append(group)

    def cross(self, first, second):
        """scene_check.cpp compare_lanes: the second lane's image against the first's."""
        result = compare(self.outputs[second], self.outputs[first], self.tolerance)
        if result["worst"] is None:
            return  # only pairs whose images differ
        heat = "cross/%s-%s.png" % (first, second)
        write_png(self.out / heat, self.golden.width, self.golden.height, heat_map_bytes(result["steps"], self.palette))
        self.json["cross_lane"].append({"first": first, "second": second, "verdict": result["verdict"],
                                        "heat_map": heat, "worst": result["worst"]})

    def write(self, **page_options):
        (self.out / "pixels").mkdir(parents=True, exist_ok=True)
        (self.out / "pixels" / (self.name + ".js")).write_text("".join(self.lines), encoding="ascii")
        write_page(self.out, self.name, self.json, **page_options)


# ------------------------------------------------------------------ the fixtures


def gradient(width, height, blue):
    return Image(width, height, lambda x, y: ((x / (width - 1)) ** 2.2, (y / (height - 1)) ** 2.2, blue, 1.0))


def fail_scene(out):
    golden = gradient(64, 48, 0.2)
    scene = Scene(out, "fixture_fail", golden)

    def damaged(blob_steps, nan, over_one):
        image = golden.copy()
        for y in range(48):
            for x in range(64):
                d2 = (x - 40) ** 2 + (y - 20) ** 2
                for c in range(3):
                    if d2 <= 16:
                        image.set(x, y, c, shift_code(golden.get(x, y)[c], blob_steps))
                    elif d2 <= 36 and c == 0:
                        image.set(x, y, c, shift_code(golden.get(x, y)[c], 1))  # within tolerance
        image.set(41, 20, 3, 0.98)  # alpha: 250 instead of 255
        if nan:
            image.set(8, 40, 0, float("nan"))
        image.set(55, 30, 1, over_one)
        return image

    scene.group(["gl", "vk"], damaged(3, True, 1.75))
    scene.group(["vk-hlsl"], damaged(2, False, 1.25))
    scene.cross("gl", "vk-hlsl")
    scene.write()
    # The same page without its pixels script: the viewer works without float values.
    write_page(out, "fixture_nopixels", dict(scene.json, scene="fixture_nopixels"), with_pixels_script=False)
    # Without PNGs: the viewer draws the images and the heat map from the float data.
    groups = [dict(g, output=dict(g["output"], png=None), golden=dict(g["golden"], png=None), heat_map=None)
              for g in scene.json["groups"]]
    write_page(out, "fixture_nopng", dict(scene.json, scene="fixture_nopng", groups=groups), pixels_stem="fixture_fail")
    # A key the pixels file lacks: a console warning (not an error), no float values for that group.
    groups = [dict(scene.json["groups"][0], output=dict(scene.json["groups"][0]["output"], pixels="fixture_fail/missing"))]
    write_page(out, "fixture_badkey", dict(scene.json, scene="fixture_badkey", groups=groups, cross_lane=[]),
               pixels_stem="fixture_fail")


def pass_scene(out):
    golden = gradient(40, 30, 0.5)
    scene = Scene(out, "fixture_pass", golden)
    within = golden.copy()
    for y in range(10, 14):
        for x in range(20, 26):
            within.set(x, y, 1, shift_code(golden.get(x, y)[1], 1))
    other = golden.copy()
    for y in range(3, 6):
        for x in range(4, 9):
            other.set(x, y, 2, shift_code(golden.get(x, y)[2], 1))
    scene.group(["gl", "vk"], within)
    scene.group(["vk-hlsl"], other, with_golden=False, verdict="fail")  # its golden is missing
    scene.cross("gl", "vk-hlsl")
    scene.write()


def wide_scene(out):
    golden = Image(1500, 40, lambda x, y: ((x % 100) / 99.0, y / 39.0, 0.3 if (x // 100) % 2 else 0.7, 1.0))
    scene = Scene(out, "fixture_wide", golden)
    scene.group(["gl", "vk", "vk-hlsl"], golden.copy())
    scene.write()


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_viewer_fixture.py OUT_DIR")
    write_fixture(Path(sys.argv[1]))


def write_fixture(out):
    out.mkdir(parents=True, exist_ok=True)
    fail_scene(out)
    pass_scene(out)
    wide_scene(out)
    pages = ["fixture_fail", "fixture_pass", "fixture_nopixels", "fixture_nopng", "fixture_badkey", "fixture_wide"]
    (out / "index.html").write_text(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>viewer fixtures</title></head><body>"
        "<h1>Viewer fixtures</h1><ul>%s</ul></body></html>\n"
        % "".join('<li><a href="%s.html">%s</a></li>' % (p, p) for p in pages), encoding="utf-8")
    print("wrote %s: %s" % (out, ", ".join(p + ".html" for p in pages)))


if __name__ == "__main__":
    main()

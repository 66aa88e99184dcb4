#!/usr/bin/env python3
"""`xshade watch` in a real browser (Debian's Chromium, headless, through chromedriver).

    watch_browser_test.py --xshade build/xshade --source . --work DIR

Starts `xshade watch` on a copy of the example project (examples/user_project) and opens its scene
page from the server, as an author would. Then, as the author edits the material:

1. The page is zoomed in, panned, put in flip mode and a pixel pinned; the material's base colour is
   changed. The page shows the new image without a reload (the same document: a mark set on
   window survives), with the zoom, the pan, the mode and the pinned pixel as they were, and the readout
   under the pinned pixel reads the new float values.
2. A syntax error is saved. The page shows the compiler's message with the source line and the
   caret under the error, and the console of `xshade watch` shows it too; watch goes on.
3. The error is fixed. The page shows the image again, still zoomed and panned, in flip mode, pinned.
4. A page opened while the shader does not compile (so without the viewer) shows the images, in
   place, once the error is fixed.

Ctrl-C (SIGINT) then ends watch with 130 and leaves no worker behind. Fails on any console error or
warning in the page. Exits 77 (CTest's skip) when Chromium, chromedriver or selenium is missing.
"""

import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from browser_available import skip_unless_browser  # noqa: E402

failures = []
SCENE = "paint_samples"
MATERIAL = Path("shaders/materials/clear_coat.hlsl")
BASE = "float4(0.6, 0.05, 0.05, 1.0)"
# A round on this 192x168 scene takes a fraction of a second; 60 s is for a machine busy with the
# rest of the suite.
ROUND_SECONDS = 60


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)
    return condition


class Watch:
    """xshade watch in the project folder, its output read as it comes."""

    def __init__(self, xshade, project, report):
        self.process = subprocess.Popen([str(xshade), "watch", "--port", "0", "--report", str(report), "-j", "2"],
                                        cwd=project, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.out, self.err = [], []
        self.lock = threading.Lock()
        for stream, lines in ((self.process.stdout, self.out), (self.process.stderr, self.err)):
            threading.Thread(target=self.read, args=(stream, lines), daemon=True).start()

    def read(self, stream, lines):
        for line in stream:
            with self.lock:
                lines.append(line)

    def wait_for(self, pattern, lines, start=0):
        """The first line from `start` that matches, waiting for it; None when watch ended first."""
        deadline = time.monotonic() + ROUND_SECONDS
        while time.monotonic() < deadline:
            with self.lock:
                for line in lines[start:]:
                    if re.search(pattern, line):
                        return line
            if self.process.poll() is not None:
                return None
            time.sleep(0.05)
        return None

    def rounds(self):
        with self.lock:
            return sum(1 for line in self.out if line.startswith("round "))

    def text(self):
        with self.lock:
            return "".join(self.out) + "".join(self.err)


def wait_for_update(browser, updates):
    """Waits until the page has put `updates` new states in place and its viewer is ready."""
    return browser.driver.execute_async_script(
        "const [want, done] = arguments, start = Date.now();"
        "(function poll() {"
        "  const live = window.xshadeLive;"
        "  if (live && live.updates >= want && document.body.dataset.xshadeLive === 'updated')"
        "    return window.xshadeViewer.ready.then(() => done(true));"
        "  if (Date.now() - start > %d) return done(false);"
        "  setTimeout(poll, 50);"
        "})();" % (ROUND_SECONDS * 1000), updates)


def view_of(browser):
    group = browser.group(0)
    readout = browser.readout(0)
    pan = browser.js("const g = window.xshadeViewer.groups[0]; return [g.tx, g.ty];")
    return {"mode": group.get_attribute("data-mode"), "zoom": browser.field(0, "zoom"), "pan": pan,
            "pinned": readout["pinned"], "x": readout["x"], "y": readout["y"]}


def edit(project, old, new):
    path = project / MATERIAL
    text = path.read_text()
    assert old in text, "%s no longer holds %r; update this test" % (MATERIAL, old)
    # As editors save: a new file renamed over the old one.
    saved = path.with_name("." + path.name + ".tmp")
    saved.write_text(text.replace(old, new, 1))
    os.replace(saved, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--xshade", type=Path, required=True)
    parser.add_argument("--source", type=Path, required=True)
    parser.add_argument("--work", type=Path, required=True)
    args = parser.parse_args()
    skip_unless_browser()
    from viewer_driver import Browser, By

    shutil.rmtree(args.work, ignore_errors=True)
    project = args.work / "project"
    shutil.copytree(args.source / "examples" / "user_project", project)
    watch = Watch(args.xshade.resolve(), project, args.work / "report")
    try:
        first = watch.wait_for(r"^round 1 ", watch.out)
        if not check(first is not None, "watch gave no first round:\n" + watch.text()):
            return
        address = re.search(r"http://127\.0\.0\.1:\d+/", first).group(0)
        with Browser() as browser:
            browser.driver.get(address + SCENE + ".html")
            browser.driver.execute_async_script("const done = arguments[0]; window.xshadeViewer.ready.then(() => done(true));")
            browser.collect_log()
            # The author's view: zoomed in twice, panned, flip mode, a pixel pinned.
            browser.button(0, 'button[data-xv-action="zoom-in"]').click()
            browser.button(0, 'button[data-xv-action="zoom-in"]').click()
            browser.button(0, 'button[data-xv-mode="flip"]').click()
            browser.drag(browser.viewport_centre(0, "single"), (-12, -8))
            browser.click_pixel(0, "single", 144, 56)  # the middle, which the zoom keeps in sight
            before = view_of(browser)
            check(before["pinned"] and before["mode"] == "flip", "the view before the edit: %s" % before)
            output_before = browser.readout(0)["output"]
            browser.js("window.sameDocument = true;")

            # 1. The material's colour changes: the new image in place, the view kept.
            edit(project, BASE, "float4(0.05, 0.3, 0.6, 1.0)")
            check(wait_for_update(browser, 1), "the page did not update after the edit:\n" + watch.text())
            check(browser.js("return window.sameDocument === true;"), "the page was loaded again, not updated in place")
            after = view_of(browser)
            check(after == before, "the view changed with the update: %s, before %s" % (after, before))
            check(browser.readout(0)["output"] != output_before,
                  "the pinned pixel still reads %s after the colour changed" % output_before)
            src = browser.js("return document.querySelector('section.xv-group img.xv-layer-output').getAttribute('src');")
            check("?v=" in (src or ""), "the output image was not asked for anew: %s" % src)

            # 2. A syntax error: the message with its source line and caret, on the page and the console.
            rounds = watch.rounds()
            edit(project, "float NoV = saturate(dot(n, v));", "float NoV = saturate(dot(n, v)) +;")
            check(wait_for_update(browser, 2), "the page did not update after the syntax error:\n" + watch.text())
            message = browser.js("return [...document.querySelectorAll('pre.message')].map((e) => e.textContent).join('\\n');")
            check("clear_coat.hlsl:33:" in message and "error: expected an expression" in message,
                  "the page does not show the compile error: %r" % message)
            lines = message.splitlines()
            source_line = next((i for i, line in enumerate(lines) if "saturate(dot(n, v)) +;" in line), None)
            if check(source_line is not None and source_line + 1 < len(lines), "no source line under the error: %r" % message):
                caret = lines[source_line + 1]
                check(caret.strip() == "^" and caret.index("^") == lines[source_line].index(";"),
                      "the caret is not under the ';':\n%s\n%s" % (lines[source_line], caret))
            check(watch.wait_for(r"error: expected an expression", watch.err) is not None,
                  "watch's console does not show the error:\n" + watch.text())
            check(watch.wait_for(r"^round %d " % (rounds + 1), watch.out) is not None and watch.process.poll() is None,
                  "watch did not go on after the error:\n" + watch.text())

            # 3. Fixed: the images again, in the view the author left.
            edit(project, "float NoV = saturate(dot(n, v)) +;", "float NoV = saturate(dot(n, v));")
            check(wait_for_update(browser, 3), "the page did not update after the fix:\n" + watch.text())
            fixed = view_of(browser)
            check(fixed == before, "the view after the fix: %s, before the error %s" % (fixed, before))

            # 4. A page opened while the shader does not compile has no viewer; once fixed, it has.
            edit(project, "float NoV = saturate(dot(n, v));", "float NoV = saturate(dot(n, v)) +;")
            check(wait_for_update(browser, 4), "the page did not update after the second error:\n" + watch.text())
            browser.driver.get(address + SCENE + ".html")
            check(not browser.groups(), "the page of a shader that does not compile shows images")
            browser.js("window.sameDocument = true;")
            edit(project, "float NoV = saturate(dot(n, v)) +;", "float NoV = saturate(dot(n, v));")
            check(wait_for_update(browser, 1), "the page opened on the error did not update after the fix:\n" + watch.text())
            check(browser.js("return window.sameDocument === true;") and len(browser.groups()) > 0,
                  "the page opened on the error shows no images after the fix")
            problems = browser.console_problems()
            check(not problems, "console errors or warnings: %s" % [p["message"] for p in problems])
    finally:
        if watch.process.poll() is None:
            watch.process.send_signal(signal.SIGINT)
        try:
            code = watch.process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            watch.process.kill()
            code = None
        check(code == 128 + signal.SIGINT, "watch ended with %s on Ctrl-C, not 130:\n%s" % (code, watch.text()))
        left = subprocess.run(["pgrep", "-f", "xshade worker.*%s" % args.work], capture_output=True, text=True).stdout
        check(not left.strip(), "workers left behind: %s" % left)
    if failures:
        print("%d check(s) failed" % len(failures))
        sys.exit(1)
    print("watch in the browser: edit, error and fix shown in place, the view kept")


if __name__ == "__main__":
    main()

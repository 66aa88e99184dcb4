#!/usr/bin/env python3
"""Save to new image: how long `xshade watch` takes from a material's save to the event that tells
open pages the new image is there, against the scene's render floor.

    tests/bench/watch_latency.py --xshade build/xshade --scene-benchmark build/tests/bench/scene_benchmark [--edits 5]

For the example project (examples/user_project, its paint_samples scene) and three fixed scenes
(toon_vs_standard, material_grid, dof_on_43), each in a folder of its own with a fresh shader
cache: `xshade watch SCENE --lane gl -j 1` starts, and the material's last `return X;` is saved
again as `return (X) * F;` with a new F each time (1.0001, 1.0002, ...), so that every save is a
program neither xshade's cache nor Mesa's has seen. The time is from the rename that saves the file
to the server-sent event on /events; the median of --edits saves is printed.

The floor is what scene_benchmark measures for the scene on gl: compiling its variants with no
cache plus the first frame (in which llvmpipe compiles the new program), the median of five runs. The goal is the floor
times 1.5 plus 100 ms. A second column runs every lane (-j 2) for information: three lanes share
two cores there, so it has no goal of its own.
"""

import argparse
import json
import os
import re
import shutil
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
RETURN = re.compile(r"^(\s*)return (.*);\s*$")


class Watch:
    def __init__(self, command, cwd):
        self.process = subprocess.Popen(command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        self.address = None
        for line in self.process.stdout:
            if line.startswith("round 1 "):
                self.address = re.search(r"127\.0\.0\.1:(\d+)", line).group(1)
                break
        if self.address is None:
            raise SystemExit("xshade watch did not finish its first round: %s" % " ".join(command))
        threading.Thread(target=lambda: [None for _ in self.process.stdout], daemon=True).start()
        self.events = []
        self.arrived = threading.Condition()
        threading.Thread(target=self.listen, daemon=True).start()

    def listen(self):
        # A plain socket: each event comes as one chunk of the chunked reply, and its "data: " line
        # is read as soon as it arrives (http.client's reader waits to fill its buffer).
        connection = socket.create_connection(("127.0.0.1", int(self.address)))
        connection.sendall(b"GET /events HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        pending = b""
        while True:
            received = connection.recv(65536)
            if not received:
                return
            pending += received
            *lines, pending = pending.split(b"\n")
            for line in lines:
                if line.startswith(b"data: "):
                    with self.arrived:
                        self.events.append((time.monotonic(), json.loads(line[6:])))
                        self.arrived.notify_all()

    def next_event(self, after, timeout=120):
        with self.arrived:
            self.arrived.wait_for(lambda: any(e[1]["round"] > after for e in self.events), timeout)
            return next(((t, e) for t, e in self.events if e["round"] > after), None)

    def stop(self):
        self.process.send_signal(signal.SIGINT)
        self.process.wait(timeout=60)


def save_with_factor(material, text, index, factor):
    lines = text.splitlines(keepends=True)
    match = RETURN.match(lines[index])
    lines[index] = "%sreturn (%s) * %s;\n" % (match.group(1), match.group(2), factor)
    saved = material.with_name("." + material.name + ".saving")
    saved.write_text("".join(lines))
    os.replace(saved, material)


def measure(xshade, case, lanes, jobs, edits, work):
    material = work / case["material"]
    text = material.read_text()
    index = max(i for i, line in enumerate(text.splitlines()) if RETURN.match(line))
    command = [str(xshade), "watch", case["scene"], "--port", "0", "--cache", str(work / "cache"),
               "--report", str(work / "report"), "-j", str(jobs)] + case["arguments"]
    if lanes:
        command += ["--lane", lanes]
    watch = Watch(command, case["cwd"])
    times = []
    try:
        for edit in range(edits):
            seen = watch.events[-1][1]["round"] if watch.events else 1
            started = time.monotonic()
            save_with_factor(material, text, index, "%.4f" % (1.0 + (edit + 1) * 1e-4 + jobs * 1e-3))
            arrived = watch.next_event(seen)
            if arrived is None:
                raise SystemExit("no event after a save of %s" % material)
            times.append((arrived[0] - started) * 1000)
    finally:
        watch.stop()
        material.write_text(text)
    return statistics.median(times)


def floor_ms(scene_benchmark, case, runs=5):
    """The median of `runs` measurements: a first frame's time varies by a third from run to run."""
    floors = []
    for _ in range(runs):
        command = [str(scene_benchmark), "1"] + case["floor_arguments"]
        table = subprocess.run(command, capture_output=True, text=True, check=True).stdout
        row = next((cells for cells in ([c.strip() for c in line.strip("|").split("|")] for line in table.splitlines())
                    if len(cells) > 5 and cells[1] == "gl"), None)
        if row is None:
            raise SystemExit("scene_benchmark gave no gl row for %s:\n%s" % (case["scene"], table))
        floors.append(float(row[3]) + float(row[5]))
    return statistics.median(floors)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--xshade", type=Path, required=True)
    parser.add_argument("--scene-benchmark", type=Path, required=True)
    parser.add_argument("--edits", type=int, default=5)
    args = parser.parse_args()
    xshade = args.xshade.resolve()
    root = Path(tempfile.mkdtemp(prefix="xshade-watch-latency-"))
    try:
        cases = []
        project = root / "example"
        shutil.copytree(SOURCE / "examples" / "user_project", project)
        cases.append({"name": "example project: paint_samples", "scene": "paint_samples", "cwd": project,
                      "work": project, "material": Path("shaders/materials/clear_coat.hlsl"), "arguments": [],
                      "floor_arguments": ["--shaders", str(project / "shaders"),
                                          str(project / "xshade/scenes/paint_samples.toml")]})
        for scene, material in (("toon_vs_standard", "toon.hlsl"), ("material_grid", "standard_pbr.hlsl"),
                                ("dof_on_43", "standard_pbr.hlsl")):
            work = root / scene
            (work / "shaders" / "materials").mkdir(parents=True)
            shutil.copy(SOURCE / "shaders" / "materials" / material, work / "shaders" / "materials")
            cases.append({"name": scene, "scene": scene, "cwd": work, "work": work,
                          "material": Path("shaders/materials") / material,
                          "arguments": ["--scenes", str(SOURCE / "scenes"), "--golden", str(SOURCE / "golden"),
                                        "--shaders", str(work / "shaders"), "--no-project"],
                          "floor_arguments": ["--shaders", str(work / "shaders"),
                                              str(SOURCE / "scenes" / (scene + ".toml"))]})
        print("| scene | floor on gl (ms) | goal (ms) | save to new image, gl (ms) | met | every lane, -j 2 (ms) |")
        print("|---|---|---|---|---|---|")
        for case in cases:
            floor = floor_ms(args.scene_benchmark, case)
            goal = floor * 1.5 + 100
            gl = measure(xshade, case, "gl", 1, args.edits, case["work"])
            every = measure(xshade, case, None, 2, args.edits, case["work"])
            print("| %s | %.0f | %.0f | %.0f | %s | %.0f |" % (case["name"], floor, goal, gl, "yes" if gl <= goal else "NO",
                                                            every))
            sys.stdout.flush()
    finally:
        shutil.rmtree(root, ignore_errors=True)


if __name__ == "__main__":
    main()

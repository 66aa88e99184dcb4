#!/usr/bin/env python3
"""What a gated run costs against what it must do: figures to read, not a test to pass.

    python3 tests/bench/gate_benchmark.py [--build build] [--warm 3] [--rounds 5]

Measured in one invocation, by the same build:
  floor   every fixed scene on every lane rendered twice (a run renders each twice) at the
          steady-state speed of scene_benchmark: draw and read-back, pipelines already built,
          the sum of 2 x the median render. What no run on these drivers can go below, one core.
  cold    `xshade run` of every fixed scene and lane with its report, every cache empty (the
          compiled-shader cache and the drivers' own in it).
  warm    the same again with the caches the cold run filled: the median of --warm runs.
Each run as wall seconds and as a multiple of the floor, with the CPU seconds of xshade and its
workers and the largest resident memory of any one of them; then the compiler's share, from
compile_benchmark: xshade's front end and GLSL emission, and its full path to SPIR-V, against
glslang compiling the same sources through its own HLSL front end.
"""

import argparse
import json
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def floor_seconds(build, rounds):
    table = subprocess.run([str(build / "tests/bench/scene_benchmark"), str(rounds)], capture_output=True, text=True,
                           check=True).stdout
    renders = []
    for line in table.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 8 and re.fullmatch(r"[\d.]+", cells[6]):
            renders.append(float(cells[6]))
    if not renders:
        sys.exit("gate_benchmark: scene_benchmark printed no render medians:\n" + table)
    return 2 * sum(renders) / 1000.0, len(renders)


def timed_run(build, cache, report):
    """Wall seconds, CPU seconds of xshade and its workers, largest resident memory (MiB)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    run = subprocess.run([str(build / "xshade"), "run", "--cache", str(cache), "--report", str(report)],
                         capture_output=True, text=True, cwd=REPO)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if run.returncode != 0:
        sys.exit("gate_benchmark: xshade run failed (%d):\n%s%s" % (run.returncode, run.stdout, run.stderr))
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, after.ru_maxrss / 1024.0


def compiler_share(build):
    out = subprocess.run([str(build / "tests/bench/compile_benchmark"), "--benchmark_format=json",
                          "--benchmark_repetitions=5", "--benchmark_report_aggregates_only=true"],
                         capture_output=True, text=True, check=True).stdout
    medians = {b["run_name"]: b["real_time"] for b in json.loads(out)["benchmarks"] if b.get("aggregate_name") == "median"}
    glslang = medians["GlslangHlslToSpirv"]
    return medians["FrontEndAndEmission"] / glslang, medians["FullPathToSpirv"] / glslang, medians


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", type=Path, default=REPO / "build")
    parser.add_argument("--warm", type=int, default=3, help="warm runs (their median is reported)")
    parser.add_argument("--rounds", type=int, default=5, help="scene_benchmark's renders per scene and lane")
    args = parser.parse_args()
    build = args.build.resolve()

    floor, lanes = floor_seconds(build, args.rounds)
    work = Path(tempfile.mkdtemp(prefix="xshade-gate-bench-"))
    try:
        cold = timed_run(build, work / "cache", work / "cold")
        warm_runs = [timed_run(build, work / "cache", work / "warm") for _ in range(args.warm)]
    finally:
        shutil.rmtree(work, ignore_errors=True)
    warm = tuple(statistics.median(run[i] for run in warm_runs) for i in range(3))
    front_end, full_path, medians = compiler_share(build)

    print("cores: %d; %d scene-and-lane renders" % (len(os.sched_getaffinity(0)), lanes))
    print("| run | wall (s) | x floor | CPU (s) | peak RSS (MiB) |")
    print("|---|---|---|---|---|")
    print("| floor (2 steady renders each) | %.2f | 1.00 | | |" % floor)
    for name, (wall, cpu, rss) in (("cold (empty caches)", cold), ("warm (median of %d)" % args.warm, warm)):
        print("| %s | %.2f | %.2f | %.2f | %.0f |" % (name, wall, wall / floor, cpu, rss))
    print()
    print("compiler, median of 5 (ms): front end + emission %.2f, full path to SPIR-V %.2f, glslang HLSL %.2f"
          % (medians["FrontEndAndEmission"], medians["FullPathToSpirv"], medians["GlslangHlslToSpirv"]))
    print("front end + emission = %.2f x glslang-HLSL; full path = %.2f x glslang-HLSL" % (front_end, full_path))


if __name__ == "__main__":
    main()

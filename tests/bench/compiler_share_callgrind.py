#!/usr/bin/env python3
"""The compiler's share of glslang's HLSL front end, in instructions (callgrind), not seconds.

    python3 tests/bench/compiler_share_callgrind.py [build/tests/bench/compile_benchmark]

Wall time on a shared two-core machine moves by a third between runs; instruction counts repeat
to a fraction of a percent, so this is the figure to follow while making the front end faster.
Runs compile_benchmark's FrontEndAndEmission and GlslangHlslToSpirv under callgrind and prints
the instructions per compile of the shader library's variants (xshade's front end and GLSL
emission for one flavour; glslang's HLSL front end to SPIR-V for both stages), and their ratio.
Instructions are not time (cache misses and branch mispredictions differ), so the closing
figure is still the benchmark's own time; this one says where the instructions go.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

BENCHMARK = sys.argv[1] if len(sys.argv) > 1 else "build/tests/bench/compile_benchmark"


def profile(filter_name):
    out = tempfile.NamedTemporaryFile(prefix="compiler_share.", suffix=".callgrind", delete=False).name
    subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out, BENCHMARK,
                    "--benchmark_filter=^" + filter_name + "$", "--benchmark_min_time=0.05"],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    tree = subprocess.run(["callgrind_annotate", "--tree=caller", "--inclusive=yes", "--threshold=100", out],
                          check=True, capture_output=True, text=True).stdout
    os.unlink(out)
    return tree.splitlines()


def per_round(lines, round_function):
    """The inclusive instructions of one timed round (every variant of the shader library once):
    the round function's calls from anywhere but the warm-up, over their number. The warm-up pays
    the one-off costs (glslang's built-in symbol tables, the front end's prelude) that the timed
    iterations do not."""
    body = "(anonymous namespace)::" + round_function + "("
    for index, line in enumerate(lines):
        match = re.match(r"\s*([\d,]+) \([^)]*\)\s+\*\s+\S*?:(.*)", line)
        if not match or not match.group(2).startswith(body):
            continue
        instructions = calls = 0
        back = index - 1
        while back >= 0 and "<" in lines[back]:
            caller = re.match(r"\s*([\d,]+) \([^)]*\)\s+<\s+\S*?:(.*) \(([\d,]+)x\)", lines[back])
            if caller and "warm_up" not in caller.group(2):
                instructions += int(caller.group(1).replace(",", ""))
                calls += int(caller.group(3).replace(",", ""))
            back -= 1
        if calls == 0:
            sys.exit(f"{round_function} ran only as the warm-up: give the benchmark more time")
        return instructions / calls
    sys.exit(f"no {round_function} in the profile")


def main():
    if not shutil.which("valgrind") or not shutil.which("callgrind_annotate"):
        sys.exit("compiler_share_callgrind.py needs valgrind (Debian: apt-get install valgrind)")
    ours = per_round(profile("FrontEndAndEmission"), "front_end_and_emission_round")
    theirs = per_round(profile("GlslangHlslToSpirv"), "glslang_hlsl_round")
    print(f"front end + emission  {ours / 1e6:8.2f} M instructions a round (9 variants)")
    print(f"glslang-HLSL          {theirs / 1e6:8.2f} M instructions a round")
    print(f"share                 {ours / theirs:8.3f}")


main()

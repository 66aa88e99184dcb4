#!/usr/bin/env python3
"""Where a CTest run's time went: per label, per suite and the slowest tests.

    python3 tests/bench/ctest_times.py [BUILD_DIR] [--junit FILE] [--slowest N]

Reads CTest's own timing of the last run in BUILD_DIR (Testing/Temporary/LastTest.log), or the
JUnit file of `ctest --output-junit FILE` (which also holds the run's wall time), and each test's
labels from `ctest --show-only=json-v1`. A suite is what a test's name holds before its first
'.': a GoogleTest suite ("Lexer", "Cases/StabilityCase") or a group of script tests ("scene",
"corpus"). A test with several labels counts under each.
"""
import argparse
import collections
import json
import re
import subprocess
import sys
import xml.etree.ElementTree as ElementTree
from pathlib import Path


def times_from_last_test_log(path):
    """{test name: seconds} from CTest's LastTest.log."""
    times, name = {}, None
    for line in path.read_text(errors="replace").splitlines():
        match = re.match(r"^\d+/\d+ Test: (.+)$", line)
        if match:
            name = match.group(1)
            continue
        match = re.match(r"^Test time =\s*([0-9.]+) sec", line)
        if match and name is not None:
            times[name] = float(match.group(1))
            name = None
    return times, None


def times_from_junit(path):
    """{test name: seconds} and the run's wall time from CTest's JUnit output."""
    root = ElementTree.parse(path).getroot()
    suites = [root] if root.tag == "testsuite" else root.findall("testsuite")
    times, wall = {}, 0.0
    for suite in suites:
        wall += float(suite.get("time", "0"))
        for case in suite.iter("testcase"):
            times[case.get("name")] = float(case.get("time", "0"))
    return times, wall or None


def labels_of(build_dir):
    """{test name: [labels]} as CTest lists them. Listing rewrites Testing/Temporary/LastTest.log
    (as an empty run), so the log is put back as it was: this script can read it again."""
    log = Path(build_dir) / "Testing" / "Temporary" / "LastTest.log"
    kept = log.read_bytes() if log.is_file() else None
    try:
        listed = subprocess.run(["ctest", "--test-dir", str(build_dir), "--show-only=json-v1"], capture_output=True,
                                text=True, check=True)
    finally:
        if kept is not None:
            log.write_bytes(kept)
    labels = {}
    for test in json.loads(listed.stdout).get("tests", []):
        found = []
        for prop in test.get("properties", []):
            if prop.get("name") == "LABELS":
                found = list(prop.get("value", []))
        labels[test["name"]] = found or ["(none)"]
    return labels


def table(title, rows, total):
    print(f"\n{title}")
    print(f"| {'':40} | tests | seconds | share |")
    print(f"|{'-' * 42}|-------|---------|-------|")
    for key, (count, seconds) in rows:
        share = 100.0 * seconds / total if total else 0.0
        print(f"| {key[:40]:40} | {count:5} | {seconds:7.1f} | {share:4.1f}% |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("build_dir", nargs="?", default="build", type=Path)
    parser.add_argument("--junit", type=Path, help="CTest's --output-junit file instead of LastTest.log")
    parser.add_argument("--slowest", type=int, default=20, help="how many of the slowest tests to list")
    args = parser.parse_args()

    if args.junit:
        times, wall = times_from_junit(args.junit)
    else:
        log = args.build_dir / "Testing" / "Temporary" / "LastTest.log"
        if not log.is_file():
            sys.exit(f"ctest_times: {log} not found: run ctest in {args.build_dir} first, or give --junit FILE")
        times, wall = times_from_last_test_log(log)
    if not times:
        sys.exit("ctest_times: the run holds no test times")
    labels = labels_of(args.build_dir)

    total = sum(times.values())
    wall_text = f", {wall:.1f} s wall" if wall else ""
    print(f"{len(times)} tests, {total:.1f} s of test time summed{wall_text}")

    per_label = collections.defaultdict(lambda: [0, 0.0])
    per_suite = collections.defaultdict(lambda: [0, 0.0])
    for name, seconds in times.items():
        for label in labels.get(name, ["(not listed now)"]):
            per_label[label][0] += 1
            per_label[label][1] += seconds
        suite = per_suite[name.split(".", 1)[0]]
        suite[0] += 1
        suite[1] += seconds
    by_time = lambda item: -item[1][1]
    table("Per label", sorted(per_label.items(), key=by_time), total)
    table("Per suite (the 25 largest)", sorted(per_suite.items(), key=by_time)[:25], total)
    print(f"\nThe {args.slowest} slowest tests")
    for name, seconds in sorted(times.items(), key=lambda item: -item[1])[:args.slowest]:
        print(f"{seconds:8.1f} s  {name}")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Every C++ source of the project is as the pinned format (.clang-format) writes it.

Runs the given clang-format (Debian 12's clang-format-14: another version formats some constructs
otherwise) over every .cpp and .h file outside build trees, without changing any, and exits 1
naming each file it would change, with the command that formats them. Exit 77 (CTest's skip)
when that clang-format is not installed (`./bootstrap deps` installs it).

Usage: format_check.py CLANG_FORMAT SOURCE_DIR
"""
import concurrent.futures
import os
import pathlib
import shutil
import subprocess
import sys

SKIP = {".git"}
# Files per clang-format process: few processes, but enough of them to use every core.
BATCH = 40


def sources(root: pathlib.Path):
    for path in sorted(root.rglob("*")):
        relative = path.relative_to(root)
        if path.suffix in (".cpp", ".h") and not any(part in SKIP or part.startswith("build") for part in relative.parts):
            yield relative.as_posix()


def unformatted(clang_format: str, root: pathlib.Path, files: list) -> list:
    """The files of `files` that clang-format would change (its --dry-run warnings name them)."""
    done = subprocess.run([clang_format, "--dry-run", "--Werror", "--style=file"] + files, cwd=root,
                          capture_output=True, text=True)
    if done.returncode == 0:
        return []
    named = {line.split(":", 1)[0] for line in done.stderr.splitlines() if ": error: code should be clang-formatted" in line}
    if not named:  # not a formatting verdict: clang-format itself failed
        raise RuntimeError(done.stderr.strip() or f"{clang_format} exited {done.returncode}")
    return sorted(named)


def main():
    if len(sys.argv) != 3:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    clang_format, root = sys.argv[1], pathlib.Path(sys.argv[2])
    if not shutil.which(clang_format):
        print(f"format: {clang_format} is not installed (./bootstrap deps installs it); not checked")
        return 77
    files = list(sources(root))
    batches = [files[i:i + BATCH] for i in range(0, len(files), BATCH)]
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        found = sorted(sum(pool.map(lambda batch: unformatted(clang_format, root, batch), batches), []))
    for path in found:
        print(f"{path}: not as .clang-format writes it")
    if found:
        print(f"format it: {pathlib.Path(clang_format).name} -i " + " ".join(found))
    print(f"format: {len(files)} files, {len(found)} not formatted")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())

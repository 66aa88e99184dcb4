#!/usr/bin/env python3
"""No source file grows past about 900 lines without saying why.

A .cpp or .h file of the project over LIMIT lines must carry a comment line that starts with
"// Why this file is long:" and gives the reason; the check lists every file that does not
(path: lines) and exits 1.

Usage: file_sizes.py SOURCE_DIR
"""
import pathlib
import sys

LIMIT = 900
MARKER = "// Why this file is long:"
# Folders that are not the project's own sources (build trees, fetched code).
SKIP = {"build", ".git"}


def main():
    if len(sys.argv) != 2:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    root = pathlib.Path(sys.argv[1])
    long_files, unexplained = 0, []
    for path in sorted(root.rglob("*")):
        relative = path.relative_to(root)
        if path.suffix not in (".cpp", ".h") or any(part in SKIP or part.startswith("build") for part in relative.parts):
            continue
        lines = path.read_text(errors="replace").splitlines()
        if len(lines) <= LIMIT:
            continue
        long_files += 1
        if not any(line.lstrip().startswith(MARKER) for line in lines):
            unexplained.append(f"{relative.as_posix()}: {len(lines)} lines, and no '{MARKER}' comment")
    for line in unexplained:
        print(line)
    print(f"file_sizes: {long_files} files over {LIMIT} lines, {len(unexplained)} without a reason")
    return 1 if unexplained else 0


if __name__ == "__main__":
    sys.exit(main())

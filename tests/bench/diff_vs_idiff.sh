#!/usr/bin/env bash
# xshade diff against OpenImageIO's idiff, process to process, on the same pairs of float images:
# MPixel/s for both (pixels of one image over the mean wall time of a whole comparison, reading
# both files included) and their ratio. Figures to read, not a test to pass.
#
#   tests/bench/diff_vs_idiff.sh [XSHADE] [RUNS]     (default build/xshade, 10 runs)
#
# The pairs are made here with oiiotool: uniform noise in [0, 1.5] as float RGBA EXR (zip), and
# the same image plus 0.002, so that every pixel differs, a third of the values are above 1 and
# every layer of xshade's comparison has work to do. Needs hyperfine and openimageio-tools.
set -euo pipefail
cd "$(dirname "$0")/../.."
xshade="$(realpath "${1:-build/xshade}")"
runs="${2:-10}"
for tool in hyperfine idiff oiiotool python3; do
  command -v "$tool" >/dev/null || { echo "diff_vs_idiff.sh: needs $tool (Debian: hyperfine, openimageio-tools)" >&2; exit 2; }
done
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

printf '%-10s %14s %14s %8s\n' "size" "xshade MPix/s" "idiff MPix/s" "ratio"
for size in 512 2048; do
  a="$work/a$size.exr" b="$work/b$size.exr"
  oiiotool --pattern noise:type=uniform:min=0:max=1.5 "${size}x${size}" 4 -d float -o "$a"
  oiiotool "$a" --addc 0.002 -d float -o "$b"
  # Both exit non-zero on these differing images; -i keeps hyperfine timing them.
  hyperfine --style none -i -w 2 -r "$runs" --export-json "$work/$size.json" \
    "$xshade diff $a $b" "idiff $a $b" >/dev/null 2>&1
  python3 - "$work/$size.json" "$size" <<'PY'
import json, sys
results = json.load(open(sys.argv[1]))["results"]
pixels = int(sys.argv[2]) ** 2 / 1e6
xshade, idiff = (pixels / r["mean"] for r in results)
print("%-10s %14.2f %14.2f %8.2f" % ("%sx%s" % (sys.argv[2], sys.argv[2]), xshade, idiff, xshade / idiff))
PY
done

#!/usr/bin/env python3
"""Corpus execution: every fragment entry of the real-world corpus (../shared/realworld) that
xshade and glslang's HLSL front end compile is run by `xshade eval --seed` on gl, vk and vk-hlsl, with the same deterministic
inputs on each lane (constant buffers from the seed in ranges shaders mean, seeded noise of each
texture's declared shape and texel kind, depth textures in (0, 1), every varying fed uv), and the
three images are compared.

Two images agree when, at the pixel where they differ most, the difference is at most
max(ABS, REL * |value|) (ABS = 1e-3, REL = 1e-4 by default), or both are bit-identical. Why those
numbers: every lane runs on llvmpipe's LLVM code generator; what differs is the way there
(xshade's GLSL through Mesa's GLSL compiler, the same GLSL through glslang and Mesa's SPIR-V
reader, or glslang's own HLSL front end), which orders, fuses and contracts float operations
differently: a few ulps an operation, and 1e-4 is about 800 ulps of a float, what a shader-length
chain of such roundings stays well within. A disagreement beyond that is a wrong result on some
lane, and is traced (the eval command printed with it, run by hand without --no-images, writes
each lane's EXR) and fixed, or listed in docs/divergences.md with its entry id. The runner itself
asks for no images: it reads only the comparisons, and an eval that writes none never loads the
image library (a quarter of each entry's time).

usage: execute_corpus.py --xshade XSHADE [--corpus DIR] [--out DIR] [--seed N] [--size WxH] [-j N]
                         [--only SUBSTR] [--divergences docs/divergences.md] [--require FRACTION]
Entries run -j at a time (default: one per core); what is printed and written is in the corpus's
order whatever N is.
The last line printed is `corpus execution: N of M entries agree on gl, vk and vk-hlsl`. With
--require, the exit code is 1 when fewer than that fraction agree or when an entry that does not
agree is missing from the divergences file; 0 otherwise.
"""
import argparse
import concurrent.futures
import json
import os
import re
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_CORPUS = os.path.normpath(os.path.join(HERE, '..', '..', '..', 'shared', 'realworld', 'corpus'))
TIMEOUT = 60  # one entry: three compiles and three renders of a small image; 10 s is typical on 2 cores

COMPARE_RE = re.compile(r'^(\S+) vs (\S+): (?:(bit-identical)|max difference (\S+) at \((\d+), (\d+)\) channel (\w): (\S+) vs (\S+))$')
FAIL_RE = re.compile(r'^(gl|vk|vk-hlsl): (failed|unavailable): (.*)$')


def agree(difference, a, b, absolute, relative):
    if difference != difference:  # NaN on one side only
        return False
    scale = max(abs(x) for x in (a, b) if x == x) if (a == a or b == b) else 0.0
    return difference <= max(absolute, relative * scale)


def run_entry(xshade, corpus, entry, out, seed, size):
    folder = os.path.join(out, entry['id'])
    os.makedirs(folder, exist_ok=True)
    cmd = [xshade, 'eval', os.path.join(corpus, entry['wrapper']), '--entry', entry['entry'], '--size', size,
           '--seed', str(seed), '-o', folder, '--no-images']
    for include in entry['include_dirs']:
        cmd += ['-I', os.path.join(corpus, include)]
    for keyword in entry.get('keywords', []):
        cmd += ['-D', keyword]
    started = time.time()
    try:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=TIMEOUT)
        text = (p.stdout + p.stderr).decode('utf-8', 'replace')
        return dict(rc=p.returncode, out=text, secs=time.time() - started, cmd=cmd)
    except subprocess.TimeoutExpired:
        return dict(rc=None, out='timed out after %d s' % TIMEOUT, secs=time.time() - started, cmd=cmd)


def glslang_accepts(corpus, entry, folder):
    """glslang's own HLSL front end compiles the entry (glslangValidator -D -V): without that the
    vk-hlsl lane cannot run it, and run_corpus.py leaves it out of its denominator too."""
    cmd = ['glslangValidator', '-D', '-V', '-S', 'frag', '-e', entry['entry']]
    cmd += ['-I' + os.path.join(corpus, d) for d in entry['include_dirs']]
    cmd += ['-D' + k for k in entry.get('keywords', [])]
    os.makedirs(folder, exist_ok=True)
    cmd += [os.path.join(corpus, entry['wrapper']), '-o', os.path.join(folder, 'glslang.spv')]
    try:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        return False
    return p.returncode == 0 and b'Entry point not found' not in p.stdout


def judge(result, absolute, relative):
    """(verdict, detail): verdict is 'agree', 'differ', 'compile' (xshade refuses it: not counted),
    'no-colour' (writes SV_Depth alone: not counted) or 'fail' (compiles, but a lane cannot run it)."""
    if result['rc'] is None:
        return 'fail', result['out']
    failures = [m for m in (FAIL_RE.match(l) for l in result['out'].splitlines()) if m]
    comparisons = [m for m in (COMPARE_RE.match(l) for l in result['out'].splitlines()) if m]
    if result['rc'] == 2 and 'writes no colour' in result['out']:
        return 'no-colour', 'writes SV_Depth alone: no colour to compare'
    if result['rc'] == 2 and not comparisons and not failures:
        first = next((l for l in result['out'].splitlines() if ': error: ' in l), result['out'].strip()[:200])
        return 'compile', first
    if failures:
        return 'fail', '; '.join('%s %s: %s' % (m.group(1), m.group(2), m.group(3)[:300]) for m in failures)
    if len(comparisons) != 2:
        return 'fail', 'expected two lane comparisons in: ' + result['out'][-300:]
    details = []
    ok = True
    for m in comparisons:
        if m.group(3):
            details.append('%s vs %s bit-identical' % (m.group(1), m.group(2)))
            continue
        difference, a, b = float(m.group(4)), float(m.group(8)), float(m.group(9))
        fine = agree(difference, a, b, absolute, relative)
        ok = ok and fine
        details.append('%s vs %s %g at (%s, %s).%s: %s vs %s' % (m.group(1), m.group(2), difference, m.group(5), m.group(6),
                                                             m.group(7), m.group(8), m.group(9)))
    return ('agree' if ok else 'differ'), '; '.join(details)


def listed_divergences(path):
    if not path or not os.path.exists(path):
        return set()
    return set(re.findall(r'`((?:ppv2|dxs|unity)-[\w.+-]+)`', open(path, encoding='utf-8').read()))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--xshade', required=True)
    ap.add_argument('--corpus', default=DEFAULT_CORPUS)
    ap.add_argument('--out', default=os.path.join(tempfile.gettempdir(), 'xshade-corpus-execution'))
    ap.add_argument('--seed', type=int, default=1)
    ap.add_argument('--size', default='32x32')
    ap.add_argument('--only', default='')
    ap.add_argument('--absolute', type=float, default=1e-3)
    ap.add_argument('--relative', type=float, default=1e-4)
    ap.add_argument('--divergences', default='')
    ap.add_argument('--require', type=float, default=None)
    ap.add_argument('-j', '--jobs', type=int, default=os.cpu_count() or 1, help='entries run at once')
    a = ap.parse_args()

    manifest = json.load(open(os.path.join(a.corpus, 'manifest.json')))
    entries = [e for e in manifest['entries'] if e['stage'] == 'fragment' and a.only in e['id']]
    os.makedirs(a.out, exist_ok=True)

    def execute(entry):
        """(row, line to print) of one entry."""
        if not glslang_accepts(a.corpus, entry, os.path.join(a.out, entry['id'])):
            return (dict(id=entry['id'], verdict='glslang', detail='glslang rejects it', secs=0),
                    'not counted: glslang\'s HLSL front end rejects it')
        result = run_entry(a.xshade, a.corpus, entry, a.out, a.seed, a.size)
        verdict, detail = judge(result, a.absolute, a.relative)
        return (dict(id=entry['id'], verdict=verdict, detail=detail, secs=round(result['secs'], 2), cmd=result['cmd']),
                verdict + ('' if verdict == 'agree' else ' - ' + detail))

    # Each entry is two processes (glslangValidator, xshade eval) that the threads only wait for.
    rows = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        for i, (row, line) in enumerate(pool.map(execute, entries)):
            rows.append(row)
            print('[%d/%d] %s: %s' % (i + 1, len(entries), row['id'], line), flush=True)
    with open(os.path.join(a.out, 'execution.json'), 'w') as f:
        json.dump(rows, f, indent=1)
    with open(os.path.join(a.out, 'execution.tsv'), 'w') as f:
        for row in rows:
            f.write('%s\t%s\t%s\n' % (row['id'], row['verdict'], row['detail']))

    run = [r for r in rows if r['verdict'] not in ('compile', 'glslang', 'no-colour')]
    agreeing = [r for r in run if r['verdict'] == 'agree']
    not_agreeing = [r for r in run if r['verdict'] != 'agree']
    listed = listed_divergences(a.divergences)
    unexplained = [r for r in not_agreeing if r['id'] not in listed]
    rejected = sum(1 for r in rows if r['verdict'] == 'glslang')
    uncompiled = sum(1 for r in rows if r['verdict'] == 'compile')
    if rejected:
        print('not counted: %d entries glslang\'s HLSL front end rejects (no vk-hlsl lane to compare)' % rejected)
    no_colour = sum(1 for r in rows if r['verdict'] == 'no-colour')
    if no_colour:
        print('not counted: %d entries that write no colour (SV_Depth alone), which eval compares' % no_colour)
    if uncompiled:
        print('not counted: %d entries xshade does not compile (the compile corpus, run_corpus.py, tracks them)' % uncompiled)
    for r in unexplained:
        print('not in %s: %s (%s): %s\n  to trace it: %s' % (a.divergences or 'the divergences file', r['id'], r['verdict'],
                                                            r['detail'], ' '.join(r['cmd'][:-1])))
    print('corpus execution: %d of %d entries agree on gl, vk and vk-hlsl' % (len(agreeing), len(run)))
    if a.require is not None:
        if len(run) == 0 or len(agreeing) < a.require * len(run):
            return 1
        if a.divergences and unexplained:
            return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())

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
Entries that share include folders and keywords run in batches, one `xshade eval` of several
files (a driver started once per lane for all of them), -j batches at a time (default: one per
core); what is printed and written is in the corpus's order whatever N is. The command printed
for an entry that does not agree evaluates it alone.
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
TIMEOUT = 60  # one entry: three compiles and three renders of a small image; 1 s is typical on 2 cores
BATCH = 12  # entries in one eval: large enough that starting the drivers is a small part, small enough to spread

COMPARE_RE = re.compile(r'^(\S+) vs (\S+): (?:(bit-identical)|max difference (\S+) at \((\d+), (\d+)\) channel (\w): (\S+) vs (\S+))$')
FAIL_RE = re.compile(r'^(gl|vk|vk-hlsl): (failed|unavailable): (.*)$')


def agree(difference, a, b, absolute, relative):
    if difference != difference:  # NaN on one side only
        return False
    scale = max(abs(x) for x in (a, b) if x == x) if (a == a or b == b) else 0.0
    return difference <= max(absolute, relative * scale)


def eval_command(xshade, corpus, entries, folder, seed, size):
    """`xshade eval` of the wrappers of `entries` (which share their include folders and keywords)
    into `folder`, comparing only; of one entry, with its --entry, the command that traces it."""
    first = entries[0]
    cmd = [xshade, 'eval'] + [os.path.join(corpus, e['wrapper']) for e in entries]
    if len(entries) == 1:
        cmd += ['--entry', first['entry']]
    cmd += ['--size', size, '--seed', str(seed), '-o', folder]
    for include in first['include_dirs']:
        cmd += ['-I', os.path.join(corpus, include)]
    for keyword in first.get('keywords', []):
        cmd += ['-D', keyword]
    return cmd + ['--no-images']


def run_batch(xshade, corpus, batch, out, seed, size):
    """One `xshade eval` of several entries that share their include folders and keywords (each
    wrapper names its fragment entry with #pragma fragment): each lane's worker evaluates them all
    with one driver, which costs less than starting a driver for each. {id: result}: the entry's
    exit code (None when it has none), its lines, its share of the time and the command that
    evaluates it alone."""
    folder = os.path.join(out, 'batches', batch[0]['id'])
    os.makedirs(folder, exist_ok=True)
    started = time.time()
    rc = None
    try:
        p = subprocess.run(eval_command(xshade, corpus, batch, folder, seed, size), stdout=subprocess.PIPE,
                           stderr=subprocess.STDOUT, timeout=TIMEOUT * len(batch))
        text, rc = p.stdout.decode('utf-8', 'replace'), p.returncode
    except subprocess.TimeoutExpired as e:
        text = (e.stdout or b'').decode('utf-8', 'replace')
    secs = round((time.time() - started) / len(batch), 2)
    results = {}
    for e in batch:
        alone = eval_command(xshade, corpus, [e], os.path.join(out, e['id']), seed, size)
        wrapper = re.escape(os.path.join(corpus, e['wrapper']))
        block = re.search(r'^== %s\n(.*?)^== %s: exit (\d+)$' % (wrapper, wrapper), text, re.S | re.M)
        if len(batch) == 1:  # one file: eval's lines as they are, its exit code the process's
            code, lines = rc, text if rc is not None else 'timed out after %d s' % TIMEOUT
        elif block:
            code, lines = int(block.group(2)), block.group(1)
        else:
            code, lines = None, 'no result in the batch\'s output (timed out after %d s, or it crashed): %s' % (
                TIMEOUT * len(batch), text[-300:])
        results[e['id']] = dict(rc=code, out=lines, secs=secs, cmd=alone)
    return results


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
    return set(re.findall(r'`((?:ppv2|dxs|unity|vks)-[\w.+-]+)`', open(path, encoding='utf-8').read()))


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

    # glslang's front end first (without it there is no vk-hlsl lane); then the entries it accepts
    # in batches of those that share include folders and keywords, BATCH at most, so that the
    # batches still spread over the jobs.
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        accepted = list(pool.map(lambda e: glslang_accepts(a.corpus, e, os.path.join(a.out, e['id'])), entries))
    groups = {}
    for entry, ok in zip(entries, accepted):
        if ok:
            groups.setdefault((tuple(entry['include_dirs']), tuple(entry.get('keywords', []))), []).append(entry)
    batches = [group[i:i + BATCH] for group in groups.values() for i in range(0, len(group), BATCH)]
    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        for batch_results in pool.map(lambda b: run_batch(a.xshade, a.corpus, b, a.out, a.seed, a.size), batches):
            results.update(batch_results)
    rows = []
    for i, (entry, ok) in enumerate(zip(entries, accepted)):
        if not ok:
            row, line = dict(id=entry['id'], verdict='glslang', detail='glslang rejects it', secs=0), \
                'not counted: glslang\'s HLSL front end rejects it'
        else:
            result = results[entry['id']]
            verdict, detail = judge(result, a.absolute, a.relative)
            row = dict(id=entry['id'], verdict=verdict, detail=detail, secs=result['secs'], cmd=result['cmd'])
            line = verdict + ('' if verdict == 'agree' else ' - ' + detail)
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

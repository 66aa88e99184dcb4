#!/usr/bin/env python3
"""The corpus gate: runs ../shared/realworld/run_corpus.py and fails on any crash, hang or
output its validators reject, and on any entry of passing.txt (the entries that compile to valid
GLSL and SPIR-V) that no longer does. New passes are listed, to be added to passing.txt.

usage: check_corpus.py --runner RUN_CORPUS.PY --xshade XSHADE --passing PASSING.TXT --out DIR [-j N]
"""
import argparse
import json
import os
import subprocess
import sys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--runner', required=True)
    ap.add_argument('--xshade', required=True)
    ap.add_argument('--passing', required=True)
    ap.add_argument('--out', required=True)
    ap.add_argument('-j', '--jobs', type=int, default=os.cpu_count() or 1, help='entries compiled at once')
    a = ap.parse_args()
    run = subprocess.run([sys.executable, a.runner, a.xshade, '--out', a.out, '-j', str(a.jobs)], stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, text=True)
    print(run.stdout, end='')
    if run.returncode != 0:
        print('check_corpus: the runner failed with exit code %d' % run.returncode)
        return 1
    results = json.load(open(os.path.join(a.out, 'results.json')))
    expected = [line.split('#')[0].strip() for line in open(a.passing)]
    expected = {line for line in expected if line}
    problems = []
    passing = set()
    for entry in results:
        ok = all(entry[target].get('ok') for target in ('gl', 'spirv'))
        if ok:
            passing.add(entry['id'])
        for target in ('gl', 'spirv'):
            result = entry[target]
            category = result.get('category', '')
            if category.startswith('crash') or result.get('kind') == 'invalid-output':
                problems.append('%s (%s): %s: %s' % (entry['id'], target, category, result.get('error', '')))
    known = {entry['id'] for entry in results}
    for name in sorted(expected - passing):
        if name not in known:
            problems.append('%s: listed in passing.txt but not in the corpus' % name)
            continue
        entry = next(e for e in results if e['id'] == name)
        why = next((entry[t].get('error', '') for t in ('gl', 'spirv') if not entry[t].get('ok')), '')
        problems.append('%s compiled before and no longer does: %s' % (name, why))
    for name in sorted(passing - expected):
        print('check_corpus: %s now compiles; add it to %s' % (name, a.passing))
    for problem in problems:
        print('check_corpus: FAIL ' + problem)
    print('check_corpus: %d entries compile to valid GLSL and SPIR-V (%d listed), %d problems' %
          (len(passing), len(expected), len(problems)))
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())

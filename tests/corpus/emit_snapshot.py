#!/usr/bin/env python3
"""Every output xshade's compiler makes, written to one folder, so that a change to the compiler's
structure can be shown to change no byte: run it before and after, then `diff -r BEFORE AFTER`.

What it compiles, with `xshade compile` (each output file, and each run's exit code with its
standard output and error, so that a diagnostic that moves counts too):
- the shader library (shaders/materials, shaders/post): every keyword combination the file
  declares, on gl, vk, spirv and vk-hlsl, and on gl, vk and spirv again with --precision half and
  with --trace-nonfinite;
- the real-world corpus (../shared/realworld/corpus): each wrapper on gl, vk, spirv and vk-hlsl,
  and each Unity `.shader` file on gl and vk (every pass);
- the conformance shaders and the fuzz seeds on gl, vk and spirv.

usage: emit_snapshot.py XSHADE OUT [-j N]
The last line printed is `emit_snapshot: N runs, M output files in OUT`.
"""
import argparse
import concurrent.futures
import glob
import json
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, '..', '..'))
CORPUS = os.path.normpath(os.path.join(ROOT, '..', 'shared', 'realworld', 'corpus'))
TARGETS = ('gl', 'vk', 'spirv', 'vk-hlsl')
# The emitter's options that change its output; vk-hlsl is glslang's and takes neither.
OPTION_SETS = (['--precision', 'half'], ['--trace-nonfinite'])


def variants(xshade, path):
    """The keyword combinations `--all-variants` lists for `path`, each as -D arguments."""
    p = subprocess.run([xshade, 'compile', '--all-variants', '--target', 'gl', path],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=ROOT)
    combos = []
    for line in p.stdout.splitlines():
        m = re.match(r'.* \[([^\]]*)\]: ', line)
        if m:
            combos.append(m.group(1).split())
    return combos or [[]]


def runs(xshade):
    """(name, arguments) of every compile."""
    out = []
    for path in sorted(glob.glob(os.path.join(ROOT, 'shaders', 'materials', '*.hlsl')) +
                       glob.glob(os.path.join(ROOT, 'shaders', 'post', '*.hlsl'))):
        stem = os.path.basename(path)[:-5]
        for combo in variants(xshade, path):
            defines = sum([['-D', k] for k in combo], [])
            tag = '+'.join(combo) or 'base'
            for target in TARGETS:
                out.append(('library.%s.%s.%s' % (stem, tag, target), [path, '--target', target] + defines))
            for options in OPTION_SETS:
                for target in TARGETS[:3]:
                    out.append(('library.%s.%s.%s%s' % (stem, tag, target, options[-1]),
                                [path, '--target', target] + options + defines))
    manifest = os.path.join(CORPUS, 'manifest.json')
    if os.path.exists(manifest):
        wrappers = {}
        for e in json.load(open(manifest))['entries']:
            wrappers.setdefault(e['wrapper'], e['include_dirs'])
        for wrapper, includes in sorted(wrappers.items()):
            args = [os.path.join(CORPUS, wrapper)] + sum([['-I', os.path.join(CORPUS, d)] for d in includes], [])
            for target in TARGETS:
                out.append(('corpus.%s.%s' % (os.path.basename(wrapper), target), args + ['--target', target]))
        for path in sorted(glob.glob(os.path.join(CORPUS, '**', '*.shader'), recursive=True)):
            name = os.path.relpath(path, CORPUS).replace('/', '+')
            for target in ('gl', 'vk'):
                out.append(('shaderlab.%s.%s' % (name, target), [path, '--target', target]))
    for path in sorted(glob.glob(os.path.join(ROOT, 'tests', 'conformance', 'shaders', '*.hlsl')) +
                       glob.glob(os.path.join(ROOT, 'tests', 'fuzz', 'seeds', '*.hlsl'))):
        for target in TARGETS[:3]:
            out.append(('%s.%s.%s' % (os.path.basename(os.path.dirname(path)), os.path.basename(path), target),
                        [path, '--target', target]))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('xshade')
    ap.add_argument('out')
    ap.add_argument('-j', type=int, default=os.cpu_count() or 1)
    a = ap.parse_args()
    xshade = os.path.abspath(a.xshade)
    os.makedirs(a.out, exist_ok=True)
    todo = runs(xshade)

    def compile_one(item):
        name, args = item
        base = os.path.join(a.out, name)
        p = subprocess.run([xshade, 'compile', '--no-project', '--shaders', os.path.join(ROOT, 'shaders')] + args +
                           ['-o', base], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, cwd=ROOT, timeout=120)
        # Absolute paths differ between checkouts; the snapshot keeps them relative.
        text = p.stdout.decode('utf-8', 'replace').replace(ROOT + '/', '').replace(CORPUS + '/', '')
        with open(base + '.log', 'w') as f:
            f.write('exit %d\n%s' % (p.returncode, text))

    done = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.j)) as pool:
        for _ in pool.map(compile_one, todo):
            done += 1
            if done % 200 == 0:
                print('emit_snapshot: %d of %d' % (done, len(todo)), file=sys.stderr, flush=True)
    files = sum(1 for f in os.listdir(a.out) if not f.endswith('.log'))
    print('emit_snapshot: %d runs, %d output files in %s' % (len(todo), files, a.out))


if __name__ == '__main__':
    main()

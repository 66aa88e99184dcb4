#!/usr/bin/env python3
"""ShaderLab corpus: every `.shader` file under the real-world corpus (../shared/realworld/corpus),
as Unity ships it, rendered by `xshade run` as the only material of a probe scene (a sphere on a
plane under one directional light) with nothing but its own Properties defaults, on gl, vk and
vk-hlsl, and the three images compared as a scene's lanes always are.

A file written as an image effect (every depth test it sets `ZTest Always`, the manual's `Cull
Off ZWrite Off ZTest Always`: drawn over the whole target whatever the depth) is instead the only
post effect of the probe scene, whose objects then have xshade's Standard-like material: its first
pass blits the scene's image, as Graphics.Blit(source, destination, material) does. A Post
Processing v2 shader (one that includes its StdLib.hlsl) also gets what PPv2's PostProcessLayer
sets before any of its passes: _RenderViewportScaleFactor = 1 (no XR viewport scaling; 0, as
nothing set, samples one texel) and _UVTransform = (1, 1, 0, 0) (no flip).

A file renders when every lane draws an image that is not one flat colour and every pair of lanes
agrees within the scene's default tolerance. Surface shaders (`#pragma surface`), whose passes
xshade generates, are rendered the same way and counted apart.

usage: render_shaderlab.py --xshade XSHADE [--corpus DIR] [--out DIR] [--passing FILE]
                           [--divergences docs/divergences.md] [--only SUBSTR] [-j N]
                           [--platform glcore|d3d11|vulkan]

The last line printed is `shaderlab: K of N .shader files render on every lane and agree`. The
exit code is 1 on a crash or a hang, on a file of the passing list (one corpus path a line) that no
longer renders, and on a disagreement between lanes that the divergences file does not list (by
the file's corpus path in backquotes); 0 otherwise.
"""
import argparse
import json
import os
import re
import struct
import subprocess
import sys
import tempfile
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_CORPUS = os.path.normpath(os.path.join(HERE, '..', '..', '..', 'shared', 'realworld', 'corpus'))
# One scene of 64x64 on three lanes compiles a handful of variants and draws two objects: about a
# second on 2 cores. 60 s is a hang, not a slow machine.
SCENE_TIMEOUT = 60

PROBE_SCENE = '''# Made by render_shaderlab.py: {path} as the only material of a probe scene.
description = "{path}"
size = [64, 64]
# Not black, so that a multiplying or blending material shows over it.
clear_color = [0.2, 0.3, 0.4, 1]

[camera]
position = [0, 1.2, 3]
target = [0, 0, 0]
fov_y = 45
near = 0.3
far = 20

[[light]]
type = "directional"
direction = [-0.5, 0.6, 0.6]

[[object]]
name = "ball"
mesh = "sphere"
material = "{material}"

[[object]]
name = "floor"
mesh = "plane"
material = "{material}"
position = [0, -1, 0]
scale = [4, 1, 4]
'''


# The probe scene for an image effect: the same objects in a material of xshade's, then the file.
POST_SCENE = PROBE_SCENE.replace('material = "{material}"', 'material = "materials/standard_pbr.hlsl"') + \
    '\n[[post]]\neffect = "{material}"\n'

# What PPv2's runtime gives every pass of its own shaders.
PPV2_GLOBALS = '[post.parameters]\n_RenderViewportScaleFactor = 1.0\n_UVTransform = [1, 1, 0, 0]\n'

# A depth test, as a pass or a SubShader states it.
ZTEST = re.compile(r'\bZTest\s+(\w+)', re.I)


def unlit_texture(corpus):
    """Unity's Unlit/Texture (Unlit-Normal.shader) in the corpus, as the scene names it."""
    for root, _, names in os.walk(corpus):
        if 'Unlit-Normal.shader' in names:
            return os.path.relpath(os.path.join(root, 'Unlit-Normal.shader'), corpus)
    raise SystemExit('render_shaderlab: no Unlit-Normal.shader in %s for the objects of a --platform scene' % corpus)


def is_image_effect(text):
    """Whether a .shader's text sets the depth test and every one it sets is Always (a ZTest in a
    SubShader applies to each of its passes)."""
    tests = [t.lower() for t in ZTEST.findall(text)]
    return bool(tests) and all(t == 'always' for t in tests)


def png_pixels(path):
    """The rows of an 8-bit, non-interlaced PNG (what xshade writes) as bytes, and the bytes a
    pixel takes; enough to tell one flat colour from an image."""
    data = open(path, 'rb').read()
    if data[:8] != b'\x89PNG\r\n\x1a\n':
        raise ValueError('%s is not a PNG' % path)
    offset, idat, width, height, channels = 8, b'', 0, 0, 0
    while offset < len(data):
        length, kind = struct.unpack('>I4s', data[offset:offset + 8])
        body = data[offset + 8:offset + 8 + length]
        if kind == b'IHDR':
            width, height, depth, colour, _, _, interlace = struct.unpack('>IIBBBBB', body)
            channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour)
            if depth != 8 or channels is None or interlace:
                raise ValueError('%s: only 8-bit non-interlaced grey or RGB(A) is read here' % path)
        elif kind == b'IDAT':
            idat += body
        offset += 12 + length
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        filter_type = raw[y * (stride + 1)]
        row = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            left = row[x - channels] if x >= channels else 0
            up = previous[x]
            up_left = previous[x - channels] if x >= channels else 0
            if filter_type == 1:
                row[x] = (row[x] + left) & 255
            elif filter_type == 2:
                row[x] = (row[x] + up) & 255
            elif filter_type == 3:
                row[x] = (row[x] + (left + up) // 2) & 255
            elif filter_type == 4:
                p = left + up - up_left
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - up_left)
                row[x] = (row[x] + (left if pa <= pb and pa <= pc else up if pb <= pc else up_left)) & 255
        rows.append(bytes(row))
        previous = row
    return rows, channels


def is_flat(path):
    rows, channels = png_pixels(path)
    first = rows[0][:channels]
    return all(row == first * (len(row) // channels) for row in rows)


def scene_id(relative):
    return re.sub(r'[^A-Za-z0-9]+', '_', os.path.splitext(relative)[0]).strip('_').lower()


def listed_divergences(path):
    if not path or not os.path.exists(path):
        return set()
    return set(re.findall(r'`([^`]+\.shader)`', open(path, encoding='utf-8').read()))


def first_error(message):
    """The first line of a message that says what went wrong (an `error:` line where there is one,
    rather than the line that says a file did not compile)."""
    lines = [line.strip() for line in message.splitlines() if line.strip()]
    return next((line for line in lines if ': error: ' in line), lines[0] if lines else '')


def judge(scene, report):
    """(verdict, detail) of one scene's results: 'render', 'differ', 'flat', 'error' (a lane did
    not render: compile error, missing input, ...), 'crash' or 'hang'."""
    if not scene['lanes']:
        return 'error', first_error(scene['message']) or 'no lane rendered'

    problems = []
    for lane in scene['lanes']:
        if lane['verdict'] == 'crash':
            return 'crash', '%s: %s' % (lane['lane'], lane['message'])
        if 'timed out' in lane['message'] or 'timeout' in lane['message']:
            return 'hang', '%s: %s' % (lane['lane'], lane['message'])
        failing = [l for l in lane['layers'] if l['verdict'] != 'pass' and l['layer'] != 'golden']
        if not lane['image'] or lane['verdict'] == 'error':
            problems.append('%s: %s' % (lane['lane'], first_error(lane['message']) or 'no image'))
        elif failing:
            problems.append('%s: %s' % (lane['lane'], '; '.join('%s %s' % (l['layer'], l['detail']) for l in failing)))
    if problems:
        return 'error', ' | '.join(problems)
    flat = [lane['lane'] for lane in scene['lanes'] if is_flat(os.path.join(report, lane['image']))]
    if flat:
        return 'flat', 'one flat colour on ' + ', '.join(flat)
    # A scene's lane check also fails where an image holds negative values (a hazard for a
    # golden); here the question is whether the lanes agree: the same negative values on each
    # lane, no NaN or Inf and no pixel beyond the tolerance is agreement.
    counts = {json.dumps(lane['non_finite']['negative']) + json.dumps(lane['non_finite']['first']) for lane in scene['lanes']}
    negative_alike = len(counts) == 1 and all(lane['non_finite']['nan'] + lane['non_finite']['inf'] == 0 for lane in scene['lanes'])
    differing = [c for c in scene['cross_lane'] if c['verdict'] != 'pass' and not (
        negative_alike and c['metrics']['steps']['failing_pixels'] == 0 and c['metrics']['above_one']['failing_pixels'] == 0)]
    if differing or len(scene['cross_lane']) < 2:
        return 'differ', '; '.join('%s vs %s: %s' % (c['first_lane'], c['second_lane'], c['verdict']) for c in differing) \
            or 'fewer than two lane comparisons'
    negative = scene['lanes'][0]['non_finite']['negative']
    return 'render', '%d negative channel values on every lane alike' % negative if negative else ''


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--xshade', required=True)
    ap.add_argument('--corpus', default=DEFAULT_CORPUS)
    ap.add_argument('--out', default=os.path.join(tempfile.gettempdir(), 'xshade-shaderlab'))
    ap.add_argument('--passing', default='')
    ap.add_argument('--divergences', default='')
    ap.add_argument('--only', default='')
    ap.add_argument('-j', '--jobs', type=int, default=os.cpu_count() or 1, help='renders at once')
    ap.add_argument('--platform', default='glcore', choices=['glcore', 'd3d11', 'vulkan'],
                    help="the Unity platform the scenes compile and draw as (a scene's [unity] platform)")
    a = ap.parse_args()

    shaders = sorted(os.path.relpath(os.path.join(root, name), a.corpus)
                     for root, _, names in os.walk(a.corpus) for name in names
                     if name.endswith('.shader') and a.only in os.path.join(root, name))
    surface = [s for s in shaders if re.search(r'^\s*#\s*pragma\s+surface\b', open(os.path.join(a.corpus, s),
                                                                                   encoding='utf-8', errors='replace').read(), re.M)]
    drawn = shaders
    scenes_dir, golden_dir, report = (os.path.join(a.out, d) for d in ('scenes', 'golden', 'report'))
    for folder in (scenes_dir, golden_dir):
        os.makedirs(folder, exist_ok=True)
        for old in os.listdir(folder):
            os.remove(os.path.join(folder, old))
    ids = {}
    # The objects of a --platform scene's image effect (below), found once.
    objects_material = unlit_texture(a.corpus) if a.platform != 'glcore' and drawn else ''
    for relative in drawn:
        ids[scene_id(relative)] = relative
        text = open(os.path.join(a.corpus, relative), encoding='utf-8', errors='replace').read()
        post = is_image_effect(text)
        scene = POST_SCENE if post else PROBE_SCENE
        if post and a.platform != 'glcore':
            # A scene of another platform draws .shader files only: the objects in Unity's
            # Unlit/Texture, a checker on each.
            scene = PROBE_SCENE.replace('material = "{material}"', 'material = "%s"\ntextures = {{ _MainTex = \"checker\" }}'
                                        % objects_material) + '\n[[post]]\neffect = "{material}"\n'
        if post and re.search(r'#\s*include\s+"[^"]*StdLib\.hlsl"', text):
            scene += PPV2_GLOBALS
        if a.platform != 'glcore':
            scene = scene.replace('\n[camera]', '\n[unity]\nplatform = "%s"\n\n[camera]' % a.platform, 1)
        with open(os.path.join(scenes_dir, scene_id(relative) + '.toml'), 'w') as f:
            f.write(scene.format(path=relative, material=relative.replace('\\', '/')))

    # Each .shader's folder holds its own includes; Unity's CG include files are a corpus source's
    # CGIncludes folder, found as a user's --shaders folder finds them.
    # A corpus source is a project: its own root is a shader folder (PPv2 includes
    # "Packages/com.unity.postprocessing/..." from there, as Unity resolves package paths).
    sources = sorted(s for s in os.listdir(a.corpus) if os.path.isdir(os.path.join(a.corpus, s)))
    include_folders = [os.path.join(a.corpus, s, 'CGIncludes') for s in sources if os.path.isdir(os.path.join(a.corpus, s, 'CGIncludes'))]
    shader_options = ['--shaders', a.corpus] + sum((['--shaders', folder] for folder in
                                                    include_folders + [os.path.join(a.corpus, s) for s in sources]), [])
    cmd = [a.xshade, 'run', '--no-project', '--scenes', scenes_dir, '--golden', golden_dir, '--report', report,
           '--cache', os.path.join(a.out, 'cache'), '--timeout', str(SCENE_TIMEOUT), '-j', str(max(1, a.jobs))] + shader_options
    rows = []
    if drawn:
        # Every scene fails its golden layer (there are none): the exit code says nothing here,
        # results.json says everything.
        run = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                             timeout=SCENE_TIMEOUT * 3 * len(drawn) + 120)
        results_path = os.path.join(report, 'results.json')
        if not os.path.exists(results_path):
            print(run.stdout[-3000:])
            print('render_shaderlab: xshade run wrote no results (exit code %d): %s' % (run.returncode, ' '.join(cmd)))
            return 1
        results = {s['scene']: s for s in json.load(open(results_path))['scenes']}
        for identifier, relative in sorted(ids.items(), key=lambda item: item[1]):
            scene = results.get(identifier)
            verdict, detail = judge(scene, report) if scene else ('error', 'not in the run\'s results')
            rows.append(dict(path=relative, verdict=verdict, detail=detail))

    with open(os.path.join(a.out, 'shaderlab.tsv'), 'w') as f:
        for row in rows:
            f.write('%s\t%s\t%s\n' % (row['path'], row['verdict'], ' '.join(row['detail'].split())))
    for row in rows:
        print('%s: %s%s' % (row['path'], row['verdict'], ' - ' + row['detail'] if row['detail'] else ''))

    failures = []
    passing_list = set()
    if a.passing:
        passing_list = {line.split('#')[0].strip() for line in open(a.passing)} - {''}
    listed = listed_divergences(a.divergences)
    rendered = {r['path'] for r in rows if r['verdict'] == 'render'}
    for row in rows:
        if row['verdict'] in ('crash', 'hang'):
            failures.append('%s: %s: %s' % (row['path'], row['verdict'], row['detail']))
        elif row['verdict'] == 'differ' and row['path'] not in listed:
            failures.append('%s: the lanes disagree and %s does not list it: %s' % (row['path'], a.divergences or 'no divergences file',
                                                                                   row['detail']))
    for path in sorted(passing_list - rendered):
        if any(r['path'] == path for r in rows) or not a.only:
            failures.append('%s: in %s, but no longer renders' % (path, a.passing))
    new = sorted(rendered - passing_list)
    if a.passing and new:
        print('render now, to be added to %s:\n  %s' % (a.passing, '\n  '.join(new)))
    for failure in failures:
        print('FAIL ' + failure)
    print('surface shaders: %d of %d render on every lane and agree' % (len(rendered & set(surface)), len(surface)))
    print('shaderlab: %d of %d .shader files render on every lane and agree' % (len(rendered - set(surface)),
                                                                               len(drawn) - len(surface)))
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())

#!/usr/bin/env python3
"""Every output validated: `xshade compile` of each wrapper of the real-world corpus for gl, vk and
spirv either exits 0 with an output its validator accepts, or exits non-zero. An exit 0 with an
output glslangValidator (gl: OpenGL GLSL; vk: Vulkan GLSL) or spirv-val (spirv) refuses, with no
output at all, or a crash or a hang, fails the test. Exit 3, xshade's report that its own output
was invalid, is listed but passes: xshade caught it.

The validators here are the command-line tools, not the library xshade validates with, so that
the check does not share xshade's own mistakes. Exits 77 (CTest's skip) when the corpus or a
validator is not here.

usage: validated_outputs.py --xshade XSHADE --corpus CORPUS_DIR --out DIR [-j N]
"""
import argparse
import collections
import concurrent.futures
import json
import os
import shutil
import subprocess
import sys

SKIP = 77  # SKIP_RETURN_CODE in tests/corpus/CMakeLists.txt
TIMEOUT = 30  # seconds for one command, as run_corpus.py allows
TARGETS = ("gl", "vk", "spirv")
STAGES = {"vert": "vertex", "frag": "fragment"}


def run(command, cwd=None):
    try:
        done = subprocess.run(command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=TIMEOUT)
        return done.returncode, done.stdout.decode("utf-8", "replace")
    except subprocess.TimeoutExpired:
        return None, "no answer in %d s" % TIMEOUT
    except OSError as error:  # not there, or not executable (a build relinking it)
        return -1, "cannot run %s: %s" % (command[0], error)


def first_line_with(text, words):
    for line in text.splitlines():
        if any(word in line.lower() for word in words):
            return line.strip()
    return text.strip().splitlines()[0] if text.strip() else "(no message)"


def compile_one(xshade, corpus, out, index, wrapper, include_dirs, target):
    """One compile: (verdict, detail, written files as (stage suffix, path)), the verdict 'ok'
    (exit 0, not yet validated), 'refused' (exit 2), 'internal' (exit 3) or 'problem'."""
    base = os.path.join(out, "w%d.%s" % (index, target))
    command = [xshade, "compile", os.path.join(corpus, wrapper), "--no-project", "--target", target, "-o", base]
    for folder in include_dirs:
        command += ["-I", os.path.join(corpus, folder)]
    code, text = run(command, cwd=out)
    if code is None:
        return "problem", "hang: " + text, []
    if code == 2:
        return "refused", "", []
    if code == 3:
        return "internal", first_line_with(text, ("internal error", "error")), []
    if code != 0:
        return "problem", "exit %s: %s" % (code, first_line_with(text, ("error",))), []
    extension = ".spv" if target == "spirv" else ".glsl"
    written = [(suffix, base + "." + suffix + extension) for suffix in STAGES if os.path.exists(base + "." + suffix + extension)]
    if not written:
        return "problem", "exit 0 without an output file", []
    return "ok", "", written


def refusals_in(said, paths):
    """{path: first error} from glslangValidator's output for several files: it prints each
    file's name before that file's messages."""
    refused, current = {}, None
    for line in said.splitlines():
        if line.strip() in paths:
            current = line.strip()
        elif current and line.startswith("ERROR") and current not in refused:
            refused[current] = line.strip()
    return refused


def refused_gl(paths, stage):
    """{path: first error} for the OpenGL GLSL files glslangValidator refuses. Without -V it checks
    each file on its own, so one run checks many and pays its start-up (its built-in declarations,
    a tenth of a second or two) once."""
    code, said = run(["glslangValidator", "-S", stage] + paths)
    if code == 0:
        return {}
    # A failure it does not put under a file's name leaves every file of the run suspect.
    return refusals_in(said, paths) or {path: first_line_with(said, ("error",)) for path in paths}


def refused_vk(paths, scratch):
    """{path: first error} for the Vulkan GLSL stages of one program (base.vert.glsl and
    base.frag.glsl, each its own stage's, so one run compiles both): compiled to SPIR-V as
    Vulkan 1.3 GLSL, the modules written into `scratch` and left there."""
    os.makedirs(scratch, exist_ok=True)
    code, said = run(["glslangValidator", "-V", "--target-env", "vulkan1.3"] + paths, cwd=scratch)
    if code == 0:
        return {}
    return refusals_in(said, paths) or {path: first_line_with(said, ("error",)) for path in paths}


def refused_spirv(path):
    code, said = run(["spirv-val", "--target-env", "vulkan1.3", path])
    return {} if code == 0 else {path: first_line_with(said, ("error",))}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--xshade", required=True)
    parser.add_argument("--corpus", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("-j", "--jobs", type=int, default=os.cpu_count() or 1)
    args = parser.parse_args()
    manifest = os.path.join(args.corpus, "manifest.json")
    if not os.path.exists(manifest):
        print("validated_outputs: skipped: no corpus at %s" % args.corpus)
        return SKIP
    missing = [tool for tool in ("glslangValidator", "spirv-val") if not shutil.which(tool)]
    if missing:
        print("validated_outputs: skipped: %s not found (Debian packages glslang-tools, spirv-tools)" % ", ".join(missing))
        return SKIP
    # A wrapper names its entries' program (#pragma vertex/fragment), so it is compiled once per
    # target, with the include folders its entries give.
    wrappers = collections.OrderedDict()
    for entry in json.load(open(manifest))["entries"]:
        wrappers.setdefault(entry["wrapper"], entry["include_dirs"])
    # A file an earlier run left would pass for this run's output.
    shutil.rmtree(args.out, ignore_errors=True)
    os.makedirs(args.out)
    xshade = os.path.abspath(args.xshade)
    jobs = [(index, wrapper, include_dirs, target)
            for index, (wrapper, include_dirs) in enumerate(wrappers.items()) for target in TARGETS]
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        compiled = list(pool.map(lambda job: compile_one(xshade, args.corpus, args.out, *job), jobs))
        # Each file an exit 0 wrote, through its validator: the gl files in a few batches (one
        # per job and stage), each vk program in one run, each SPIR-V module in one.
        checks = []
        for suffix in STAGES:
            paths = [path for (_, _, _, target), (_, _, files) in zip(jobs, compiled) if target == "gl"
                     for stage, path in files if stage == suffix]
            size = max(1, -(-len(paths) // max(1, args.jobs)))
            checks += [(refused_gl, paths[at:at + size], suffix) for at in range(0, len(paths), size)]
        for (index, _, _, target), (_, _, files) in zip(jobs, compiled):
            if target == "vk" and files:
                checks.append((refused_vk, [path for _, path in files], os.path.join(args.out, "spv%d" % index)))
            if target == "spirv":
                checks += [(refused_spirv, path) for _, path in files]
        refusals = {}
        for refused in pool.map(lambda check: check[0](*check[1:]), checks):
            refusals.update(refused)
    verdicts = []
    for job, (verdict, detail, files) in zip(jobs, compiled):
        for suffix, path in files:
            if path in refusals and verdict == "ok":
                verdict = "problem"
                detail = "exit 0 with a %s stage that %s refuses: %s" % (
                    STAGES[suffix], "spirv-val" if job[3] == "spirv" else "glslangValidator", refusals[path])
            if path not in refusals:
                os.remove(path)
        verdicts.append((job, (verdict, detail)))

    counts = collections.Counter((job[3], verdict) for job, (verdict, _) in verdicts)
    for target in TARGETS:
        print("validated_outputs: %-5s %3d valid, %3d refused (exit 2), %3d internal errors (exit 3), %d problems" % (
            target, counts[(target, "ok")], counts[(target, "refused")], counts[(target, "internal")],
            counts[(target, "problem")]))
    for (_, wrapper, _, target), (verdict, detail) in verdicts:
        if verdict == "internal":
            print("validated_outputs: caught (exit 3): %s --target %s: %s" % (wrapper, target, detail[:200]))
    problems = [(job, detail) for job, (verdict, detail) in verdicts if verdict == "problem"]
    for (_, wrapper, _, target), detail in problems:
        print("validated_outputs: FAIL %s --target %s: %s" % (wrapper, target, detail[:300]))
    print("validated_outputs: %d compiles of %d wrappers, %d problems" % (len(jobs), len(wrappers), len(problems)))
    # The modules glslangValidator wrote go; the outputs a validator refused stay in --out to be read.
    for index in range(len(wrappers)):
        shutil.rmtree(os.path.join(args.out, "spv%d" % index), ignore_errors=True)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

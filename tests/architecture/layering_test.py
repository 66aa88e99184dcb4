#!/usr/bin/env python3
"""layering.py finds what it is for: an include or a link that runs up, and a private header
used from outside its folder; and it passes a tree whose edges all point down."""
import pathlib
import subprocess
import sys
import tempfile

CHECK = pathlib.Path(__file__).with_name("layering.py")
sys.path.insert(0, str(CHECK.parent))
import layering  # noqa: E402


def tree(files: dict) -> tempfile.TemporaryDirectory:
    folder = tempfile.TemporaryDirectory()
    root = pathlib.Path(folder.name)
    for room in layering.LAYERS:
        (root / room).mkdir(parents=True, exist_ok=True)
    for name, text in files.items():
        (root / name).write_text(text)
    return folder


def run(root: str):
    done = subprocess.run([sys.executable, str(CHECK), root], capture_output=True, text=True)
    return done.returncode, done.stdout


def expect(condition: bool, what: str, output: str):
    if not condition:
        print(f"FAILED: {what}\n{output}")
        sys.exit(1)


with tree({"harness/scene/scene.h": '#include "harness/image/image.h"\n#include "base/result.h"\n',
           "glsl/emit.cpp": '#include "hlsl_like/semantics.h"\n#include <vector>\n'}) as root:
    code, output = run(root)
    expect(code == 0, "a tree whose includes point down passes", output)

with tree({"harness/image/image.h": '#include "base/result.h"\n#include "harness/render/lanes.h"\n'}) as root:
    code, output = run(root)
    expect(code == 1 and "harness/image/image.h:2: includes harness/render/lanes.h" in output,
           "an include that runs up fails with its file and line", output)

with tree({"glsl/emit.cpp": '#include "hlsl_like/sema_internal.h"\n'}) as root:
    code, output = run(root)
    expect(code == 1 and "private to hlsl_like/" in output, "a private header used from outside fails", output)

with tree({"harness/gl/gl.cpp": '#include "harness/vulkan/vk.h"\n'}) as root:
    code, output = run(root)
    expect(code == 1 and "harness/gl may use only" in output, "a sideways include between backends fails", output)

with tree({"harness/vulkan/vulkan_backend.cpp": '#include "spirv/spirv_compiler.h"\n',
           "harness/vulkan/vulkan_backend_test.cpp": '#include "spirv/spirv_compiler.h"\n'}) as root:
    code, output = run(root)
    expect(code == 1 and "harness/vulkan/vulkan_backend.cpp:1: includes spirv/spirv_compiler.h" in output
           and "vulkan_backend_test.cpp" not in output,
           "a backend may not use the compiler, and its tests may", output)

with tree({"harness/backend/CMakeLists.txt": "add_library(xshade_backend b.cpp)\n"
           "target_link_libraries(xshade_backend PUBLIC xshade_image PRIVATE xshade_render)\n"}) as root:
    code, output = run(root)
    expect(code == 1 and "harness/backend/CMakeLists.txt:2: xshade_backend links xshade_render" in output,
           "a CMake link that runs up fails", output)

print("layering_test: 6 cases as expected")

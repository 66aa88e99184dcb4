#!/usr/bin/env python3
"""The library graph runs one way: every #include and every CMake link points down.

Each room (a folder that is one library) may use itself and the rooms its entry in LAYERS lists,
and nothing else; a header named *_internal.h is private to its own folder. The check reads
every source file and every CMakeLists.txt of the rooms below, and exits 1 naming each edge that
breaks the order (file:line: what it includes or links, and which rooms it may use).

Usage: layering.py SOURCE_DIR
"""
import pathlib
import re
import sys

# Bottom to top. A room may use the rooms listed with it; the lists are written out in full
# (not derived) so that a new edge is a visible change to this table.
LAYERS = {
    "base": [],
    "hlsl_like": ["base"],
    "shaderlab": ["base"],
    "glsl": ["base", "hlsl_like"],
    "spirv": ["base", "hlsl_like", "glsl"],
    # Generation: a module as a target's code, the one way from the compiler to a target.
    "codegen": ["base", "hlsl_like", "glsl", "spirv"],
    "harness/image": ["base"],
    # A scene names the Unity platform its .shader files compile for (shaderlab::UnityPlatform).
    "harness/scene": ["base", "shaderlab", "harness/image"],
    "harness/backend": ["base", "harness/image"],
    # The backends take programs already made: no compiler room (their tests use one, TEST_USES).
    "harness/gl": ["base", "harness/backend"],
    "harness/vulkan": ["base", "harness/backend"],
    "harness/assets": ["base", "harness/image", "harness/scene", "harness/backend"],
    # Where a scene meets the compiler: codegen's programs, and glsl's trace record and spirv's
    # compile of the hand-written stages (lanes.h).
    "harness/render": ["base", "hlsl_like", "shaderlab", "glsl", "spirv", "codegen", "harness/image", "harness/scene",
                       "harness/backend", "harness/gl", "harness/vulkan", "harness/assets"],
    "harness/gate": ["base", "harness/image", "harness/scene", "harness/backend", "harness/assets", "harness/render"],
    # The reports are written from the gate's results alone: neither a backend nor a renderer.
    "harness/report": ["base", "harness/image", "harness/scene", "harness/backend", "harness/gate"],
    # `xshade watch`'s parts: which files a checked scene read, inotify, the report served over HTTP.
    "harness/live": ["base", "harness/image", "harness/scene", "harness/backend", "harness/gate"],
    "stability": ["harness/image", "harness/scene", "harness/backend", "harness/assets", "harness/render",
                  "harness/report"],
    "accuracy": ["base", "harness/image", "harness/scene", "harness/backend", "harness/assets", "harness/render",
                 "harness/gate", "harness/report"],
    "cli": ["base", "hlsl_like", "shaderlab", "spirv", "codegen", "harness/image", "harness/scene", "harness/render", "harness/gate", "harness/report", "harness/live", "stability", "accuracy"],
}
# What a room's tests (*_test.cpp) may use besides: a backend's tests make their shaders with the
# compiler that the backend itself never calls.
TEST_USES = {
    "harness/gl": ["glsl"],
    "harness/vulkan": ["glsl", "spirv"],
}

# The CMake library each room builds.
LIBRARY = {room: "xshade_" + room.split("/")[-1] for room in LAYERS if room != "cli"}
LIBRARY["cli"] = "xshade"
ROOM_OF_LIBRARY = {library: room for room, library in LIBRARY.items()}

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
LINK = re.compile(r"target_link_libraries\(\s*(\S+)([^)]*)\)", re.S)


def room_of(relative: str):
    """The room a project path (file or include) is in: the longest LAYERS key it starts with."""
    best = None
    for room in LAYERS:
        if relative == room or relative.startswith(room + "/"):
            if best is None or len(room) > len(best):
                best = room
    return best


def check_includes(root: pathlib.Path, problems: list):
    for room in LAYERS:
        folder = root / room
        for path in sorted(folder.rglob("*")):
            if path.suffix not in (".h", ".cpp"):
                continue
            relative = path.relative_to(root).as_posix()
            if room_of(relative) != room:
                continue  # a room of its own below this one's folder
            allowed = LAYERS[room] + (TEST_USES.get(room, []) if path.name.endswith("_test.cpp") else [])
            for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                match = INCLUDE.match(line)
                if not match:
                    continue
                included = match.group(1)
                target = room_of(included)
                if target is None:
                    continue  # not one of the rooms: a generated or external header
                if included.endswith("_internal.h") and pathlib.PurePosixPath(included).parent.as_posix() != room:
                    problems.append(f"{relative}:{number}: includes {included}, private to {target}/")
                elif target != room and target not in allowed:
                    problems.append(f"{relative}:{number}: includes {included} ({target}); "
                                    f"{room} may use only {', '.join(LAYERS[room]) or 'nothing'}")


def check_links(root: pathlib.Path, problems: list):
    for room in LAYERS:
        cmake = root / room / "CMakeLists.txt"
        if not cmake.exists():
            continue
        text = cmake.read_text()
        for match in LINK.finditer(text):
            target, arguments = match.group(1), match.group(2)
            if target != LIBRARY[room]:
                continue  # a test executable: it may link what it tests and what helps
            line = text.count("\n", 0, match.start()) + 1
            for word in arguments.split():
                used = ROOM_OF_LIBRARY.get(word)
                if used and used != room and used not in LAYERS[room]:
                    problems.append(f"{room}/CMakeLists.txt:{line}: {target} links {word} ({used}); "
                                    f"{room} may use only {', '.join(LAYERS[room]) or 'nothing'}")


def main():
    if len(sys.argv) != 2:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    root = pathlib.Path(sys.argv[1])
    missing = [room for room in LAYERS if not (root / room).is_dir()]
    if missing:
        print(f"layering: no folder {', '.join(missing)} under {root}", file=sys.stderr)
        return 2
    problems = []
    check_includes(root, problems)
    check_links(root, problems)
    for problem in problems:
        print(problem)
    print(f"layering: {len(LAYERS)} rooms, {len(problems)} edges that run up or sideways")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

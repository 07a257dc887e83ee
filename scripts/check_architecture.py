#!/usr/bin/env python3
"""Checks the dependency rules of docs/architecture.md: contracts at the bottom, processes above
them, no arrow between processes and none upward.

Reads every folder's sources (#include "hapticctrl/...") and CMake files (hapticctrl::<target>
links, include directories reaching into another folder) and fails, naming the file and line, on
any arrow the rules do not allow. Usage: scripts/check_architecture.py [source dir]
"""
import pathlib
import re
import sys

# The contracts (ground floor) use nothing of the project; each process room may use these.
CONTRACTS = {"shm", "protocol", "lcmtypes", "arm_model", "ros2types"}
ALLOWED = {
    "base": set(),  # the vocabulary below the contracts (the real-time mark): every room may use it
    "program": set(),  # scaffolding (options, main skeleton): every process may use it
    "shm": set(),
    "protocol": set(),
    # the regions it carries one for one, mapped through shm's field tables (lcmtypes/regions.hpp)
    "lcmtypes": {"shm"},
    "arm_model": set(),
    "ros2types": set(),
    "rt_core": {"shm", "arm_model", "program"},
    "client": {"protocol"},  # it runs on another machine: never shm/ or rt_core/
    "bridges/udp": CONTRACTS | {"program"},
    "bridges/lcm": CONTRACTS | {"program"},
    "bridges/web": CONTRACTS | {"program"},
    "bridges/dds": CONTRACTS | {"program"},
    "hmi": {"shm", "lcmtypes", "program"},
    "demo": {"client", "lcmtypes", "program"},  # an application of the client library
    "mujoco": {"client", "lcmtypes", "program"},  # another: a MuJoCo scene as the client
    "bench/netem": {"protocol", "program"},  # the impairment relay the tests and benchmarks use
}
# Rooms that may use anything: they test or measure the others.
FREE = {"tests", "bench"}
SOURCES = (".cpp", ".hpp", ".h", ".c")


def room_of(path: pathlib.Path, root: pathlib.Path) -> str | None:
    rel = path.relative_to(root).as_posix()
    for room in sorted(ALLOWED, key=len, reverse=True):
        if rel == room or rel.startswith(room + "/"):
            return room
    return None


def include_owners(root: pathlib.Path) -> dict[str, str]:
    """'hapticctrl/shm' -> 'shm', 'hapticctrl/virtuose_api.h' -> 'client', ..."""
    owners = {}
    for room in ALLOWED:
        include = root / room / "include"
        if not include.is_dir():
            continue
        for top in include.iterdir():
            for entry in top.iterdir() if top.is_dir() else []:
                owners[f"{top.name}/{entry.name}"] = room
    owners["hapticctrl_lcm"] = "lcmtypes"  # lcm-gen's headers, generated at build time
    owners["ros2_messages.h"] = "ros2types"  # idlc's header, generated at build time
    return owners


def target_owners(root: pathlib.Path) -> dict[str, str]:
    """'hapticctrl::shm' -> 'shm', from the ALIAS declarations."""
    owners = {}
    for cmake in root.rglob("CMakeLists.txt"):
        room = room_of(cmake.parent, root)
        if room is None:
            continue
        for alias in re.findall(r"add_library\((hapticctrl::\w+) ALIAS", cmake.read_text()):
            owners[alias] = room
    return owners


def check(root: pathlib.Path) -> list[str]:
    problems = []
    includes = include_owners(root)
    targets = target_owners(root)
    include_re = re.compile(r'#\s*include\s*[<"]([^>"]+)[>"]')
    for path in sorted(root.rglob("*")):
        if path.suffix not in SOURCES and path.name != "CMakeLists.txt":
            continue
        if any(part in ("build", "node_modules", ".git") or part.startswith("build-")
               for part in path.relative_to(root).parts):
            continue
        room = room_of(path, root)
        if room is None:
            continue  # tests/, bench/ (but bench/netem), scripts: free
        allowed = ALLOWED[room] | {room, "base"}  # base/ is below every room
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
            used = set()
            if path.name == "CMakeLists.txt":
                used |= {targets[t] for t in re.findall(r"hapticctrl::\w+", line)
                         if t in targets and "ALIAS" not in line}
                for reach in re.findall(r"\$\{PROJECT_SOURCE_DIR\}/([\w/]+)", line):
                    owner = room_of(root / reach, root)
                    if owner is not None:
                        used.add(owner)
            else:
                match = include_re.search(line)
                if match:
                    name = match.group(1)
                    for prefix, owner in includes.items():
                        if name == prefix or name.startswith(prefix + "/"):
                            used.add(owner)
            for owner in sorted(used - allowed):
                problems.append(f"{path.relative_to(root)}:{number}: {room}/ uses {owner}/, "
                                f"which it may not (it may use: {', '.join(sorted(ALLOWED[room])) or 'nothing'})")
    return problems


def main() -> int:
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    problems = check(root)
    for p in problems:
        print(p, file=sys.stderr)
    if problems:
        print(f"check_architecture: {len(problems)} forbidden arrows (docs/architecture.md)",
              file=sys.stderr)
        return 1
    print(f"check_architecture: {len(ALLOWED)} rooms, every arrow allowed")
    return 0


if __name__ == "__main__":
    sys.exit(main())

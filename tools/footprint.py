#!/usr/bin/python3
"""Flash, RAM and worst-case step stack of the control core in one cross build.

  tools/footprint.py --core-dir DIR --map FILE [--root FN ...] [--json PATH]

--core-dir  the build folder of firmware/ configured with -DTVO_STACK_USAGE=ON: its object folder
            holds one .ci call graph (gcc -fcallgraph-info=su) per core source.
--map       the GNU ld map file of a --gc-sections link that uses the core; only the input sections
            that came from libtvo_core.a are counted, so libc, libm and startup code are not.
--root      functions whose worst-case stack depth to report (default: tvo_controller_step).

Flash = .text + .rodata + .data of the core, RAM = .data + .bss of the core (what the linker kept).
Stack: the deepest path of static frame sizes through the call graph. The core's only indirect
calls are the objective's term callbacks (tvo_gradient_jet_fn, tvo_constraint_max_fn); an indirect
call is charged the deepest of the functions that implement them (names ending in _gradient_jet or
_constraint_max). Calls into libc/libm/libgcc (no .ci of ours) are charged EXTERNAL_FRAME_BYTES
each, a stated bound, not a measurement. The core has no recursion; a cycle is reported as an error.
"""
import argparse
import json
import pathlib
import re
import sys

# Charged per call that leaves the core (memset, sinf, __aeabi_* ...): newlib-nano's and libgcc's
# leaf routines use well under this on Cortex-M and RV32.
EXTERNAL_FRAME_BYTES = 64
CALLBACK_SUFFIXES = ("_gradient_jet", "_gradient_hessian", "_constraint_max")

NODE_RE = re.compile(r'node: \{ title: "([^"]+)" label: "([^"]*)"')
EDGE_RE = re.compile(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"')
BYTES_RE = re.compile(r'\\n(\d+) bytes \((static|dynamic[^)]*)\)')


def read_call_graph(core_dir):
    frames, edges = {}, {}
    files = sorted(pathlib.Path(core_dir).rglob("*.ci"))
    if not files:
        sys.exit(f"footprint: no .ci files under {core_dir} (configure firmware/ with -DTVO_STACK_USAGE=ON)")
    for path in files:
        text = path.read_text()
        for name, label in NODE_RE.findall(text):
            match = BYTES_RE.search(label)
            if match:
                if match.group(2) != "static":
                    sys.exit(f"footprint: {name} has a {match.group(2)} frame: worst case not static")
                frames[name] = int(match.group(1))
        for src, dst in EDGE_RE.findall(text):
            edges.setdefault(src, set()).add(dst)
    return frames, edges


def worst_stack(root, frames, edges):
    # The objective's own dispatchers share the suffixes but are the callers, not the callbacks.
    callbacks = [f for f in frames if f.endswith(CALLBACK_SUFFIXES) and not f.startswith("tvo_objective_")]
    memo, active = {}, set()

    def depth(fn):
        if fn in memo:
            return memo[fn]
        if fn == "__indirect_call":
            result = max((depth(c) for c in callbacks), default=(EXTERNAL_FRAME_BYTES, [fn]))
            memo[fn] = result
            return result
        if fn not in frames:
            return EXTERNAL_FRAME_BYTES, [fn + " (external)"]
        if fn in active:
            sys.exit(f"footprint: recursion through {fn}: no static worst case")
        active.add(fn)
        best = (0, [])
        for callee in sorted(edges.get(fn, ())):
            best = max(best, depth(callee), key=lambda item: item[0])
        active.discard(fn)
        memo[fn] = (frames[fn] + best[0], [fn] + best[1])
        return memo[fn]

    if root not in frames:
        sys.exit(f"footprint: {root} not in the call graph")
    return depth(root)


SECTION_RE = re.compile(r"^ (\.\S+)\s+0x[0-9a-f]+\s+0x([0-9a-f]+)\s+(\S+)$")
SECTION_NAME_ONLY_RE = re.compile(r"^ (\.\S+)$")
SECTION_CONT_RE = re.compile(r"^\s+0x[0-9a-f]+\s+0x([0-9a-f]+)\s+(\S+)$")


def core_sections(map_path, archive="libtvo_core.a"):
    """Sizes by output kind of the input sections from the archive that the link kept."""
    sizes = {"text": 0, "rodata": 0, "data": 0, "bss": 0}
    in_memory_map, pending = False, None
    for line in pathlib.Path(map_path).read_text().splitlines():
        if line.startswith("Linker script and memory map"):
            in_memory_map = True
            continue
        if not in_memory_map or line.startswith("/DISCARD/"):
            continue
        name = size = origin = None
        match = SECTION_RE.match(line)
        if match:
            name, size, origin = match.group(1), int(match.group(2), 16), match.group(3)
        elif SECTION_NAME_ONLY_RE.match(line):
            pending = SECTION_NAME_ONLY_RE.match(line).group(1)  # long names wrap to the next line
            continue
        elif pending and SECTION_CONT_RE.match(line):
            cont = SECTION_CONT_RE.match(line)
            name, size, origin = pending, int(cont.group(1), 16), cont.group(2)
        pending = None
        if name is None or archive not in origin or size == 0:
            continue
        for kind in ("text", "rodata", "data", "bss"):
            if name.startswith("." + kind) or (kind == "rodata" and name.startswith(".srodata")) \
                    or (kind == "data" and name.startswith(".sdata")) or (kind == "bss" and name.startswith(".sbss")):
                sizes[kind] += size
                break
    return sizes


def instance_sizes(map_path):
    """The probe defines tvo_sizeof_<type>[sizeof(type)]: their section sizes are the struct sizes."""
    sizes, pending = {}, None
    for line in pathlib.Path(map_path).read_text().splitlines():
        match = re.match(r"^ \.rodata\.tvo_sizeof_(\w+)(?:\s+0x[0-9a-f]+\s+0x([0-9a-f]+))?", line)
        if match and match.group(2):
            sizes[match.group(1)] = int(match.group(2), 16)
        elif match:
            pending = match.group(1)
        elif pending and SECTION_CONT_RE.match(line):
            sizes[pending] = int(SECTION_CONT_RE.match(line).group(1), 16)
            pending = None
    return sizes


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--core-dir", required=True)
    parser.add_argument("--map", required=True)
    parser.add_argument("--root", action="append")
    parser.add_argument("--json")
    args = parser.parse_args()
    frames, edges = read_call_graph(args.core_dir)
    sections = core_sections(args.map)
    result = {
        "flash_bytes": sections["text"] + sections["rodata"] + sections["data"],
        "ram_bytes": sections["data"] + sections["bss"],
        "sections": sections,
        "instance_bytes": instance_sizes(args.map),
        "stack": {},
    }
    for root in args.root or ["tvo_controller_step"]:
        bytes_, path = worst_stack(root, frames, edges)
        result["stack"][root] = {"bytes": bytes_, "path": path}
    result["stack_bytes"] = max(v["bytes"] for v in result["stack"].values())
    text = json.dumps(result, indent=2)
    if args.json:
        pathlib.Path(args.json).write_text(text + "\n")
    print(text)


if __name__ == "__main__":
    main()

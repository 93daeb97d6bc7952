#!/usr/bin/python3
"""Flash, RAM and worst-case step stack of the control core in one cross build.

  tools/footprint.py --core-dir DIR --map FILE --elf FILE --objdump PROG [--root FN ...] [--json PATH]

--core-dir  the build folder of firmware/ configured with -DTVO_STACK_USAGE=ON: its object folder
            holds one .ci call graph (gcc -fcallgraph-info=su) per core source.
--map       the GNU ld map file of a --gc-sections link that uses the core; only the input sections
            that came from libtvo_core.a are counted, so libc, libm and startup code are not.
--elf       the linked program of that map; --objdump the toolchain's objdump, to disassemble it.
--root      functions whose worst-case stack depth to report (default: tvo_controller_step).

Flash = .text + .rodata + .data of the core, RAM = .data + .bss of the core (what the linker kept).
Stack: the deepest path of static frame sizes through the call graph. The core makes indirect
calls in four files (INDIRECT_TARGETS; one elsewhere is an error): objective.c calls the terms'
callbacks (tvo_gradient_jet_fn, tvo_constraint_max_fn), charged the deepest of the functions that
implement them (names ending in _gradient_jet, _gradient_hessian or _constraint_max) that the link
kept; law.c calls the objective's general path (tvo_general_path_fn), charged law_general_path if
the link kept it and nothing if not (then no add function stored it: the pointer is NULL);
controller.c calls the position-only velocity source's plan (tvo_position_velocity_t), charged
the deeper of controller_position_velocity and its _commit if the link kept them and nothing if not (then only
tvo_controller_init_pose_velocity initialised controllers, and it refuses that source); sampled_loop.h
calls the objective's start rule (tvo_start_rule_fn), charged problem_start_rule if the link kept it
and nothing if not (then no problem with inequalities stored it). Calls into libc/libm/libgcc (no .ci of
ours) are measured in the linked ELF (--elf, disassembled by --objdump): each library function's
frame is the sum of its stack-pointer decrements (pushes, stack adjustments), its callees are its
direct calls and tail branches, so a library path is charged in full (newlib's sinf of a huge
argument goes through __kernel_rem_pio2f, over 400 B on Cortex-M). A library function with an
indirect call or a stack adjustment by a register on the path is an error, as is recursion. A
branch into another function (its start or its middle) counts as a call to all of it; not followed:
a jump through a register without link (taken as a switch table) and code that runs off the end
of one function into the next (libgcc's __aeabi_fsub into __addsf3: leaves with no frame of their
own on today's paths, checked by hand).
"""
import argparse
import json
import pathlib
import re
import subprocess
import sys

CALLBACK_SUFFIXES = ("_gradient_jet", "_gradient_hessian", "_constraint_max")
# The source file of an indirect call -> what it can reach: names ending in these suffixes (terms'
# callbacks) or these exact names.
INDIRECT_TARGETS = {
    "objective.c": {"suffixes": CALLBACK_SUFFIXES, "names": (), "may_be_absent": False},
    "law.c": {"suffixes": (), "names": ("law_general_path",), "may_be_absent": True},
    "controller.c": {"suffixes": (), "names": ("controller_position_velocity", "controller_position_velocity_commit"), "may_be_absent": True},
    "sampled_loop.h": {"suffixes": (), "names": ("problem_start_rule",), "may_be_absent": True},
}
INDIRECT = "__indirect_call"

NODE_RE = re.compile(r'node: \{ title: "([^"]+)" label: "([^"]*)"')
EDGE_RE = re.compile(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"(?: label: "([^"]*)")?')
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
        for src, dst, label in EDGE_RE.findall(text):
            if dst == INDIRECT:
                # label "<path>:<line>:<column>": an indirect call is told apart by its file
                source = pathlib.PurePath(label.rsplit(":", 2)[0]).name if label else "?"
                if source not in INDIRECT_TARGETS:
                    sys.exit(f"footprint: an indirect call in {src} ({label}): INDIRECT_TARGETS does not say "
                             "what it can reach")
                dst = f"{INDIRECT}@{source}"
            edges.setdefault(src, set()).add(dst)
    return frames, edges


FUNCTION_RE = re.compile(r"^[0-9a-f]+ <([^>+]+)>:$")
INSN_RE = re.compile(r"^\s*[0-9a-f]+:\s+(\S+)\s*(.*)$")
TARGET_RE = re.compile(r"<([^>+]+)(?:\+0x[0-9a-f]+)?>$")
REG_LIST_RE = re.compile(r"\{([^}]*)\}")
# ARM: push/stmdb sp!/vpush/vstmdb sp! {list}; sub sp, #n; str/strd ..., [sp, #-n]!.
# RISC-V: add(i) sp,sp,-n.
ARM_SUB_RE = re.compile(r"^sp, (?:sp, )?#(\d+)")
PRE_INDEX_RE = re.compile(r"\[sp, #-(\d+)\]!")
RV_ADD_RE = re.compile(r"^sp,sp,-(\d+)$")
FUNCTION_SYMBOL_RE = re.compile(r"^([0-9a-f]+) .* F \S+\s+[0-9a-f]+\s+(?:\.hidden )?(\S+)$", re.M)


def register_list_bytes(args):
    """Bytes a push of the listed registers takes: 4 per core or s register, 8 per d register."""
    total = 0
    for item in REG_LIST_RE.search(args).group(1).split(","):
        item = item.strip()
        first, _, last = item.partition("-")
        count = int(last[1:]) - int(first[1:]) + 1 if last else 1
        total += count * (8 if first.startswith("d") else 4)
    return total


def stack_decrement(op, args):
    """Bytes an instruction takes from the stack; None when by a register (not static)."""
    base = op.split(".")[0]
    if base == "push" or base == "vpush" or (base in ("stmdb", "stmfd", "vstmdb") and args.startswith("sp!")):
        return register_list_bytes(args)
    if base in ("sub", "subw") and args.startswith("sp,"):
        match = ARM_SUB_RE.match(args)
        return int(match.group(1)) if match else None
    if base.startswith("str") and PRE_INDEX_RE.search(args):
        return int(PRE_INDEX_RE.search(args).group(1))
    if base in ("add", "addi") and args.startswith("sp,sp,-"):
        return int(RV_ADD_RE.match(args).group(1))
    if base == "sub" and args.startswith("sp,sp,"):
        return None
    # By a register: Thumb-1's large frames (add sp, rN with rN negative), RISC-V's add sp,sp,rN.
    if base == "add" and re.match(r"^sp, (?:sp, )?[a-z]+[0-9]*$", args) or re.match(r"^sp,sp,[a-z]+[0-9]*$", args):
        return None
    return 0


def read_binary_graph(elf, objdump):
    """Frames and direct callees of every function in a linked program, from its disassembly."""
    text = subprocess.run([objdump, "-d", "--no-show-raw-insn", elf], check=True, capture_output=True,
                          text=True).stdout
    frames, edges, millicode, problems = {}, {}, {}, {}
    current = None
    for line in text.splitlines():
        match = FUNCTION_RE.match(line)
        if match:
            current = match.group(1)
            frames.setdefault(current, 0)
            edges.setdefault(current, set())
            continue
        match = INSN_RE.match(line) if current else None
        if not match:
            continue
        # Comments: ";" and "@" (Arm), " # " (RISC-V's address annotations; Arm immediates have no space).
        op, args = match.group(1), match.group(2).split(";")[0].split("@")[0].split(" # ")[0].strip()
        if current.startswith("__riscv_save"):
            # RV32 millicode: saves up to 12 registers in one 64-byte block for its caller.
            frames[current] = 64
            continue
        taken = stack_decrement(op, args)
        if taken is None:
            problems.setdefault(current, f"stack adjusted by a register ({op} {args})")
        else:
            frames[current] += taken
        base = op.split(".")[0]
        target = TARGET_RE.search(args)
        # An indirect call has no static callee; an indirect jump without link (bx/jr through a
        # register) is taken as the library's switch tables, which stay in the function (a tail call
        # through a function pointer would be missed: none is in newlib's or libgcc's routines here).
        # A RISC-V far call (auipc; jalr) names its target in the comment: a call.
        if base in ("blx", "jalr") and not target:
            problems.setdefault(current, f"indirect call ({op} {args})")
        elif target and (base.startswith("b") or base in ("j", "jal", "jalr", "jr", "call", "tail")):
            callee = target.group(1)
            if base == "jal" and args.startswith("t0,"):
                millicode[current] = callee  # its frame is the caller's until the caller returns
            elif callee != current:
                edges[current].add(callee)
    for fn, routine in millicode.items():
        frames[fn] += frames.get(routine, 64)
        edges[fn].discard(routine)
    # Aliases (__aeabi_uidiv is __udivsi3): the disassembly labels an address by one of its names.
    symbols = subprocess.run([objdump, "-t", elf], check=True, capture_output=True, text=True).stdout
    by_address = {}
    for match in FUNCTION_SYMBOL_RE.finditer(symbols):
        by_address.setdefault(match.group(1), []).append(match.group(2))
    for names in by_address.values():
        label = next((n for n in names if n in frames), None)
        for name in names:
            if label and name not in frames:
                frames[name], edges[name] = frames[label], edges[label]
                if label in problems:
                    problems[name] = problems[label]
    return frames, edges, problems


def worst_stack(root, frames, edges, binary):
    """The deepest path from root: our functions by gcc's call graph, the library's by the ELF's."""
    bin_frames, bin_edges, bin_problems = binary

    def reachable(source):
        spec = INDIRECT_TARGETS[source]
        # A static function's title is "<file>:<name>": a name matches either.
        missing = [name for name in spec["names"] if name not in {f.split(":")[-1] for f in frames}]
        if missing:  # not linked may be; not compiled is a renamed target this table missed
            sys.exit(f"footprint: {', '.join(missing)} (an indirect call in {source} reaches it) is not in the "
                     "core's call graph")
        # The objective's own dispatchers share the suffixes but are the callers, not the callbacks.
        return [f for f in frames if f.split(":")[-1] in bin_frames and not f.startswith("tvo_objective_")
                and ((bool(spec["suffixes"]) and f.endswith(spec["suffixes"])) or f.split(":")[-1] in spec["names"])]

    memo, active = {}, set()

    def depth(fn):
        if fn in memo:
            return memo[fn]
        if fn.startswith(INDIRECT + "@"):
            source = fn.split("@", 1)[1]
            targets = reachable(source)
            if not targets and not INDIRECT_TARGETS[source]["may_be_absent"]:
                sys.exit(f"footprint: an indirect call in {source}, but nothing it can reach is in the link")
            memo[fn] = max((depth(c) for c in targets), key=lambda item: item[0], default=(0, []))
            return memo[fn]
        ours = fn in frames
        if not ours and fn not in bin_frames:
            sys.exit(f"footprint: {fn} is called but is neither in the core's call graph nor in the link")
        if not ours and fn in bin_problems:
            sys.exit(f"footprint: no static stack bound through {fn}: {bin_problems[fn]}")
        if fn in active:
            sys.exit(f"footprint: recursion through {fn}: no static worst case")
        active.add(fn)
        best = (0, [])
        for callee in sorted(edges.get(fn, ()) if ours else bin_edges[fn]):
            best = max(best, depth(callee), key=lambda item: item[0])
        active.discard(fn)
        frame = frames[fn] if ours else bin_frames[fn]
        memo[fn] = (frame + best[0], [fn if ours else fn + " (library)"] + best[1])
        return memo[fn]

    if root not in frames:
        sys.exit(f"footprint: {root} not in the call graph")
    return depth(root)


def check_binary_frames(frames, binary):
    """The disassembly must find gcc's own frame for the core's public functions the link kept (the
    check of the library's figures); returns how many it compared and how many matched exactly."""
    bin_frames = binary[0]
    compared = equal = 0
    for fn, frame in frames.items():
        if ":" in fn or fn not in bin_frames:
            continue
        if bin_frames[fn] < frame:
            sys.exit(f"footprint: the disassembly finds {bin_frames[fn]} B for {fn}, gcc says {frame} B")
        compared += 1
        equal += bin_frames[fn] == frame
    return {"compared": compared, "equal": equal}


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
    parser.add_argument("--elf", required=True)
    parser.add_argument("--objdump", required=True)
    parser.add_argument("--root", action="append")
    parser.add_argument("--json")
    args = parser.parse_args()
    frames, edges = read_call_graph(args.core_dir)
    binary = read_binary_graph(args.elf, args.objdump)
    frames_check = check_binary_frames(frames, binary)
    sections = core_sections(args.map)
    result = {
        "flash_bytes": sections["text"] + sections["rodata"] + sections["data"],
        "ram_bytes": sections["data"] + sections["bss"],
        "sections": sections,
        "instance_bytes": instance_sizes(args.map),
        "stack": {},
        "frames_from_disassembly_vs_gcc": frames_check,
    }
    for root in args.root or ["tvo_controller_step"]:
        bytes_, path = worst_stack(root, frames, edges, binary)
        result["stack"][root] = {"bytes": bytes_, "path": path}
    result["stack_bytes"] = max(v["bytes"] for v in result["stack"].values())
    text = json.dumps(result, indent=2)
    if args.json:
        pathlib.Path(args.json).write_text(text + "\n")
    print(text)


if __name__ == "__main__":
    main()

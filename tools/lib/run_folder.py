#!/usr/bin/python3
"""The folder a run writes when the user names none: runs/NAME for a run with the defaults, and
runs/NAME-OPTION-VALUE... with the options that change what runs, in the order given, so that
`tools/demo --sigma 1e-3` (runs/demo-sigma-1e-3) does not overwrite `tools/demo` (runs/demo).
tools/demo, tools/scenario and tools/fleet use it: one rule for every run folder.

Usage: tools/lib/run_folder.py NAME [OPTIONS...]    prints the folder (relative to the working folder)
"""
import hashlib
import os
import re
import sys

# Options that say where a run writes, talks or checks, not what it runs: they do not name a folder.
NOT_A_VARIANT = {"--out-dir", "--summary-json", "--lcm-url", "--firmware", "--max-output-mib", "--dry-run",
                 "--answer-timeout-s", "--json", "--port", "--build-dir", "--check", "--local"}
# Longer names end in a hash of the whole name instead (a file system allows 255 bytes).
MAX_NAME = 96


def part(text):
    """A value as a name's part: its file name if it is a path, without characters a shell would quote."""
    return re.sub(r"[^A-Za-z0-9._,+-]", "_", os.path.basename(text.rstrip("/")) or text)


def run_folder(name, options):
    parts = [part(name)]
    i = 0
    while i < len(options):
        option = options[i]
        i += 1
        if not option.startswith("--"):
            continue  # a stray value: the program refuses it, naming it
        value = None
        if "=" in option:
            option, value = option.split("=", 1)
        elif i < len(options) and not options[i].startswith("--"):
            value = options[i]
            i += 1
        if option in NOT_A_VARIANT:
            continue
        parts.append(option[2:])
        if value is not None:
            parts.append(part(value))
    folder = "-".join(parts)
    if len(folder) > MAX_NAME:
        folder = folder[:MAX_NAME - 9] + "-" + hashlib.sha1(folder.encode()).hexdigest()[:8]
    return os.path.join("runs", folder)


if __name__ == "__main__":
    if len(sys.argv) < 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        sys.exit(0 if len(sys.argv) >= 2 else 2)
    print(run_folder(sys.argv[1], sys.argv[2:]))

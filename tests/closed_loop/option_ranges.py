#!/usr/bin/env python3
"""CTest: every numeric option of a program, read from its --help, is refused outside its range.

An option is numeric when CLI11 shows its type as FLOAT, INT or UINT (or a pair of them, A,B); a
KEY=TYPE item in an option's description (tvo_study's --trace-config) is walked the same way. Each
must show its range ("in [lo, hi]", a parenthesis for an excluded end; host/src/option_ranges.hpp),
else the test fails: a new option without a range fails here. For every such value:

  below and above the range, and unparsable text: exit code 2, one line on stderr that names the
  option and shows the range as --help does, and nothing created in --no-work-path (so the check ran
  before any work);
  each closed end (or, for an open end, a value just inside): not refused by the range check (exit 0
  with the --accept-arg arguments, or exit 2 from a rule between options, which the --case entries
  test).

Usage: option_ranges.py --program EXE [--common-option=NAME=VALUE]... [--accept-arg=ARG]...
                        [--no-work-path PATH] [--case="ARGS"]... [--accept-case="ARGS"]...
  --common-option  given to every run, but for the option under test (e.g. --lcm-url memq://)
  --case           more refusals (rules between options): exit 2 naming the first option of ARGS
  --accept-case    more accepted runs (with the --accept-arg arguments): exit 0
"""
import argparse
import os
import re
import shlex
import shutil
import subprocess
import sys
from decimal import Decimal

OPTION_LINE = re.compile(r"^  (?:-\w,)?(--[a-z0-9][a-z0-9-]*)(?: (\S.*?))?(?: {2,}(.*))?$")
RANGE = re.compile(r"in ([\[(])([^,\[\]()]+), ([^,\[\]()]+)([\])])")
SUB_KEY = re.compile(r"\b([a-z_]+)=(INT|UINT|FLOAT) (in [\[(][^,\[\]()]+, [^,\[\]()]+[\])])")
NUMERIC = {"FLOAT", "INT", "UINT"}


class Element:
    """One number an option takes: its kind (FLOAT is real, INT and UINT whole) and range."""

    def __init__(self, kind, range_text):
        m = RANGE.fullmatch(range_text) or RANGE.search(range_text)
        self.kind = kind
        self.shown = range_text[m.start(1):m.end(4)]  # "[lo, hi]" as the program prints it
        self.lo_open, self.hi_open = m.group(1) == "(", m.group(4) == ")"
        self.lo_text, self.hi_text = m.group(2), m.group(3)
        self.lo, self.hi = Decimal(self.lo_text), Decimal(self.hi_text)

    def whole(self):
        return self.kind != "FLOAT"

    def step(self, at):
        return Decimal(1) if self.whole() else max(abs(at) / 100, Decimal("1e-9"))

    def text(self, value):
        return str(int(value)) if self.whole() else repr(float(value))

    def outside(self):
        below = self.lo if self.lo_open else self.lo - self.step(self.lo)
        above = self.hi if self.hi_open else self.hi + self.step(self.hi)
        unparsable = ["abc", "1.5"] if self.whole() else ["abc", "nan", "1e400"]
        return [("below", self.text(below)), ("above", self.text(above))] + [("unparsable", u) for u in unparsable]

    def inside(self):
        lo = self.text(self.lo + self.step(self.lo)) if self.lo_open else self.lo_text
        hi = self.text(self.hi - self.step(self.hi)) if self.hi_open else self.hi_text
        return [lo, hi]


def parse_help(text):
    """[(option, type token, description)] of every option line of CLI11's --help."""
    options, current = [], None
    for line in text.splitlines():
        m = OPTION_LINE.match(line)
        if m:
            current = [m.group(1), m.group(2) or "", m.group(3) or ""]
            options.append(current)
        elif current is not None and line.startswith(" " * 10):
            current[2] += " " + line.strip()
        else:
            current = None
    return options


class Walk:
    def __init__(self, args):
        self.args = args
        self.failures = []
        self.runs = 0

    def run(self, option, extra, accept=False):
        argv = [self.args.program]
        for common in self.args.common_option:
            name, _, value = common.partition("=")
            if name != option:
                argv += [name, value]
        argv += extra + (self.args.accept_arg if accept else [])
        if self.args.no_work_path:
            shutil.rmtree(self.args.no_work_path, ignore_errors=True)
        self.runs += 1
        proc = subprocess.run(argv, capture_output=True, text=True, timeout=60)
        return argv, proc

    def fail(self, argv, proc, why):
        self.failures.append(f"{shlex.join(argv[1:])}: {why} (exit {proc.returncode}; stderr: {proc.stderr.strip()!r})")

    def expect_refused(self, option, extra, shown=None):
        argv, proc = self.run(option, extra)
        lines = [l for l in proc.stderr.splitlines() if l.strip()]
        if proc.returncode != 2:
            self.fail(argv, proc, "expected exit code 2")
        elif len(lines) != 1:
            self.fail(argv, proc, f"expected one line on stderr, got {len(lines)}")
        elif option not in lines[0]:
            self.fail(argv, proc, f"stderr does not name {option}")
        elif shown is not None and shown not in lines[0]:
            self.fail(argv, proc, f"stderr does not show the range {shown}")
        if self.args.no_work_path and os.path.exists(self.args.no_work_path):
            self.fail(argv, proc, f"{self.args.no_work_path} was created: the check came after some work")

    def expect_accepted(self, option, extra, value, allow_rule=True):
        argv, proc = self.run(option, extra, accept=True)
        refused_by_range = option in proc.stderr and f"got '{value}', expected" in proc.stderr
        if proc.returncode == 0:
            return
        if allow_rule and proc.returncode == 2 and not refused_by_range:
            print(f"  note: {shlex.join(argv[1:])}: in range, refused by a rule between options: {proc.stderr.strip()}")
            return
        self.fail(argv, proc, "an in-range value was refused")

    def walk_option(self, option, elements, compose):
        """compose(values) -> the option's argument text; one element varied at a time."""
        for index, element in enumerate(elements):
            others = [e.inside()[0] for e in elements]
            for what, value in element.outside():
                values = list(others)
                values[index] = value
                self.expect_refused(option, [option, compose(values)], element.shown)
            for value in element.inside():
                values = list(others)
                values[index] = value
                self.expect_accepted(option, [option, compose(values)], value)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--program", required=True)
    parser.add_argument("--common-option", action="append", default=[], metavar="NAME=VALUE")
    parser.add_argument("--accept-arg", action="append", default=[])
    parser.add_argument("--no-work-path")
    parser.add_argument("--case", action="append", default=[])
    parser.add_argument("--accept-case", action="append", default=[])
    args = parser.parse_args()
    walk = Walk(args)

    proc = subprocess.run([args.program, "--help"], capture_output=True, text=True, timeout=60)
    if proc.returncode != 0:
        print(f"FAIL: {args.program} --help exited {proc.returncode}: {proc.stderr}")
        return 1
    options = parse_help(proc.stdout)
    walked = []
    for option, token, description in options:
        base = re.split(r"[:=]", token, maxsplit=1)[0] if token else ""
        kinds = base.strip("[]").split(",") if base else []
        if kinds and all(k in NUMERIC for k in kinds):
            ranges = [m.group(0) for m in RANGE.finditer(token)]
            if not ranges:
                walk.failures.append(f"{option}: numeric ({base}) but --help shows no range")
                continue
            if len(ranges) == 1:
                ranges *= len(kinds)
            if len(ranges) != len(kinds):
                walk.failures.append(f"{option}: {len(kinds)} numbers but {len(ranges)} ranges in --help")
                continue
            elements = [Element(k, r) for k, r in zip(kinds, ranges)]
            walk.walk_option(option, elements, ",".join)
            walked.append(f"{option} {' '.join(e.kind + ' ' + e.shown for e in elements)}")
        elif base == "TEXT":
            for key, kind, shown in SUB_KEY.findall(description):
                element = Element(kind, shown)
                walk.walk_option(option, [element], lambda values, key=key: f"{key}={values[0]}")
                walked.append(f"{option} {key}= {kind} {element.shown}")
        elif base:
            walk.failures.append(f"{option}: type {base!r} is neither numeric nor TEXT: teach this test about it")

    # The defaults run (a control: the accepted runs above mean something).
    walk.expect_accepted("", [], "", allow_rule=False)
    for case in args.case:
        extra = shlex.split(case)
        walk.expect_refused(extra[0], extra)
    for case in args.accept_case:
        extra = shlex.split(case)
        walk.expect_accepted(extra[0], extra, "", allow_rule=False)

    print(f"{args.program}: {len(walked)} numbers walked, {walk.runs} runs:")
    for line in walked:
        print(f"  {line}")
    if not walked:
        walk.failures.append("no numeric option found in --help")
    for failure in walk.failures:
        print(f"FAIL: {failure}")
    return 1 if walk.failures else 0


if __name__ == "__main__":
    sys.exit(main())

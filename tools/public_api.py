#!/usr/bin/python3
"""The public API of the control core: the functions the installed headers declare.

  tools/public_api.py [--check] [--count] [--headers DIR]

Reads every header of firmware/include/tvo (what `cmake --install` installs; firmware/src/internal
is not installed) and lists the functions they declare. --check compares them with
firmware/cmake/tvo_public_api.txt, one name per line, and fails naming any function declared but
not listed (an internal function in an installed header) or listed but not declared. --count prints
only the number; --check also fails unless firmware/README.md states it ("**N functions**"). --headers reads another folder (the CTest
public_api_selftest points it at firmware/src/internal, where the check must fail).
"""
import argparse
import pathlib
import re
import sys

REPO = pathlib.Path(__file__).resolve().parent.parent
HEADERS = REPO / "firmware/include/tvo"
LIST = REPO / "firmware/cmake/tvo_public_api.txt"
README = REPO / "firmware/README.md"

COMMENT = re.compile(r"/\*.*?\*/|//[^\n]*", re.S)
# A declaration or definition at file scope: a return type, the name, its parameter list (not a
# typedef, not a function pointer member, not a macro).
FUNCTION = re.compile(r"^(?!typedef\b)(?:static\s+inline\s+)?[A-Za-z_][\w\s\*]*?\b(tvo_\w+)\s*\(", re.M)


def declared(headers):
    names = {}
    for header in sorted(headers.glob("*.h")):
        text = COMMENT.sub("", header.read_text())
        text = re.sub(r"^#.*?(?<!\\)$", "", text, flags=re.M | re.S)  # preprocessor lines
        for match in FUNCTION.finditer(text):
            names.setdefault(match.group(1), header.name)
    return names


def listed():
    return [line.strip() for line in LIST.read_text().splitlines() if line.strip() and not line.startswith("#")]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--check", action="store_true", help="fail unless the headers declare exactly the list")
    parser.add_argument("--count", action="store_true", help="print the number of public functions")
    parser.add_argument("--headers", type=pathlib.Path, default=HEADERS, help="the folder of headers to read")
    args = parser.parse_args()
    names = declared(args.headers)
    if args.count:
        print(len(names))
        return 0
    if not args.check:
        for name, header in sorted(names.items(), key=lambda item: (item[1], item[0])):
            print(f"{header}: {name}")
        return 0
    expected = listed()
    extra = sorted(set(names) - set(expected))
    missing = sorted(set(expected) - set(names))
    for name in extra:
        print(f"public_api: {names[name]} declares {name}, which is not in {LIST.relative_to(REPO)} "
              "(an internal function belongs in firmware/src/internal)", file=sys.stderr)
    for name in missing:
        print(f"public_api: {name} is listed but no installed header declares it", file=sys.stderr)
    stated = None
    if args.headers == HEADERS:  # the README counts the installed headers, not a --headers folder
        match = re.search(r"\*\*(\d+) functions\*\*", README.read_text())
        stated = int(match.group(1)) if match else None
        if stated != len(names):
            print(f"public_api: {README.relative_to(REPO)} states {stated} functions, the headers declare "
                  f"{len(names)}", file=sys.stderr)
    if extra or missing or len(expected) != len(set(expected)) or (args.headers == HEADERS and stated != len(names)):
        return 1
    print(f"public_api: the installed headers declare the {len(names)} listed functions")
    return 0


if __name__ == "__main__":
    sys.exit(main())

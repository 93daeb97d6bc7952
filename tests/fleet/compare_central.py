#!/usr/bin/python3
"""A scenario run by one central node and by a fleet of one node per robot (tools/fleet --local): the
fleet's figures must match the central node's to 3 significant digits, and the fleet's nodes must agree.

Usage: compare_central.py BUILD_DIR SCENARIO PORT OUT_DIR KEY [KEY ...]
PORT and PORT + 1 are the fleet's, PORT + 2 the central run's (all on loopback, ttl=0).
"""
import json
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent.parent


def same_to_3_digits(a, b):
    return abs(a - b) <= 5e-4 * max(abs(a), abs(b)) or abs(a - b) <= 1e-12


def main():
    build, scenario, port, out = Path(sys.argv[1]), sys.argv[2], int(sys.argv[3]), Path(sys.argv[4])
    keys = sys.argv[5:]
    out.mkdir(parents=True, exist_ok=True)
    central = subprocess.run([str(build / "host/tvo_sim"), "--scenario", scenario, "--sigma", "0",
                              "--firmware", str(build / "firmware/tvo_firmware_node"),
                              "--lcm-url", f"udpm://239.255.76.67:{port + 2}?ttl=0", "--out-dir", str(out / "central")],
                             capture_output=True, text=True)
    if central.returncode != 0:
        print(central.stdout, central.stderr)
        return 1
    fleet = subprocess.run([str(REPO / "tools/fleet"), scenario, "--local", "--port", str(port), "--build-dir",
                            str(build), "--out-dir", str(out / "fleet"), "--json", str(out / "fleet.json")],
                           capture_output=True, text=True)
    if fleet.returncode != 0:
        print(fleet.stdout, fleet.stderr)
        return 1
    a = json.loads((out / "central/summary.json").read_text())
    b = json.loads((out / "fleet.json").read_text())
    failures = []
    for key in keys:
        line = f"{key}: central {a.get(key)!r}, fleet of {b['nodes']} nodes {b.get(key)!r}"
        print(line)
        if a.get(key) is None or b.get(key) is None or not same_to_3_digits(a[key], b[key]):
            failures.append(line)
    for key, want in (("digest_mismatch_periods", 0), ("limit_violations", 0)):
        print(f"{key}: {b[key]}")
        if b[key] != want:
            failures.append(f"{key} = {b[key]}, expected {want}")
    for f in failures:
        print(f"FAIL: {f}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

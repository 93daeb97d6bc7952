#!/usr/bin/python3
"""A scenario run by one central node and by a fleet of one node per robot (tools/fleet --local): the
fleet's figures must match the central node's to 3 significant digits, and the fleet's nodes must agree.
With --one-bus the fleet runs on one URL with no hub (tools/fleet --one-bus): then its run.csv must equal
the central run's byte for byte (both ask the nodes' telemetry every period).

Usage: compare_central.py [--one-bus] BUILD_DIR SCENARIO PORT OUT_DIR KEY [KEY ...]
PORT .. PORT + nodes are the fleet's, the next one the central run's (all on loopback, ttl=0).
"""
import json
import subprocess
import sys
from pathlib import Path

import yaml

REPO = Path(__file__).resolve().parent.parent.parent


def same_to_3_digits(a, b):
    return abs(a - b) <= 5e-4 * max(abs(a), abs(b)) or abs(a - b) <= 1e-12


def robots_of(scenario):
    data = yaml.safe_load(Path(scenario).read_text())
    while "robots" not in data and "base" in data:
        scenario = Path(scenario).parent / data["base"]
        data = yaml.safe_load(Path(scenario).read_text())
    return len(data["robots"])


def main():
    argv = sys.argv[1:]
    one_bus = argv[0] == "--one-bus"
    argv = argv[1:] if one_bus else argv
    build, scenario, port, out = Path(argv[0]), argv[1], int(argv[2]), Path(argv[3])
    keys = argv[4:]
    out.mkdir(parents=True, exist_ok=True)
    central_port = port + (1 if one_bus else robots_of(scenario) + 1)
    central = subprocess.run([str(build / "host/tvo_sim"), "--scenario", scenario, "--sigma", "0", "--telemetry-every", "1",
                              "--firmware", str(build / "firmware/tvo_firmware_node"),
                              "--lcm-url", f"udpm://239.255.76.67:{central_port}?ttl=0", "--out-dir", str(out / "central")],
                             capture_output=True, text=True)
    if central.returncode != 0:
        print(central.stdout, central.stderr)
        return 1
    fleet = subprocess.run([str(REPO / "tools/fleet"), scenario, "--local", "--port", str(port), "--build-dir",
                            str(build), "--out-dir", str(out / "fleet"), "--json", str(out / "fleet.json"),
                            *(["--one-bus"] if one_bus else [])],
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
    if one_bus:
        same = (out / "central/run.csv").read_bytes() == (out / "fleet/run.csv").read_bytes()
        print(f"run.csv: {'identical' if same else 'differs'} (central node, fleet on one bus)")
        if not same:
            failures.append("run.csv of the fleet on one bus differs from the central node's")
    else:
        for key, want in (("digest_mismatch_periods", 0), ("limit_violations", 0)):
            print(f"{key}: {b[key]}")
            if b[key] != want:
                failures.append(f"{key} = {b[key]}, expected {want}")
    for f in failures:
        print(f"FAIL: {f}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

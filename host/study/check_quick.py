#!/usr/bin/env python3
"""CTest "study_quick": runs tvo_study --quick and checks the issue's "Measured" figures in its JSON.

  uncompensated order 1 +/- 0.05; delay ratios 2.0 +/- 0.1 and 3.0 +/- 0.15 (small h);
  compensated tau = h within 5 % of tau = 0 at small h; ZOH-aware order >= 1.8;
  plus: compensation restores the tau = 0 stability edge (exact, to 1e-6 s), the exact edges shrink
  with tau, and no stable run saw a controller status other than TVO_OK.

Usage: check_quick.py <tvo_study> <out_dir>
"""
import json
import os
import subprocess
import sys


def main() -> int:
    study, out_dir = sys.argv[1], sys.argv[2]
    os.makedirs(out_dir, exist_ok=True)
    path = os.path.join(out_dir, "study_quick.json")
    if os.path.exists(path):
        os.remove(path)
    proc = subprocess.run([study, "--quick", "--json", path], capture_output=True, text=True)
    print(proc.stdout)
    if proc.returncode != 0:
        print(f"FAIL: tvo_study --quick exited with {proc.returncode}: {proc.stderr}")
        return 1
    with open(path) as f:
        d = json.load(f)

    failures = 0

    def check(name, value, lo, hi):
        nonlocal failures
        ok = value is not None and lo <= value <= hi
        print(f"{'ok  ' if ok else 'FAIL'} {name} = {value} (want [{lo}, {hi}])")
        failures += 0 if ok else 1

    check("order_tau0", d.get("order_tau0"), 0.95, 1.05)
    check("ratio_tau_half", d.get("ratio_tau_half"), 1.9, 2.1)
    check("ratio_tau_full", d.get("ratio_tau_full"), 2.85, 3.15)
    check("comp_ratio_tau_full", d.get("comp_ratio_tau_full"), 0.95, 1.05)
    check("zoh_aware_order", d.get("zoh_aware_order"), 1.8, float("inf"))
    # Per point too: every small-h compensated tau = h error within 5 % of tau = 0.
    comp = d["compensated"][1]
    small = d["study1"]["small_h_max_s"]
    for row in comp["table"]:
        if row["h_s"] <= small:
            check(f"comp tau=h / tau=0 at h={row['h_s']:g}", row["ratio_to_tau0"], 0.95, 1.05)
    e, ce = d.get("edge_exact_s"), d.get("comp_edge_exact_s")
    check("edge_exact tau=0 > tau=h/2", (e[0] - e[1]) if e else None, 1e-3, float("inf"))
    check("edge_exact tau=h/2 > tau=h", (e[1] - e[2]) if e else None, 1e-3, float("inf"))
    for i, name in enumerate(["tau=h/2", "tau=h"], start=1):
        check(f"comp edge {name} - tau=0 edge", (ce[i] - ce[0]) if ce else None, -1e-6, 1e-6)
    sim = d.get("edge_sim_s")
    for i in range(3):
        # a finite simulated edge, at or above the exact one (a 20 s run cannot diverge visibly below it)
        check(f"edge_sim[{i}] - edge_exact[{i}]", (sim[i] - e[i]) if sim and sim[i] is not None else None,
              -0.005, 0.2)
    bad = sum(c["not_ok_steps"] for c in d["study1"]["curves"])
    check("controller steps not TVO_OK", bad, 0, 0)
    print(f"{failures} check(s) failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Tunes the law's gains k_p, k_d against a target: a grid of closed loops through the firmware's
own core (float32, bit for bit what the board computes), scored by the RMS tracking error after the
transient. Run with the venv's python after `pip install ./host/python` (host/python/README.md), or
with PYTHONPATH=<build>/host/python /usr/bin/python3; --quick: a small grid (the test's).

    v/bin/python host/python/examples/tune_gains.py [--quick]
"""
import sys

import numpy as np

import tvo

problem = tvo.Problem(robots=1).track(0, tvo.ellipse(center_m=(0, 0), semi_axis_m=(3, 1.5), omega_radps=2 * np.pi / 10))
start = [[-1.0, -2.0, 0.0]]  # x, y, heading: off the ellipse, at rest


def score(kp, kd, seconds=10.0, period_s=0.01):
    """RMS tracking error over the second half of a closed loop, in m."""
    ctl = tvo.UnicycleController(problem, period_s=period_s, gain_kp=kp, gain_kd=kd)
    loop = ctl.run(start, steps=int(seconds / period_s))
    error = loop.tracking_error(problem)[:, 0]
    return float(np.sqrt(np.mean(error[len(error) // 2:] ** 2)))


quick = "--quick" in sys.argv
grid = [(kp, kd) for kp in ([10, 40] if quick else [5, 10, 20, 40, 80])
        for kd in ([4, 13] if quick else [3, 6, 9, 13, 18])]  # s^2 + k_d s + k_p: Hurwitz for k_p, k_d > 0
results = {(kp, kd): score(kp, kd, seconds=6.0 if quick else 10.0) for kp, kd in grid}
for (kp, kd), rms in sorted(results.items(), key=lambda item: item[1]):
    print(f"k_p = {kp:5.1f}  k_d = {kd:5.1f}  RMS error {rms * 1000:8.3f} mm")
best = min(results, key=results.get)
print(f"best: k_p = {best[0]}, k_d = {best[1]} (tvo_sim --gains {best[0]},{best[1]})")
# The law is exponentially stable for any Hurwitz pair: every run must track, the best to a few mm.
assert all(np.isfinite(r) for r in results.values()) and results[best] < 0.01, results

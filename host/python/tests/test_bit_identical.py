#!/usr/bin/python3
"""The `tvo` module steps the core bit for bit as the firmware build of the same precision does.

Runs the same closed loops (exact unicycle plants, the core's controller) through Python
(tvo.UnicycleController.run) and through closed_loop_ref.c linked with the firmware's host build of
the core (tvo_core in float32, tvo_core_double in float64: the core tvo_firmware_node runs) and with
the shared library the module calls, and compares every period's outcome, reason, flags, command bits (speed,
turn rate as tvo_real_t) and the plant's pose bits.

Not compared: the Cortex-M4F build, which links newlib's expf/logf instead of glibc's (the PIL test,
tests/target/pil_check.py, bounds that difference).

Usage: test_bit_identical.py REF_F32 REF_F64 REF_SO_F32 REF_SO_F64   (PYTHONPATH: <build>/host/python)
"""
import math
import subprocess
import sys

import numpy as np

import tvo

CASES = [  # (case, steps, kp, kd, zoh)
    (0, 1500, 40.0, 13.0, 0),
    (0, 500, 25.0, 9.0, 1),
    (1, 800, 40.0, 13.0, 0),
]


def problem(case):
    """closed_loop_ref.c's make_problem, value for value."""
    if case == 0:
        p = tvo.Problem(1).track(0, tvo.ellipse((0.0, 0.0), (3.0, 1.5), 0.6283185307179586))
        p.add_obstacle((2.0, -1.0), 0.5)
        p.robot_radius_m = 0.2
        return p, [[-1.0, -2.0, 0.0]]
    p = tvo.Problem(2)
    p.track(0, tvo.polynomial([[-2.0, 0.5, 0.01], [0.0, 0.2, -0.005]]))
    p.track(1, tvo.polynomial([[2.0, -0.5, 0.0], [0.5, 0.1, 0.002]]), weight=(2.0, 0.5))
    p.add_distance_bound(0, 1, min_m=0.8)
    p.add_halfspace(1, (0.0, 1.0), 1.5)
    p.barrier["c0"] = 2.0
    return p, [[-2.5, -0.5, 0.3], [2.2, 0.0, 2.8]]


def python_lines(precision, case, steps, kp, kd, zoh):
    p, start = problem(case)
    ctl = tvo.UnicycleController(p, precision, tick_hz=1000000, period_ticks=10000, delay_ticks=5000,
                                 gain_kp=kp, gain_kd=kd, zoh_aware=zoh)
    loop = ctl.run(start, steps, measure_speed=(case == 1))
    bits = np.uint32 if precision == "float32" else np.uint64
    width = 8 if precision == "float32" else 16
    v = loop.speed_mps.view(bits)
    w = loop.turn_rate_radps.view(bits)
    pose = loop.poses[1:].view(np.uint64)
    lines = []
    for k in range(steps):
        fields = [str(k), str(int(loop.outcome[k])), str(int(loop.reason[k])), str(int(loop.flags[k]))]
        for r in range(v.shape[1]):
            fields += [f"{int(v[k, r]):0{width}x}", f"{int(w[k, r]):0{width}x}"]
            fields += [f"{int(b):016x}" for b in pose[k, r]]
        lines.append(" ".join(fields))
    return lines, loop


def main(argv):
    refs = {"float32": argv[1], "float64": argv[2]}
    failures = 0
    for precision, ref, lib_ref in [("float32", argv[1], argv[3]), ("float64", argv[2], argv[4])]:
        for case, steps, kp, kd, zoh in CASES:
            args = [str(case), str(steps), repr(kp), repr(kd), str(zoh)]
            c_lines = subprocess.run([ref, *args], capture_output=True, text=True, check=True).stdout.splitlines()
            lib_lines = subprocess.run([lib_ref, *args], capture_output=True, text=True, check=True).stdout.splitlines()
            py_lines, loop = python_lines(precision, case, steps, kp, kd, zoh)
            if lib_lines != c_lines:
                print(f"FAIL: {precision} case {case}: the module's shared library and the firmware's host build "
                      "of the core differ in C")
                failures += 1
            label = f"{precision} case {case} kp={kp} kd={kd} zoh={zoh}, {steps} periods"
            ok_steps = int(np.sum(loop.outcome == 0))
            if c_lines == py_lines:
                print(f"ok: {label}: every period identical (outcome, reason, flags, command bits, plant bits) in "
                      f"Python, C on the firmware's core build and C on the module's library; {ok_steps} applied steps")
                if ok_steps < steps // 2:
                    print(f"FAIL: {label}: fewer than half of the steps applied a command: the loop tests little")
                    failures += 1
                continue
            failures += 1
            first = next((k for k, (a, b) in enumerate(zip(c_lines, py_lines)) if a != b), min(len(c_lines), len(py_lines)))
            print(f"FAIL: {label}: first difference at period {first} "
                  f"({len(c_lines)} C lines, {len(py_lines)} Python lines)\n  C:      "
                  f"{c_lines[first] if first < len(c_lines) else '-'}\n  Python: "
                  f"{py_lines[first] if first < len(py_lines) else '-'}")
    # The comparison can fail: float32 from Python against the float64 C loop must differ.
    c_lines = subprocess.run([refs["float64"], "0", "50", "40.0", "13.0", "0"], capture_output=True, text=True,
                             check=True).stdout.splitlines()
    if c_lines == python_lines("float32", 0, 50, 40.0, 13.0, 0)[0]:
        print("FAIL: float32 Python matched the float64 C loop: the comparison compares nothing")
        failures += 1
    # The loop must be a real test: the final tracking error of case 0 in float32 is small.
    _, loop = python_lines("float32", 0, 1500, 40.0, 13.0, 0)
    p, _ = problem(0)
    err = loop.tracking_error(p)[-1, 0]
    print(f"case 0 float32: tracking error after 15 s {err:.4f} m")
    if not math.isfinite(err) or err > 0.5:
        print("FAIL: the closed loop does not track")
        failures += 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

#!/usr/bin/python3
"""tvo.export_c writes C a firmware compiles, and its values round-trip exactly.

For every scenario of host/scenarios (waypoint targets solved by the host's own code through
tvo_scenario_export) and a hand-built problem using every kind of entry, in float32 and float64:
  - the exported header compiles with the host's gcc and the project's warnings as errors, with
    export_roundtrip.c, linked with the core of that precision; run, it builds the problem and the
    controller settings through the core, and the bytes of its tvo_problem_desc_t and
    tvo_controller_config_t must equal those the `tvo` module built from the same description;
  - float32: the header also compiles for a Cortex-M4F with arm-none-eabi-gcc (if installed).

Usage: test_export_c.py CC ARM_CC ROUNDTRIP_C LIBTVO_F32 LIBTVO_F64 SCENARIO_DIR
"""
import glob
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

import tvo
from tvo import _build_paths

WARNINGS = ["-Wall", "-Wextra", "-Wpedantic", "-Werror", "-Wconversion", "-Wsign-conversion", "-Wdouble-promotion",
            "-Wfloat-conversion", "-Wshadow", "-Wcast-qual", "-Wcast-align", "-Wvla", "-Wstrict-prototypes",
            "-Wmissing-prototypes", "-Wundef", "-Wswitch-enum", "-Wformat=2", "-Wnull-dereference"]
CORTEX_M4F = ["-mcpu=cortex-m4", "-mthumb", "-mfpu=fpv4-sp-d16", "-mfloat-abi=hard"]


def handmade():
    p = tvo.Problem(2)
    p.track(0, tvo.circle((0.5, -0.25), 2.0, 0.7, phase_rad=0.1), weight=(1.5, 0.75))
    p.track(1, tvo.ellipse((0.0, 1.0), (2.5, 1.25), -0.3, phase_rad=1.0, rotation_rad=0.2))
    p.add_halfspace(0, (0.6, 0.8), 3.0, normal_rate=(0.0, 0.01), bound_rate_mps=0.05)
    p.add_distance_bound(0, 1, min_m=0.5, max_m=6.0, max_rate_mps=-0.01)
    p.add_obstacle((5.0, 5.0), 0.3)
    p.robot_radius_m = 0.1
    p.add_offset(0, 1, tvo.polynomial([[0.1, 0.01], [-0.2]]))
    p.barrier.update({"c0": 2.0, "relaxation_degree": 5})
    p.robots[1]["initial_speed_mps"] = 0.25
    return p


class Handmade:
    name = "handmade"
    problem = handmade()
    starts = np.array([[2.5, -0.25, 1.6], [2.5, 1.0, 1.6]])
    controller = {"period_ticks": 20000, "delay_ticks": 4000, "gain_kp": 30.0, "gain_kd": 11.0, "zoh_aware": 1,
                  "omega_max_radps": 2 * math.pi}


def module_bytes(source, precision):
    ctl = tvo.UnicycleController(source.problem, precision, **source.controller)
    ffi = ctl.core.ffi
    start = ffi.new("tvo_real_t[]", [float(v) for v in np.asarray(source.starts).ravel()])
    return {"desc": bytes(ffi.buffer(ctl.built.desc)).hex(), "config": bytes(ffi.buffer(ctl.config)).hex(),
            "start": bytes(ffi.buffer(start)).hex()}


def main(argv):
    cc, arm_cc, roundtrip_c, libs, scenario_dir = argv[1], argv[2], argv[3], argv[4:6], argv[6]
    includes = [f"-I{d}" for d in _build_paths.INCLUDE_DIRS if d]
    sources = [tvo.load_scenario(path) for path in sorted(glob.glob(os.path.join(scenario_dir, "*.yaml")))]
    sources.append(Handmade())
    failures, arm_checked = 0, 0
    with tempfile.TemporaryDirectory() as tmp:
        for source in sources:
            with open(os.path.join(tmp, "scenario_export.h"), "w", encoding="utf-8") as f:
                f.write(tvo.export_c(source, "scenario"))
            for precision, lib in zip(tvo.PRECISIONS, libs):
                label = f"{source.name} ({precision})"
                exe = os.path.join(tmp, f"roundtrip_{precision}")
                double = "1" if precision == "float64" else "0"
                build = subprocess.run([cc, "-std=c11", *WARNINGS, f"-DTVO_USE_DOUBLE={double}", f"-I{tmp}", *includes,
                                        roundtrip_c, "-o", exe, lib, f"-Wl,-rpath,{os.path.dirname(lib)}", "-lm"],
                                       capture_output=True, text=True)
                if build.returncode != 0:
                    print(f"FAIL: {label}: the export does not compile:\n{build.stderr}")
                    failures += 1
                    continue
                run = subprocess.run([exe], capture_output=True, text=True)
                if run.returncode != 0:
                    print(f"FAIL: {label}: {run.stderr.strip()}")
                    failures += 1
                    continue
                c_bytes = dict(line.split(" ", 1) for line in run.stdout.splitlines())
                py_bytes = module_bytes(source, precision)
                bad = [k for k in py_bytes if c_bytes.get(k) != py_bytes[k]]
                if bad:
                    print(f"FAIL: {label}: {', '.join(bad)} differ between the C export and the module")
                    failures += 1
                else:
                    print(f"ok: {label}: compiles (-Werror), problem and controller bytes identical "
                          f"({len(py_bytes['desc']) // 2} + {len(py_bytes['config']) // 2} bytes)")
            if arm_cc and os.path.exists(arm_cc):
                obj = os.path.join(tmp, "roundtrip_m4f.o")
                build = subprocess.run([arm_cc, "-std=c11", *CORTEX_M4F, "-O2", *WARNINGS, "-DTVO_USE_DOUBLE=0",
                                        f"-I{tmp}", *includes, "-c", roundtrip_c, "-o", obj],
                                       capture_output=True, text=True)
                if build.returncode != 0:
                    print(f"FAIL: {source.name}: the export does not compile for Cortex-M4F:\n{build.stderr}")
                    failures += 1
                else:
                    arm_checked += 1
    if arm_cc and os.path.exists(arm_cc):
        print(f"arm-none-eabi-gcc (Cortex-M4F, float32): {arm_checked} of {len(sources)} exports compile")
    else:
        print("arm-none-eabi-gcc not found: the Cortex-M4F compile was not checked (tools/setup bench installs it)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

#!/usr/bin/python3
"""tools/lib/run_folder.py's rule (CTest tools_run_folder): a run with the defaults writes runs/NAME,
each variant its own runs/NAME-OPTION-VALUE... (the demo's variants never overwrite runs/demo), and
options that only say where a run writes or talks name no folder."""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools/lib"))
from run_folder import MAX_NAME, run_folder  # noqa: E402

CASES = [
    (("demo", []), "runs/demo"),
    (("demo", ["--sigma", "1e-3"]), "runs/demo-sigma-1e-3"),
    (("demo", ["--sigma=1e-3"]), "runs/demo-sigma-1e-3"),
    (("demo", ["--position-only"]), "runs/demo-position-only"),
    (("demo", ["--realtime", "--pil"]), "runs/demo-realtime-pil"),
    (("demo", ["--key-file", "/home/me/keys/robot.key"]), "runs/demo-key-file-robot.key"),
    (("demo", ["--gains", "-1,2"]), "runs/demo-gains--1,2"),
    (("demo", ["--lcm-url", "udpm://239.255.76.67:7667?ttl=0", "--firmware", "x", "--answer-timeout-s", "5"]),
     "runs/demo"),
    (("obstacles", ["--sigma", "1e-3", "--position-only"]), "runs/obstacles-sigma-1e-3-position-only"),
    (("fleet-formation8", ["--fleet", "--loss", "0.1", "--local", "--json", "out.json", "--check", "collisions==0"]),
     "runs/fleet-formation8-fleet-loss-0.1"),
    (("my scenario", ["--seed", "a b"]), "runs/my_scenario-seed-a_b"),
]
failures = [f"{args}: {run_folder(*args)!r}, expected {want!r}" for args, want in CASES if run_folder(*args) != want]
long_a = run_folder("demo", ["--seed", "1" * 200])
long_b = run_folder("demo", ["--seed", "1" * 199])
if len(Path(long_a).name) > MAX_NAME or long_a == long_b:
    failures.append(f"long names: {long_a!r} and {long_b!r} (at most {MAX_NAME} characters, distinct)")
for f in failures:
    print("FAIL:", f)
print(f"{len(CASES) + 1 - len(failures)} of {len(CASES) + 1} cases hold")
sys.exit(1 if failures else 0)

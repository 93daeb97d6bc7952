#!/usr/bin/python3
"""tools/fleet as a user meets it (CTests fleet_tool_*), on loopback (--local) with the build's programs.

Usage: fleet_tool.py CASE BUILD_DIR PORT OUT_DIR
  summary    fleet-formation.yaml with 10 % loss: exit 0; the human summary (final error, collisions,
             clearance, the disagreement, what it is and its bound); the run folder holds summary.json
             (what --json wrote, the same), run.csv, run.png, hub.json, logs/; 4 robots run on
             tvo_firmware_node (the smallest node that takes them); --json - prints the JSON instead
  collision  tests/scenario_files/collision.yaml (two robots meet): exit 3 after writing every output,
             the plot made, the collision in summary.json and in the summary
  refuse     a broken file is refused as tvo_sim refuses it (exit 2, FILE:LINE:COLUMN), before the tool
             asks for a node or the hub: a build folder holding tvo_sim alone does not make it fail on
             them; so is a folder given as the file
"""
import json
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
FLEET = REPO / "tools/fleet"


def run(args, **kwargs):
    done = subprocess.run([sys.executable, str(FLEET), *map(str, args)], capture_output=True, text=True, **kwargs)
    print(f"$ tools/fleet {' '.join(map(str, args))}\nexit {done.returncode}\n--- stdout\n{done.stdout}--- stderr\n"
          f"{done.stderr}---")
    return done


def expect(failures, condition, what):
    if not condition:
        failures.append(what)


def case_summary(build, port, out, failures):
    scenario = REPO / "host/scenarios/fleet-formation.yaml"
    common = [scenario, "--local", "--port", port, "--build-dir", build, "--loss", "0.1"]
    done = run([*common, "--out-dir", out / "run", "--json", out / "run.json"])
    expect(failures, done.returncode == 0, f"exit {done.returncode}, expected 0")
    for text in ("final tracking error", "collisions", "min clearance", "closest pair of robots",
                 "nodes' disagreement", "twice the limits", "The disagreement: every node computes",
                 "What bounds it under loss", "outputs: "):
        expect(failures, text in done.stdout, f"the summary lacks '{text}'")
    expect(failures, not done.stdout.lstrip().startswith("{"), "the summary is JSON, not for a human")
    for name in ("summary.json", "run.csv", "run.png", "hub.json", "scenario.json", "run.lcmlog", "logs/sim.log"):
        path = out / "run" / name
        expect(failures, path.exists() and path.stat().st_size > 0, f"missing or empty {path}")
    if (out / "run/summary.json").exists() and (out / "run.json").exists():
        summary = json.loads((out / "run/summary.json").read_text())
        expect(failures, summary == json.loads((out / "run.json").read_text()), "--json wrote another JSON")
        expect(failures, summary.get("node_binary") == "tvo_firmware_node",
               f"4 robots ran on {summary.get('node_binary')}, expected tvo_firmware_node")
        for key in ("final_error_m", "collisions", "digest_mismatch_periods",
                    "min_pair_distance_m", "limit_violations", "dropped_samples"):
            expect(failures, key in summary, f"summary.json lacks {key}")
    done = run([*common, "--out-dir", out / "json", "--json", "-"])
    try:
        printed = json.loads(done.stdout)
        expect(failures, printed.get("robots") == 4, f"--json - printed robots {printed.get('robots')}")
    except json.JSONDecodeError:
        failures.append("--json - did not print JSON alone")


def case_collision(build, port, out, failures):
    done = run([REPO / "tests/scenario_files/collision.yaml", "--local", "--port", port, "--build-dir", build,
                "--out-dir", out / "run"])
    expect(failures, done.returncode == 3, f"exit {done.returncode}, expected 3 (a collision)")
    expect(failures, "collision(s) (exit code 3" in done.stderr, "stderr does not say the run collided")
    for name in ("run.png", "run.csv", "summary.json"):
        expect(failures, (out / "run" / name).exists(), f"missing {name}")
    if (out / "run/summary.json").exists():
        summary = json.loads((out / "run/summary.json").read_text())
        expect(failures, summary.get("collisions", 0) >= 1 and summary.get("collision_events"),
               f"summary.json: collisions {summary.get('collisions')}, events {summary.get('collision_events')}")
    expect(failures, "(the first: robot" in done.stdout, "the summary does not say where the collision was")


def case_refuse(build, port, out, failures):
    only_sim = out / "only-sim/host"
    only_sim.mkdir(parents=True, exist_ok=True)
    (only_sim / "tvo_sim").unlink(missing_ok=True)
    (only_sim / "tvo_sim").symlink_to(Path(build) / "host/tvo_sim")
    broken = REPO / "tests/scenario_files/broken/bad_value.yaml"
    done = run([broken, "--local", "--build-dir", out / "only-sim", "--out-dir", out / "run"])
    expect(failures, done.returncode == 2, f"exit {done.returncode}, expected 2")
    expect(failures, f"{broken}:10:15: obstacles[1].radius_m: must be > 0 (got -1)" in done.stderr,
           "the refusal does not name FILE:LINE:COLUMN and the field as tvo_sim does")
    expect(failures, "not built" not in done.stderr, "it asked for programs before refusing the file")
    done = run([broken.parent, "--local", "--build-dir", out / "only-sim"])
    expect(failures, done.returncode == 2 and "is a folder, not a scenario file" in done.stderr,
           "a folder given as the file is not named as one")


def main():
    case, build, port, out = sys.argv[1], sys.argv[2], sys.argv[3], Path(sys.argv[4])
    out.mkdir(parents=True, exist_ok=True)
    failures = []
    {"summary": case_summary, "collision": case_collision, "refuse": case_refuse}[case](build, port, out, failures)
    for f in failures:
        print(f"FAIL: {f}")
    print("ok" if not failures else f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

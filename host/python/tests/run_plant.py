#!/usr/bin/python3
"""host/python/examples/plant.py against a built tvo_firmware_node on a keyed bus, in lockstep.

  converge: one node, the demo's 20 s; the plant's final error must equal the demo's
            (tools/figures/summaries/demo.json, tvo_sim's run of the same setting) to 3 significant
            digits, the node must exit after the plant's STOP, having accepted all 2,000 samples and
            dropped no frame (unauthenticated=0 replayed=0 malformed=0).
  restart:  rule 5: the node is killed amid the session and a new one starts on the same boot file
            (a higher boot id); the plant must stop its robot, START a new session naming the new boot
            (restarts>=1), which the new node takes, and still converge (final error below 1e-3 m, the
            closed-loop tests' bound for the demo).
  silent:   rule 5: the node is frozen (SIGSTOP) amid the session for longer than the plant's watchdog
            (10 samples unanswered), then resumed; the plant must stop its robot and repeat the same
            START, which the node acks (the same session, the same boot), and still converge (1e-3 m).

Usage: run_plant.py MODE NODE PLANT_PY DEMO_JSON LCM_URL WORK_DIR   (PYTHONPATH: <build>/host/python)
"""
import json
import os
import re
import signal
import subprocess
import sys
import time

# A test key (tools/keygen makes real ones).
KEY_HEX = "00112233445566778899aabbccddeeff0123456789abcdeffedcba9876543210"


def start_node(node, url, key, boot, log):
    return subprocess.Popen([node, "--key-file", key, "--lcm-url", url, "--boot-file", boot, "--exit-with-parent"],
                            stdout=subprocess.DEVNULL, stderr=open(log, "w"))


def counts(log):
    """The node's exit line: key=value counts."""
    with open(log, encoding="utf-8") as f:
        text = f.read()
    line = re.search(r"counts (.*)", text)
    if not line:
        sys.exit(f"the node printed no counts line:\n{text}")
    return {k: int(v) for k, v in re.findall(r"(\w+)=(-?\d+)", line.group(1))}


def wait_for(log, pattern, timeout_s):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        with open(log, encoding="utf-8") as f:
            if re.search(pattern, f.read()):
                return True
        time.sleep(0.01)
    return False


def main():
    try:
        import lcm  # noqa: F401  (plant.py's; built from Debian's lcm source by tools/setup python)
    except ImportError as e:
        print(f"skipped: LCM's Python module is not built ({e}): tools/setup python fetches Debian's lcm source")
        sys.exit(77)
    if len(sys.argv) != 7 or sys.argv[1] not in ("converge", "restart", "silent"):
        sys.exit(__doc__)
    mode, node, plant_py, demo_json, url, work = sys.argv[1:]
    os.makedirs(work, exist_ok=True)
    key, boot = os.path.join(work, "bus.key"), os.path.join(work, "node.boot")
    with open(os.open(key, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600), "w", encoding="ascii") as f:
        f.write(KEY_HEX + "\n")
    os.chmod(key, 0o600)
    logs = [os.path.join(work, f"node{i}.log") for i in (1, 2)]
    first = start_node(node, url, key, boot, logs[0])
    plant = subprocess.Popen([sys.executable, plant_py, "--key-file", key, "--lcm-url", url],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    nodes = [first]
    if mode in ("restart", "silent"):
        # amid the session: once the node took the START (the plant's 2,000 samples take about a second
        # after it), so that most of the 20 s are left to converge again
        if not wait_for(logs[0], r"START of session \d+ done", 30):
            plant.kill()
            sys.exit("the first node never took a START")
    if mode == "restart":       # the node dies; a new boot starts
        first.send_signal(signal.SIGKILL)
        first.wait()
        nodes.append(start_node(node, url, key, boot, logs[1]))
    elif mode == "silent":      # frozen past the plant's watchdog (10 x plant.py's 0.5 s wait), then back
        first.send_signal(signal.SIGSTOP)
        time.sleep(6.5)
        first.send_signal(signal.SIGCONT)
    out, err = plant.communicate(timeout=120)
    print(out + err, end="")
    codes = [n.wait(timeout=30) for n in nodes[-1:]]
    if plant.returncode != 0 or codes != [0]:
        sys.exit(f"exit codes: plant {plant.returncode}, node {codes} (expected 0, [0])")
    got = dict(re.findall(r"(\w+)=(\S+)", out))
    final_error = float(got["final_error_m"])
    last = counts(logs[len(nodes) - 1])
    print(f"node {len(nodes)} counts: {last}")
    for name in ("unauthenticated", "replayed", "malformed"):
        if last[name] != 0:
            sys.exit(f"the node dropped genuine frames: {name}={last[name]}")
    if int(got["dropped_frames"]) != 0:
        sys.exit(f"the plant dropped {got['dropped_frames']} frame(s) of the node")
    if mode == "converge":
        with open(demo_json, encoding="utf-8") as f:
            demo_error = json.load(f)["final_error_m"]
        if last["accepted"] != 2000 or last["sessions"] != 1 or got["restarts"] != "0":
            sys.exit(f"expected one session of 2000 accepted samples and no restart: {last}, "
                     f"restarts={got['restarts']}")
        if f"{final_error:.2e}" != f"{demo_error:.2e}":
            sys.exit(f"final error {final_error:.6g} m is not the demo's {demo_error:.6g} m to 3 significant digits")
        print(f"the demo's final error to 3 significant digits: {final_error:.6g} m (demo.json {demo_error:.6g} m)")
    elif mode == "silent":
        with open(logs[0], encoding="utf-8") as f:
            first_boot = int(re.search(r"boot (\d+)", f.read()).group(1))
        if int(got["restarts"]) < 1 or last["sessions"] != 1 or last["boot_id"] != first_boot:
            sys.exit(f"expected the plant to repeat the same START to the same boot: "
                     f"restarts={got['restarts']}, {last}")
        if not final_error < 1e-3:
            sys.exit(f"did not converge after the silence: final error {final_error:.6g} m, bound 1e-3 m")
        print(f"repeated its START after the silence, converged: {final_error:.6g} m < 1e-3 m")
    else:
        if int(got["restarts"]) < 1 or last["sessions"] != 1 or last["accepted"] < 1 or last["boot_id"] < 2:
            sys.exit(f"expected the plant to START again on the new boot: restarts={got['restarts']}, node 2: {last}")
        if not final_error < 1e-3:
            sys.exit(f"did not converge after the restart: final error {final_error:.6g} m, bound 1e-3 m")
        print(f"restarted on boot {last['boot_id']}, converged: {final_error:.6g} m < 1e-3 m")


if __name__ == "__main__":
    main()

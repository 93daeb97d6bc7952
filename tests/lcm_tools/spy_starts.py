#!/usr/bin/python3
"""tools/spy as a user runs it, under xvfb-run: lcm-spy starts, finds every message type of the project
in the jar tools/spy puts on the CLASSPATH, and listens on the --lcm-url given (LCM reports ttl=0,
which only that URL carries). Without a display tools/spy refuses with exit 2 and says why.
(The live decoding of a run by lcm-spy is checked by record_and_convert.py --xvfb-run.)

Usage: spy_starts.py --xvfb-run XVFB_RUN --spy TOOLS_SPY --lcm-url URL --types N
"""
import argparse
import os
import signal
import subprocess
import sys
import threading

START_TIMEOUT_S = 180.0  # a JVM and Xvfb on a loaded machine (and tools/spy's up-to-date check)


def fail(message):
    print(f"FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--xvfb-run", required=True)
    p.add_argument("--spy", required=True)
    p.add_argument("--lcm-url", required=True)
    p.add_argument("--types", type=int, required=True)
    args = p.parse_args()

    no_display = {k: v for k, v in os.environ.items() if k != "DISPLAY"}
    refused = subprocess.run([args.spy, "--lcm-url", args.lcm_url], env=no_display, capture_output=True, text=True)
    if refused.returncode != 2 or "DISPLAY" not in refused.stderr:
        fail(f"tools/spy without a display: exit {refused.returncode}, {refused.stderr!r}")

    expected = [f"Found {args.types} LCM types", "TTL set to zero"]
    # Its own session: the whole group (xvfb-run, Xvfb, java) is stopped at the end.
    proc = subprocess.Popen([args.xvfb_run, "-a", args.spy, "--lcm-url", args.lcm_url], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, start_new_session=True)
    lines = []
    seen = threading.Event()

    def read():
        for line in proc.stdout:
            lines.append(line)
            if all(any(e in l for l in lines) for e in expected):
                seen.set()
        seen.set()

    threading.Thread(target=read, daemon=True).start()
    seen.wait(START_TIMEOUT_S)
    running = proc.poll() is None
    if running:
        os.killpg(proc.pid, signal.SIGTERM)
    proc.wait(timeout=60)
    text = "".join(lines)
    print(text, end="")
    missing = [e for e in expected if e not in text]
    if missing or not running:
        fail(f"lcm-spy through tools/spy: missing {missing} in its output, still running: {running}")
    if "Exception" in text:
        fail("lcm-spy reported an exception")
    print(f"OK: tools/spy started lcm-spy with {args.types} types on {args.lcm_url}")


if __name__ == "__main__":
    main()

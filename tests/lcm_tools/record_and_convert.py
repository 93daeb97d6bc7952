#!/usr/bin/python3
"""LCM's own tools on a real run: tools/log2csv (tvo_log2csv) turns the run's LCM log into the run CSV,
tools/plot_run.py plots it, and lcm-spy's own type database (SpyDecode.java) decodes the same log with
the generated Java classes. Realtime: lcm-logger records the run on its own LCM URL, as it would a
robot. Lockstep: the simulator's own run.lcmlog (a lockstep run sends its messages as fast as the
machine goes, and lcm-logger, behind UDP, may lose some of a burst; the exact checks need all).

Checks (none depends on the machine's speed):
  - log2csv's header is the simulator's (one contract); every value is finite
  - one row per robot per period: as many as the Java decoder found samples in the log, and at least
    MIN_RECORDED_FRACTION of the run's steps (lcm-logger listens on UDP; lockstep: all of them)
  - realtime: an undecodable message recorded before the run is counted and reported by log2csv
  - the rows' times are the session's sample instants (epoch + (n + 1) h - tau) and increase
  - Java and C++ decode the same positions; the reference column is robot 0's target as Java read
    it from the START's nested robot_t / path_t
  - lockstep with tau = 0 and no noise (a scenario with obstacles, so the barrier's telemetry is not
    0): every column but the heading equals the simulator's CSV row for row; realtime: the final
    error agrees with summary.json's within ERROR_TOLERANCE_M
  - plot_run.py writes its figure
  - with --xvfb-run: lcm-spy's own window, started before the run (SpyProbe.java), found every type
    and matched and decoded every channel the recording holds with the same class, without error
"""
import argparse
import csv
import json
import math
import os
import re
import signal
import socket
import struct
import subprocess
import sys
import threading
import time

# lcm-logger listens on UDP: under load a few datagrams may be lost; the run must still be there.
MIN_RECORDED_FRACTION = 0.9
# Realtime: our final row is the last sample (tau before the sim's last row) and the measured pose.
ERROR_TOLERANCE_M = 0.02
# %.9g in the CSV against Java's full double.
REL_TOL = 1e-8
LOGGER_START_TIMEOUT_S = 30.0
LOGGER_STOP_TIMEOUT_S = 30.0
SPY_START_TIMEOUT_S = 120.0  # a JVM and Xvfb on a loaded machine: generous, only a ceiling
PROBE_CHANNEL = "TVO_TELEMETRY"  # one of firmware/edge/channels.h's; the test checks log2csv counts it
PROBE_PAYLOAD = b"bad"           # shorter than a fingerprint: undecodable
LCM_SELF_TEST_CHANNEL = "LCM_SELF_TEST"  # LCM's own start-up datagrams: no type of ours
END_CHANNEL = "TVO_TEST_LOG_END"  # the test's last datagram: recorded means everything before is


def fail(message):
    print(f"FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def run(cmd, **kwargs):
    print("+", " ".join(cmd), flush=True)
    return subprocess.run(cmd, **kwargs)


def close(a, b, abs_tol=1e-12):
    return math.isclose(a, b, rel_tol=REL_TOL, abs_tol=abs_tol)


def read_csv(path):
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        return header, [dict(zip(header, row)) for row in reader]


def publish_raw(url, channel, payload, seqno):
    """One small LCM datagram (header "LC02", sequence, channel, NUL, payload) to a udpm:// URL."""
    m = re.match(r"udpm://([0-9.]+):(\d+)", url)
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM, socket.IPPROTO_UDP) as s:
        s.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)  # loopback only, as ?ttl=0
        s.sendto(struct.pack(">II", 0x4C433032, seqno) + channel.encode() + b"\0" + payload,
                 (m.group(1), int(m.group(2))))


def publish_until_recorded(proc, url, log_path, channel, payload):
    """Publishes a datagram on channel every 50 ms until lcm-logger has written one to log_path."""
    deadline = time.monotonic() + LOGGER_START_TIMEOUT_S
    seqno = 0
    while not (os.path.exists(log_path) and channel.encode() in open(log_path, "rb").read()):
        if proc.poll() is not None or time.monotonic() > deadline:
            proc.kill()
            fail(f"lcm-logger did not record {channel} within {LOGGER_START_TIMEOUT_S} s: {proc.stdout.read()}")
        publish_raw(url, channel, payload, seqno)
        seqno += 1
        time.sleep(0.05)


def start_logger(logger, url, log_path):
    """lcm-logger, once it records: it opens its file before it subscribes, so a probe must come
    through. The probe is a message of the protocol's channel TVO_TELEMETRY too short to decode:
    log2csv must count and skip it (nobody else listens yet: the run starts after)."""
    proc = subprocess.Popen([logger, "-f", "--flush-interval=20", f"--lcm-url={url}", log_path],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    publish_until_recorded(proc, url, log_path, PROBE_CHANNEL, PROBE_PAYLOAD)
    return proc


def stop_logger(proc, url, log_path):
    """SIGINT, once lcm-logger has caught up: it drops what it has not yet read when it exits."""
    publish_until_recorded(proc, url, log_path, END_CHANNEL, b"")
    proc.send_signal(signal.SIGINT)
    try:
        out, _ = proc.communicate(timeout=LOGGER_STOP_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        proc.kill()
        fail("lcm-logger did not stop on SIGINT")
    print(out, end="")


def start_spy(args):
    """SpyProbe (lcm-spy's window) under xvfb-run, once lcm-spy has subscribed."""
    cmd = [args.xvfb_run, "-a", args.java, "-cp", args.classpath, "SpyProbe", args.lcm_url]
    print("+", " ".join(cmd), flush=True)
    proc = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    lines = []
    ready = threading.Event()

    def read():
        for line in proc.stdout:
            lines.append(line)
            if line.strip() == "spy ready":
                ready.set()
        ready.set()  # ended: the caller sees whether "spy ready" came

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    if not ready.wait(SPY_START_TIMEOUT_S) or "spy ready\n" not in lines:
        proc.kill()
        fail(f"lcm-spy did not start under xvfb-run: {''.join(lines)}")
    return proc, reader, lines


def stop_spy(spy):
    proc, reader, lines = spy
    proc.stdin.close()
    try:
        proc.wait(timeout=SPY_START_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        proc.kill()
        fail("lcm-spy did not print its table")
    reader.join()
    text = "".join(lines)
    print(text, end="")
    if proc.returncode != 0:
        fail(f"SpyProbe exited {proc.returncode}")
    return text


def check_spy(text, decoded, types):
    """lcm-spy found every type and decoded, live, every channel the recording holds."""
    found = re.search(r"^Found (\d+) LCM types$", text, re.M)
    if not found or int(found.group(1)) != len(types):
        fail(f"lcm-spy found {found and found.group(1)} LCM types, the project has {len(types)}")
    live = {m[0]: m[1:] for m in re.findall(r"^live (\S+) (\S+) received=(\d+) errors=(\d+) decoded=(\w+)$", text, re.M)}
    for channel, cls in decoded.items():
        if channel not in live:
            fail(f"lcm-spy saw nothing on {channel}")
        live_cls, received, errors, ok = live[channel]
        if live_cls != cls or int(received) == 0 or int(errors) != 0 or ok != "true":
            fail(f"lcm-spy on {channel}: class {live_cls} (log: {cls}), {received} received, {errors} errors, decoded {ok}")
    print(f"OK: lcm-spy decoded {sorted(decoded)} live")


def java_decode(args, log_path, out_dir, recorded):
    samples = os.path.join(out_dir, "java_samples.csv")
    cmd = [args.java, "-cp", args.classpath, "SpyDecode", log_path, samples, args.package] + args.types
    result = run(cmd, capture_output=True, text=True)
    print(result.stdout, end="")
    if result.returncode != 0:
        fail(f"SpyDecode failed ({result.returncode}): {result.stderr}")
    found = re.search(r"^types found (\d+)$", result.stdout, re.M)
    if not found or int(found.group(1)) != len(args.types):
        fail(f"lcm-spy's database found {found and found.group(1)} of the {len(args.types)} types")
    unknown = dict(re.findall(r"^unknown (\S+) (\d+)$", result.stdout, re.M))
    probes = int(unknown.pop(PROBE_CHANNEL, "0"))
    if recorded:
        unknown.pop(LCM_SELF_TEST_CHANNEL, None)
        unknown.pop(END_CHANNEL, None)
    if unknown or (probes == 0) == recorded:
        fail(f"messages no generated class decodes besides the {probes} probes: {unknown}")
    start_line = re.search(r"^start (.*)$", result.stdout, re.M)
    if not start_line:
        fail("no START in the recording")
    start = dict(kv.split("=", 1) for kv in start_line.group(1).split())
    _, rows = read_csv(samples)
    decoded = dict(re.findall(r"^decoded (\S+) (\S+) \d+$", result.stdout, re.M))
    return start, rows, probes, decoded


def target_position(start, t_s):
    """Robot 0's target at t_s from the START's path_t as Java decoded it (path_t.lcm's kinds)."""
    kind = int(start["target.kind"])
    if kind == 0:  # KIND_POLYNOMIAL: sum_j coeff[axis][j] t^j
        return tuple(sum(c * t_s ** j for j, c in enumerate(axis)) for axis in json.loads(start["target.coeff"]))
    if kind not in (1, 2):
        fail(f"the check evaluates on-board paths only, the START has kind {kind}")
    center = json.loads(start["target.center_m"])
    a, b = json.loads(start["target.semi_axis_m"])
    b = a if kind == 1 else b  # KIND_CIRCLE: radius in semi_axis_m[0]
    phi = float(start["target.omega_radps"]) * t_s + float(start["target.phase_rad"])
    rot = float(start["target.rotation_rad"]) if kind == 2 else 0.0
    x, y = a * math.cos(phi), b * math.sin(phi)
    return (center[0] + math.cos(rot) * x - math.sin(rot) * y, center[1] + math.sin(rot) * x + math.cos(rot) * y)


def check_through_java(args, log_path, out, rows, reported, spy_text):
    """The log as lcm-spy decodes it (and, live, lcm-spy's window) against log2csv's CSV."""
    start, java_rows, probes, decoded = java_decode(args, log_path, out, reported is not None)
    if spy_text is not None:
        check_spy(spy_text, decoded, args.types)
    if reported and int(reported.group(1)) != probes:
        fail(f"log2csv reported {reported.group(1)} undecodable probes, Java found {probes}")
    if len(rows) != len(java_rows):
        fail(f"log2csv wrote {len(rows)} rows, the log holds {len(java_rows)} robot samples (Java)")
    period_us, delay_us = int(start["period_us"]), int(start["delay_us"])
    for row, java in zip(rows, java_rows):
        t_s = float(row["t_s"])
        sample_us = round(t_s * 1e6) + delay_us
        if sample_us % period_us != 0 or abs(t_s * 1e6 - round(t_s * 1e6)) > 1e-3:
            fail(f"row at t = {t_s} s is not a sample instant (epoch + (n + 1) h - tau)")
        if not (close(float(row["x_m"]), float(java["x_m"])) and close(float(row["y_m"]), float(java["y_m"]))):
            fail(f"position at t = {t_s}: CSV ({row['x_m']}, {row['y_m']}), Java ({java['x_m']}, {java['y_m']})")
        if row["robot"] == "0":
            tx, ty = target_position(start, t_s)
            if not (close(float(row["target_x_m"]), tx, 1e-8) and close(float(row["target_y_m"]), ty, 1e-8)):
                fail(f"reference at t = {t_s}: CSV ({row['target_x_m']}, {row['target_y_m']}), START ({tx}, {ty})")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--mode", choices=("realtime", "lockstep"), required=True)
    p.add_argument("--sim", required=True)
    p.add_argument("--firmware", required=True)
    p.add_argument("--log2csv", required=True)
    p.add_argument("--plot", required=True)
    p.add_argument("--logger", required=True)
    # Without Java (TVO_LCM_JAVA off) the checks through lcm-spy's decoding are left out.
    p.add_argument("--java", help="java, for the checks through lcm-spy's decoding (SpyDecode, SpyProbe)")
    p.add_argument("--classpath", help="lcm.jar, the types' jar and SpyDecode's classes")
    p.add_argument("--package")
    p.add_argument("--lcm-url", required=True)
    p.add_argument("--out-dir", required=True)
    p.add_argument("--duration-s", default="3")
    p.add_argument("--scenario", default="demo")
    p.add_argument("--xvfb-run", help="also watch the run with lcm-spy's window under this xvfb-run")
    p.add_argument("types", nargs="*")
    args = p.parse_args()
    if args.java and not (args.classpath and args.package and args.types):
        p.error("--java needs --classpath, --package and the types")
    if args.xvfb_run and not args.java:
        p.error("--xvfb-run needs --java")

    out = os.path.abspath(args.out_dir)
    sim_dir, conv_dir = os.path.join(out, "sim"), os.path.join(out, "log2csv")
    os.makedirs(sim_dir, exist_ok=True)
    os.makedirs(conv_dir, exist_ok=True)
    lockstep = args.mode == "lockstep"
    log_path = os.path.join(sim_dir, "run.lcmlog") if lockstep else os.path.join(out, "recorded.lcmlog")
    for stale in (log_path, os.path.join(conv_dir, "run.csv"), os.path.join(conv_dir, "run.png")):
        if os.path.exists(stale):
            os.remove(stale)

    sim_args = [args.sim, "--firmware", args.firmware, "--lcm-url", args.lcm_url, "--out-dir", sim_dir,
                "--duration-s", args.duration_s, "--sigma", "0", "--scenario", args.scenario]
    # Lockstep with tau = 0: the sample of period n is the plant's state at the simulator's row n + 1.
    sim_args += ["--delay-s", "0"] if lockstep else ["--realtime"]
    logger = None if lockstep else start_logger(args.logger, args.lcm_url, log_path)
    spy, spy_text = None, ""
    try:
        spy = start_spy(args) if args.xvfb_run else None  # after the probes: they are not messages
        sim = run(sim_args)
    finally:
        if spy:
            spy_text = stop_spy(spy)
        if logger:
            stop_logger(logger, args.lcm_url, log_path)
    if sim.returncode != 0:
        fail(f"tvo_sim exited {sim.returncode}")
    with open(os.path.join(sim_dir, "summary.json")) as f:
        summary = json.load(f)

    csv_path = os.path.join(conv_dir, "run.csv")
    conv = run([args.log2csv, log_path, "-o", csv_path, "--scenario-json", os.path.join(conv_dir, "scenario.json")],
               capture_output=True, text=True)
    print(conv.stdout, conv.stderr, sep="", end="")
    if conv.returncode != 0:
        fail(f"log2csv exited {conv.returncode}")
    plot = run(["/usr/bin/python3", args.plot, csv_path], capture_output=True, text=True)
    png = os.path.join(conv_dir, "run.png")
    if plot.returncode != 0 or not os.path.exists(png) or os.path.getsize(png) == 0:
        fail(f"plot_run.py failed ({plot.returncode}): {plot.stderr}")

    header, rows = read_csv(csv_path)
    sim_header, sim_rows = read_csv(os.path.join(sim_dir, "run.csv"))
    if header != sim_header:
        fail(f"log2csv's header {header} is not the simulator's {sim_header}")
    for i, row in enumerate(rows):
        if not all(math.isfinite(float(v)) for v in row.values()):
            fail(f"row {i} has a value that is not finite: {row}")

    with open(os.path.join(sim_dir, "scenario.json")) as f:
        robots = int(json.load(f)["robot_count"])
    steps = int(summary["steps"])
    reported = re.search(rf"did not decode \(skipped\): {PROBE_CHANNEL} (\d+)", conv.stdout)
    if not lockstep and (not reported or int(reported.group(1)) == 0):
        fail(f"log2csv did not report the undecodable probes on {PROBE_CHANNEL}")
    previous_t = -math.inf
    for row in rows:
        if float(row["t_s"]) < previous_t:
            fail(f"rows out of time order at t = {row['t_s']}")
        previous_t = float(row["t_s"])
    if args.java:
        check_through_java(args, log_path, out, rows, reported, spy_text if spy else None)
    else:
        print("lcm-spy's decoding not checked: no --java (TVO_LCM_JAVA off)")
    minimum = robots * steps if lockstep else math.ceil(MIN_RECORDED_FRACTION * robots * steps)
    if not minimum <= len(rows) <= robots * steps:
        fail(f"{len(rows)} rows for a run of {steps} steps and {robots} robots (expected {minimum} .. {robots * steps})")

    if lockstep:
        # The simulator's row n + 1 (t = (n + 1) h) is the state our row n sampled, with the same answer.
        by_time = {(r["t_s"], r["robot"]): r for r in sim_rows}
        for row in rows:
            twin = by_time.get((row["t_s"], row["robot"]))
            if twin is None:
                fail(f"no simulator row at t = {row['t_s']}")
            for key in header:
                if key != "heading_rad" and not close(float(row[key]), float(twin[key])):
                    fail(f"t = {row['t_s']}: {key} is {row[key]} from the log, {twin[key]} in the simulator's CSV")
        if args.scenario != "demo" and not any(float(r["barrier_c"]) > 0.0 for r in rows):
            fail("the barrier's c(t) is 0 in every row: the telemetry columns were not filled")
    final = max(float(r["error_m"]) for r in rows if r["t_s"] == rows[-1]["t_s"])
    if abs(final - summary["final_error_m"]) > (1e-9 if lockstep else ERROR_TOLERANCE_M):
        fail(f"final error {final} m from the log, {summary['final_error_m']} m in summary.json")
    print(f"OK: {args.mode}: {len(rows)} rows of {robots * steps}, final error {final:.3g} m "
          f"(summary {summary['final_error_m']:.3g} m), figure {png}")


if __name__ == "__main__":
    main()

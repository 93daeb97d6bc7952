"""How tools/fleet starts a fleet's processes: which node a robot count needs, the network namespaces,
one node per robot, the hub and tvo_sim, and what each leaves behind. The one place that knows
the programs' command lines and the wire between them (host/README.md, "A fleet"); tools/fleet itself
reads only tvo_sim's outputs (run.csv, summary.json, scenario.json) and the hub's --json.
"""
import os
import re
import shutil
import signal
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
SKIP = 77

# The nodes, smallest first: (CMake target, where the build puts it, where its size limits are written).
# A node takes fleets of up to TVO_MAX_OUTPUT_DIM / 2 robots (tvo/config.h: 2 flat outputs per robot).
NODES = (
    ("tvo_firmware_node", "firmware/tvo_firmware_node",
     "firmware/include/tvo/config.h", r"#define TVO_MAX_OUTPUT_DIM (\d+)"),
    ("tvo_firmware_node_fleet", "firmware/tvo_firmware_node_fleet",
     "firmware/cmake/tvo_fleet_limits.cmake", r"TVO_MAX_OUTPUT_DIM=(\d+)"),
    ("tvo_firmware_node_swarm", "firmware/tvo_firmware_node_swarm",
     "firmware/cmake/tvo_swarm_limits.cmake", r"TVO_MAX_OUTPUT_DIM=(\d+)"),
)
SIM = ("tvo_sim", "host/tvo_sim")
HUB = ("tvo_fleet_hub", "host/tvo_fleet_hub")


def node_robot_limit(node):
    """The robots a node's fleet sessions take, read from where its build's limits are written."""
    _, _, source, pattern = node
    match = re.search(pattern, (REPO / source).read_text())
    if match is None:
        raise RuntimeError(f"no TVO_MAX_OUTPUT_DIM in {source}: cannot tell how many robots its node takes")
    return int(match.group(1)) // 2


def node_for(robots):
    """The smallest node whose fleet sessions take this many robots, or None."""
    return next((node for node in NODES if node_robot_limit(node) >= robots), None)


def built_robot_limit(binary):
    """What the built node says it takes (its --help); None if it does not say."""
    text = subprocess.run([str(binary), "--help"], capture_output=True, text=True).stdout
    match = re.search(r"[Ss]essions of\s+up to (\d+) robots", text)
    return int(match.group(1)) if match else None


def dry_run(build, scenario, sim_args, key_args):
    """tvo_sim checks the file and the options as a fleet run would use them, running nothing:
    (exit code, its output, robots). Exit code 2 is a refused file or option (FILE:LINE:COLUMN)."""
    done = subprocess.run([str(build / SIM[1]), "--scenario", str(scenario), "--dry-run",
                           "--lcm-url", "memq://", *key_args, *sim_args], capture_output=True, text=True)
    match = re.search(r"scenario .*?, (\d+) robot\(s\)", done.stdout)
    return done.returncode, done.stdout + done.stderr, int(match.group(1)) if match else None


class Namespaces:
    """The bridge, one namespace per node and one for the plant; removed in close()."""

    def __init__(self, nodes):
        self.tag = f"tvofl{os.getpid()}"
        self.bridge_ns = f"{self.tag}br"
        self.names = [f"{self.tag}n{k}" for k in range(nodes)] + [f"{self.tag}p"]
        self.made = []

    def ip(self, *args):
        subprocess.run(["ip", *args], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)

    @staticmethod
    def remove_stale():
        """Namespaces of earlier runs that were killed (SIGKILL skips any clean-up): their process is gone."""
        listing = subprocess.run(["ip", "netns", "list"], capture_output=True, text=True).stdout
        for line in listing.splitlines():
            m = re.match(r"(tvofl(\d+)(?:br|n\d+|p))\b", line)
            if m and not Path(f"/proc/{m.group(2)}").exists():
                subprocess.run(["ip", "netns", "del", m.group(1)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

    def make(self):
        if shutil.which("ip") is None:
            return "the 'ip' command (Debian package iproute2; tools/setup fleet installs it) is not installed"
        self.remove_stale()
        try:
            self.ip("netns", "add", self.bridge_ns)
        except subprocess.CalledProcessError:
            return "cannot create a network namespace here (needs root or CAP_NET_ADMIN; --local runs on loopback)"
        self.made.append(self.bridge_ns)
        self.ip("-n", self.bridge_ns, "link", "add", "br0", "type", "bridge", "mcast_snooping", "0")
        self.ip("-n", self.bridge_ns, "link", "set", "br0", "up")
        for i, ns in enumerate(self.names):
            self.ip("netns", "add", ns)
            self.made.append(ns)
            self.ip("-n", ns, "link", "add", "eth0", "type", "veth", "peer", "name", f"p{i}", "netns", self.bridge_ns)
            self.ip("-n", self.bridge_ns, "link", "set", f"p{i}", "master", "br0")
            self.ip("-n", self.bridge_ns, "link", "set", f"p{i}", "up")
            self.ip("-n", ns, "addr", "add", f"10.98.0.{i + 1}/24", "dev", "eth0")
            self.ip("-n", ns, "link", "set", "lo", "up")
            self.ip("-n", ns, "link", "set", "eth0", "up")
            self.ip("-n", ns, "route", "add", "224.0.0.0/4", "dev", "eth0")  # multicast leaves through the link
        return None

    def prefix(self, index):
        return ["ip", "netns", "exec", self.names[index]]

    def rx_packets(self, index):
        """Packets the namespace's link has received so far (the traffic did cross the bridge)."""
        text = subprocess.run([*self.prefix(index), "cat", "/sys/class/net/eth0/statistics/rx_packets"],
                              capture_output=True, text=True).stdout.strip()
        return int(text) if text.isdigit() else 0

    def close(self):
        for ns in reversed(self.made):
            subprocess.run(["ip", "netns", "del", ns], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.made = []


@dataclass
class Launch:
    """What a fleet run left: tvo_sim's exit code and outputs (in out), the hub's figures, the logs."""
    skipped: str = None            # why the run could not start (exit code 77), else None
    error: str = None              # why it failed, with the log that says so, else None
    sim_code: int = None           # tvo_sim's exit code (0, or 3: a collision)
    hub_json: Path = None
    extra: dict = field(default_factory=dict)   # figures only the plumbing knows (per node, per link)


def launch(build, node, scenario, robots, out, logs, *, loss, loss_until_s, seed, local, port, key_file, sim_args,
           one_bus=False):
    """Runs one node per robot, the hub (unless one_bus) and tvo_sim; tvo_sim writes run.csv, run.lcmlog,
    scenario.json and sim-summary.json into out, the hub hub.json; each process's log goes to logs."""
    key = ["--key-file", str(Path(key_file).resolve())] if key_file else []
    sim, hub = build / SIM[1], build / HUB[1]
    ttl = 0 if local else 1
    if one_bus:  # every process on the robots' network
        plant_url = f"udpm://239.255.76.69:{port}?ttl={ttl}"
        node_urls = [plant_url] * robots
    else:
        plant_url = f"udpm://239.255.76.70:{port}?ttl=0"  # tvo_sim and the hub: one host, never on the link
        # Each node on its own URL (its link to the hub: the hub decides what each link loses).
        node_urls = [f"udpm://239.255.76.69:{port + 1 + k}?ttl={ttl}" for k in range(robots)]
    nets = None if local else Namespaces(robots)
    procs, files = [], []
    result = Launch(hub_json=None if one_bus else out / "hub.json")

    def stop_all(*_):
        for p in procs:
            if p.poll() is None:
                p.terminate()
        for p in procs:
            try:
                p.wait(timeout=5)
            except subprocess.TimeoutExpired:
                p.kill()
        for f in files:
            f.close()
        if nets is not None:
            nets.close()

    def on_signal(signo, _frame):
        stop_all()
        sys.exit(128 + signo)

    signal.signal(signal.SIGTERM, on_signal)
    signal.signal(signal.SIGINT, on_signal)
    try:
        if nets is not None:
            why = nets.make()
            if why is not None:
                result.skipped = why
                return result
        prefix = (lambda i: []) if nets is None else nets.prefix
        for k in range(robots):
            log = open(logs / f"node{k}.log", "w")
            files.append(log)
            procs.append(subprocess.Popen([*prefix(k), str(build / node[1]), "--own-robot", str(k), "--lcm-url", node_urls[k],
                                           "--boot-file", str(logs / f"node{k}.boot"), "--exit-with-parent", *key], stdout=log, stderr=subprocess.STDOUT))
        hub_proc = None
        if not one_bus:
            hub_log = open(logs / "hub.log", "w")
            files.append(hub_log)
            hub_proc = subprocess.Popen([*prefix(robots), str(hub), "--plant-url", plant_url,
                                         *[a for url in node_urls for a in ("--node-url", url)], "--loss", repr(loss),
                                         "--loss-until-s", repr(loss_until_s), "--seed", str(seed),
                                         "--json", str(result.hub_json), *key],
                                        stdout=hub_log, stderr=subprocess.STDOUT)
            procs.append(hub_proc)
        sim_cmd = [*prefix(robots), str(sim), "--scenario", str(Path(scenario).resolve()), "--lcm-url", plant_url,
                   "--telemetry-every", "1", "--sigma", "0", "--out-dir", str(out), "--summary-json", str(out / "sim-summary.json"),
                   *key, *sim_args]
        with open(logs / "sim.log", "w") as sim_log:
            result.sim_code = subprocess.run(sim_cmd, stdout=sim_log, stderr=subprocess.STDOUT).returncode
        if result.sim_code not in (0, 3):  # 3: completed with a collision (tools/fleet reports it)
            result.error = f"tvo_sim exited with {result.sim_code}:\n{(logs / 'sim.log').read_text()}"
            return result
        if hub_proc is not None:
            try:
                hub_proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                hub_proc.terminate()
                hub_proc.wait(timeout=5)
        for p in procs[:robots]:
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                pass
        for k, p in enumerate(procs[:robots]):
            if p.returncode != 0:  # still running 10 s after STOP (None), or failed
                why = "did not exit after STOP" if p.returncode is None else f"exited with {p.returncode}"
                result.error = f"node {k} {why}:\n{(logs / f'node{k}.log').read_text()}"
                return result
        if hub_proc is not None and not result.hub_json.exists():
            result.error = f"the hub wrote no figures:\n{(logs / 'hub.log').read_text()}"
            return result
        # Each node's exit line counts the frames its keyed link dropped (unauthenticated=N replayed=N).
        counts = [(re.search(r"\bunauthenticated=(\d+)", text), re.search(r"\breplayed=(\d+)", text))
                  for text in ((logs / f"node{k}.log").read_text() for k in range(robots))]
        result.extra["node_unauthenticated"] = [int(u.group(1)) if u else None for u, _ in counts]
        result.extra["node_replayed"] = [int(r.group(1)) if r else None for _, r in counts]
        if all(u is not None and r is not None for u, r in counts):
            result.extra["node_unauthenticated_min"] = min(result.extra["node_unauthenticated"])
            result.extra["node_replayed_min"] = min(result.extra["node_replayed"])
        if nets is not None:
            result.extra["node_link_rx_packets_min"] = min(nets.rx_packets(k) for k in range(robots))
        return result
    finally:
        stop_all()
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        signal.signal(signal.SIGINT, signal.SIG_DFL)

#!/usr/bin/python3
"""A keyed fleet (tools/fleet --key-file) under attack reproduces the unkeyed fleet.

Usage: keyed_fleet.py BUILD_DIR SCENARIO PORT OUT_DIR

Runs the scenario unkeyed, then keyed while an attacker on every node's link (no key) answers every 5th
genuine frame it hears on TVO_SAMPLE (towards the node) and TVO_COMMAND (towards the hub) with (a) the
same frame again (a replay) and (b) a forgery: the message altered (a sample's x moved 1 m, a command's
bytes changed) under a trailer of the same sender with a counter far above its last, tagged with another
key (the next counter would race the sender's own next frame, which makes the forgery a replay).
Passes only if the keyed run's final error and joint-command digest over the run equal the unkeyed
run's, the nodes agree every period, every node dropped forged and replayed samples (its counters
unauthenticated, replayed >= 1 each, from its last announcement) and the hub forged and replayed
commands (hub_unauthenticated, hub_replayed >= 1).
"""
import json
import select
import socket
import struct
import subprocess
import sys
import threading
from pathlib import Path

try:
    from cryptography.hazmat.primitives.ciphers.aead import ChaCha20Poly1305
except ImportError:
    print("SKIPPED: Python's cryptography (Debian python3-cryptography) is not installed")
    sys.exit(77)

REPO = Path(__file__).resolve().parents[2]
GROUP = "239.255.76.69"  # tools/fleet's node links: node k on port PORT + 1 + k
MAGIC = 0x4C433032       # LCM's short-message header
TRAILER = 28             # auth.h: sender id, counter, tag
FORGED_COUNTER_LEAD = 1 << 32  # counters count frames from a boot, or microseconds (the hub): 71 min ahead


def lcm_packet(seq, channel, data):
    return struct.pack(">II", MAGIC, seq) + channel.encode() + b"\0" + data


class Attacker(threading.Thread):
    def __init__(self, ports):
        super().__init__(daemon=True)
        self.key = ChaCha20Poly1305(bytes(range(32)))  # not the fleet's key
        self.rx = {}
        for port in ports:
            rx = socket.socket(socket.AF_INET, socket.SOCK_DGRAM, socket.IPPROTO_UDP)
            rx.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            rx.bind(("", port))
            rx.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, socket.inet_aton(GROUP) + socket.inet_aton("0.0.0.0"))
            rx.setblocking(False)
            self.rx[rx] = port
        self.tx = socket.socket(socket.AF_INET, socket.SOCK_DGRAM, socket.IPPROTO_UDP)
        self.tx.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)
        self.tx.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_LOOP, 1)
        self.stop = threading.Event()
        self.seen = {}
        self.sent = {"sample": 0, "command": 0}
        self.seq = 0x40000000

    def forge(self, channel, frame):
        message, trailer = frame[:-TRAILER], frame[-TRAILER:]
        sender, counter = struct.unpack(">IQ", trailer[:12])
        altered = bytearray(message)
        if "SAMPLE" in channel:  # fingerprint 8, header: utime 8, session 4, sequence 4, robot 1; has 1; then x
            x = struct.unpack(">d", altered[26:34])[0]
            altered[26:34] = struct.pack(">d", x + 1.0)
        else:
            altered[-9] ^= 0x40
        # Far enough ahead that no genuine frame passes it during the run, so only the tag can refuse it.
        nonce = struct.pack(">IQ", sender, counter + FORGED_COUNTER_LEAD)
        tag = self.key.encrypt(nonce, b"", channel.encode() + b"\0" + bytes(altered))
        return bytes(altered) + nonce + tag

    def send(self, port, channel, data):
        self.seq += 1
        self.tx.sendto(lcm_packet(self.seq, channel, data), (GROUP, port))

    def run(self):
        while not self.stop.is_set():
            ready, _, _ = select.select(list(self.rx), [], [], 0.1)
            for rx in ready:
                self.take(self.rx[rx], rx.recv(65536))

    def take(self, port, packet):
        if len(packet) < 8 or struct.unpack(">I", packet[:4])[0] != MAGIC or packet[4] & 0x40:
            return  # not ours, or one of our own packets (seqno 0x40000000 + n)
        end = packet.index(b"\0", 8)
        channel, frame = packet[8:end].decode(), packet[end + 1:]
        kind = {"TVO_SAMPLE": "sample", "TVO_COMMAND": "command"}.get(channel)
        if kind is None or len(frame) <= TRAILER:
            return
        link = (port, channel)
        self.seen[link] = self.seen.get(link, 0) + 1
        if self.seen[link] % 5 == 0:
            self.send(port, channel, frame)                     # the replay
            self.send(port, channel, self.forge(channel, frame))  # the forgery
            self.sent[kind] += 2


def fleet(build, scenario, port, out, *extra):
    json_path = out / "result.json"
    cmd = [sys.executable, str(REPO / "tools/fleet"), scenario, "--local", "--port", str(port), "--build-dir", build,
           "--out-dir", str(out), "--json", str(json_path), *extra]
    done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited with {done.returncode}:\n{done.stdout}")
    return json.loads(json_path.read_text())


def main():
    build, scenario, port, out = sys.argv[1], sys.argv[2], int(sys.argv[3]), Path(sys.argv[4])
    out.mkdir(parents=True, exist_ok=True)
    plain = fleet(build, scenario, port, out / "unkeyed")
    key = out / "fleet.key"
    key.unlink(missing_ok=True)
    subprocess.run([str(REPO / "tools/keygen"), str(key)], check=True, stdout=subprocess.DEVNULL)
    attacker = Attacker([port + 1 + k for k in range(plain["nodes"])])
    attacker.start()
    try:
        keyed = fleet(build, scenario, port, out / "keyed", "--key-file", str(key))
    finally:
        attacker.stop.set()
        attacker.join()
    print(f"attacker: heard {sum(attacker.seen.values())} genuine frames, sent {attacker.sent}")
    failures = []
    for name in ("final_error_m", "command_digest_run", "compared_periods", "collisions"):
        print(f"{name}: unkeyed {plain.get(name)}, keyed {keyed.get(name)}")
        if plain.get(name) != keyed.get(name):
            failures.append(f"{name} differs")
    for name, bound in (("digest_mismatch_periods", 0), ("limit_violations", 0)):
        if keyed.get(name) != bound:
            failures.append(f"{name} = {keyed.get(name)}, expected {bound}")
    if not keyed.get("keyed"):
        failures.append("the hub did not run keyed")
    for name in ("node_unauthenticated", "node_replayed"):  # each node's counters, from its announcements
        print(f"{name}: {keyed.get(name)}")
        if not keyed.get(name) or any(c is None or c < 1 for c in keyed[name]):
            failures.append(f"{name} = {keyed.get(name)}: some node counted nothing")
    for name in ("hub_unauthenticated", "hub_replayed"):
        print(f"{name}: {keyed.get(name)}")
        if not keyed.get(name):
            failures.append(f"{name} = {keyed.get(name)}: the hub counted nothing")
    if attacker.sent["sample"] == 0 or attacker.sent["command"] == 0:
        failures.append(f"the attacker sent {attacker.sent}: it heard no traffic on the nodes' links")
    for f in failures:
        print(f"FAIL: {f}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Runs a processor-in-the-loop closed loop: the firmware's PIL program in QEMU (mps2-an386,
Cortex-M4F), tvo_pil_bridge between its serial port and LCM, and tvo_sim as the plant.

  tools/pil_run.py --elf PIL.elf --bridge tvo_pil_bridge --sim tvo_sim [--corrupt-every N]
                   [--lcm-url URL] -- [tvo_sim options...]

tvo_sim runs without --firmware: the node it talks to is the microcontroller. With --key-file among
tvo_sim's options the target is provisioned with the same key: the key region (board.h's layout, at
the ELF's tvo_board_key_region_start) is written by QEMU's loader at boot, never into the image, with
the counter base taken from this machine's clock (microseconds since the Unix epoch). The exit code is
tvo_sim's (non-zero also when QEMU or the bridge fail). Writes <out-dir>/pil.json with the counts the
target printed on its console at the end (target_<key>: frames, node counters, its clock) and the
bridge's (bridge_<key>), both as key=value lines, and the run's wall time (wall_s).
"""
import argparse
import json
import os
import re
import shutil
import socket
import stat
import struct
import subprocess
import sys
import tempfile
import time

from progress import Progress

END_TIMEOUT_S = 20
# The plant starts once the target's program runs: a START sent before it waits in QEMU's serial
# socket, and in CLOCK_NODE that wait would count as the START's transit (edge_spec.md) for the whole
# session. Booting takes well under a second; the bound only ends a run whose target never came up.
READY_TIMEOUT_S = 60
READY_LINE = "PIL ready"


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def option_value(args, name, default):
    for i, arg in enumerate(args):
        if arg == name and i + 1 < len(args):
            return args[i + 1]
        if arg.startswith(name + "="):
            return arg.split("=", 1)[1]
    return default


def counts_after(prefix, text):
    """The integer key=value pairs on the last line starting with prefix, or {}."""
    lines = [line for line in text.splitlines() if line.startswith(prefix)]
    if not lines:
        return {}
    return {key: int(value) for key, value in re.findall(r"(\w+)=(-?\d+)", lines[-1])}


KEY_MAGIC = b"TVOK"  # board.h: TVO_BOARD_KEY_MAGIC, then the key, then the counter base (uint64 LE)


def key_region_blob(key_file):
    """board.h's key region for the key in key_file (64 hex digits, owner-only), counter base = now."""
    mode = os.stat(key_file).st_mode
    if mode & (stat.S_IRWXG | stat.S_IRWXO):
        sys.exit(f"pil: key file '{key_file}': group or others may access it (chmod 600)")
    text = open(key_file, encoding="ascii").read().removesuffix("\n")
    if not re.fullmatch(r"[0-9a-fA-F]{64}", text):
        sys.exit(f"pil: key file '{key_file}': expected 64 hexadecimal digits")
    return KEY_MAGIC + bytes.fromhex(text) + struct.pack("<Q", time.time_ns() // 1000)


def key_region_address(elf):
    """Where the ELF's linker script put the key region."""
    nm = shutil.which("arm-none-eabi-nm") or sys.exit("pil: arm-none-eabi-nm not found (binutils-arm-none-eabi)")
    out = subprocess.run([nm, elf], capture_output=True, text=True, check=True).stdout
    m = re.search(r"^([0-9a-f]+) \w tvo_board_key_region_start$", out, re.M)
    if not m:
        sys.exit(f"pil: {elf} has no key region (tvo_board_key_region_start): built without Mbed TLS?")
    return int(m.group(1), 16)


def wait_ready(log, processes):
    """True once the target printed READY_LINE; False if a process ended or READY_TIMEOUT_S passed."""
    deadline = time.monotonic() + READY_TIMEOUT_S
    while time.monotonic() < deadline:
        log.seek(0)
        if READY_LINE in log.read():
            return True
        if any(proc.poll() is not None for proc in processes):
            return False
        time.sleep(0.01)
    return False


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--elf", required=True)
    parser.add_argument("--bridge", required=True)
    parser.add_argument("--sim", required=True)
    parser.add_argument("--qemu", default="qemu-system-arm")
    parser.add_argument("--corrupt-every", type=int, default=0)
    parser.add_argument("--lcm-url", default="")
    parser.add_argument("sim_args", nargs="*")
    args = parser.parse_args()

    started = time.monotonic()
    port = free_port()
    out_dir = option_value(args.sim_args, "--out-dir", "runs/demo")
    os.makedirs(out_dir, exist_ok=True)
    # A --lcm-url among the simulator's options (tools/demo --pil passes them all) is the bridge's too.
    lcm_url = args.lcm_url or option_value(args.sim_args, "--lcm-url", "")
    lcm = ["--lcm-url", lcm_url] if lcm_url else []
    qemu_log = tempfile.TemporaryFile(mode="w+")
    bridge_log = tempfile.TemporaryFile(mode="w+")
    key_file = option_value(args.sim_args, "--key-file", "")
    provision = []
    key_dir = tempfile.TemporaryDirectory()  # the key region's bytes, owner-only, gone at exit
    if key_file:
        blob_path = os.path.join(key_dir.name, "key_region.bin")
        fd = os.open(blob_path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        with os.fdopen(fd, "wb") as blob:
            blob.write(key_region_blob(key_file))
        provision = ["-device", f"loader,file={blob_path},addr={key_region_address(args.elf):#x},force-raw=on"]
    qemu = subprocess.Popen(
        [args.qemu, "-M", "mps2-an386", "-cpu", "cortex-m4", "-nographic", "-monitor", "none",
         "-semihosting-config", "enable=on,target=native",
         "-serial", f"tcp:127.0.0.1:{port},server=on,wait=on,nodelay=on", *provision, "-kernel", args.elf],
        stdin=subprocess.DEVNULL, stdout=qemu_log, stderr=subprocess.STDOUT)
    bridge = subprocess.Popen(
        [args.bridge, "--connect", f"127.0.0.1:{port}", "--corrupt-every", str(args.corrupt_every)] + lcm,
        stdin=subprocess.DEVNULL, stdout=bridge_log, stderr=subprocess.STDOUT)
    # Three phases: the target boots, the closed loop runs (tvo_sim), QEMU and the bridge end. No
    # estimate: the loop's length in lockstep depends on how fast QEMU runs here.
    progress = Progress("pil", total=3, estimate=False)
    progress.update(0, "booting the target in QEMU")
    try:
        if wait_ready(qemu_log, (qemu, bridge)):
            progress.update(1, "closed loop (tvo_sim)")
            sim_lcm = [] if option_value(args.sim_args, "--lcm-url", "") else lcm
            sim_rc = progress.call([args.sim] + sim_lcm + args.sim_args)
            progress.update(2, "QEMU and the bridge ending")
        else:
            progress.close()
            print(f"pil: the target did not print '{READY_LINE}' within {READY_TIMEOUT_S} s "
                  "(or QEMU or the bridge ended)", file=sys.stderr)
            sim_rc = 1
            for proc in (qemu, bridge):
                if proc.poll() is None:
                    proc.terminate()
    except KeyboardInterrupt:
        sim_rc = 130
    rc = sim_rc
    for name, proc in (("QEMU", qemu), ("tvo_pil_bridge", bridge)):
        try:
            proc.wait(timeout=END_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            progress.echo(f"pil: {name} did not end after the session; terminating it\n", sys.stderr)
            proc.kill()
            proc.wait()
            rc = rc or 1
        if proc.returncode not in (0, None) and sim_rc == 0:
            rc = 1
            progress.echo(f"pil: {name} failed (exit {proc.returncode})\n", sys.stderr)
    progress.close()
    qemu_log.seek(0)
    bridge_log.seek(0)
    target_text = qemu_log.read()
    bridge_text = bridge_log.read()
    shown = [line for line in target_text.splitlines() if line.strip() and "waiting for connection" not in line]
    sys.stderr.write("".join(f"pil target: {line}\n" for line in shown))
    sys.stderr.write("".join(f"pil bridge: {line}\n" for line in bridge_text.splitlines() if line.strip()))
    target = counts_after("PIL ", target_text)
    if not target and rc == 0:
        print("pil: the target printed no counts (did its program end on STOP?)", file=sys.stderr)
        rc = 1
    counts = {f"target_{key}": value for key, value in target.items()}
    counts.update({f"bridge_{key}": value for key, value in counts_after("tvo_pil_bridge: frames ", bridge_text).items()})
    counts["wall_s"] = round(time.monotonic() - started, 3)
    with open(os.path.join(out_dir, "pil.json"), "w") as f:
        json.dump(counts, f, indent=2)
        f.write("\n")
    return rc


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Runs a processor-in-the-loop closed loop: the firmware's PIL program in QEMU (mps2-an386,
Cortex-M4F), tvo_pil_bridge between its serial port and LCM, and tvo_sim as the plant.

  tools/pil_run.py --elf PIL.elf --bridge tvo_pil_bridge --sim tvo_sim [--corrupt-every N]
                   [--lcm-url URL] [--boot-file PATH] -- [tvo_sim options...]

tvo_sim runs without --firmware: the node it talks to is the microcontroller. The target is
provisioned at every boot (board.h's provisioned region, at the ELF's
tvo_board_provisioned_region_start, written by QEMU's loader, never into the image) with its boot id:
the next number of a counter file kept on this machine, under an exclusive lock, the same file and
format as tvo_firmware_node's (--boot-file; default $XDG_STATE_HOME/tvo-flat/node-boot-id, else
~/.local/state/tvo-flat/node-boot-id), so a boot id never repeats across runs. With --key-file among
tvo_sim's options the same key is provisioned too. The exit code is tvo_sim's (non-zero also when QEMU
or the bridge fail). Writes <out-dir>/pil.json with the counts the target printed on its console at
the end (target_<key>: frames, node counters, its boot id, its clock) and the bridge's (bridge_<key>),
both as key=value lines, and the run's wall time (wall_s).
"""
import argparse
import fcntl
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


# board.h's provisioned region: "TVOB", the boot id (int64 LE), then "TVOK" and the key if keyed.
BOOT_MAGIC = b"TVOB"
KEY_MAGIC = b"TVOK"
MAX_BOOT_ID = 2**23 - 1  # a node signs with boot id << 40 (firmware/edge/auth.h)
BOOT_FILE = "tvo-flat/node-boot-id"  # under the state folder, as firmware/edge/boot_file.h


def default_boot_file():
    state = os.environ.get("XDG_STATE_HOME", "")
    if state.startswith("/"):
        return os.path.join(state, BOOT_FILE)
    home = os.environ.get("HOME", "")
    if not home.startswith("/"):
        sys.exit("pil: neither XDG_STATE_HOME nor HOME is an absolute path: give the boot file (--boot-file PATH)")
    return os.path.join(home, ".local/state", BOOT_FILE)


def next_boot_id(path, option):
    """The counter file's next boot id, written back under an exclusive lock (firmware/edge/boot_file.c's rules)."""
    def fail(what):
        sys.exit(f"pil: boot file '{path}': {what} ({option})")
    folder = os.path.dirname(path)
    try:
        os.makedirs(folder, mode=0o700, exist_ok=True)
        fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o600)
    except OSError as e:
        fail(f"cannot open it for reading and writing: {e.strerror}")
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)  # another node may be taking its number
        text = os.pread(fd, 32, 0).decode("ascii", "replace")
        if len(text) >= 32 or not re.fullmatch(r"\d*\n?", text):
            fail(f"expected the last boot id (a whole number and a newline), found {text[:20]!r}; a node's boot ids "
                 "must never repeat, so fix the file by hand (a number above every id used) rather than removing it")
        last = int(text) if text.strip() else 0
        if last >= MAX_BOOT_ID:
            fail(f"every boot id up to {MAX_BOOT_ID} is used")
        line = f"{last + 1}\n".encode()
        os.pwrite(fd, line, 0)
        os.ftruncate(fd, len(line))
        os.fsync(fd)
        return last + 1
    except OSError as e:
        fail(f"cannot take the next boot id: {e.strerror}")
    finally:
        os.close(fd)


def read_key(key_file):
    """The 32-byte key of key_file (64 hex digits, owner-only), as tvo_firmware_node reads it."""
    mode = os.stat(key_file).st_mode
    if mode & (stat.S_IRWXG | stat.S_IRWXO):
        sys.exit(f"pil: key file '{key_file}': group or others may access it (chmod 600)")
    text = open(key_file, encoding="ascii").read().removesuffix("\n")
    if not re.fullmatch(r"[0-9a-fA-F]{64}", text):
        sys.exit(f"pil: key file '{key_file}': expected 64 hexadecimal digits")
    return bytes.fromhex(text)


def provisioned_region(boot_id, key):
    """board.h's provisioned region for this boot: the boot id, and the key if there is one."""
    return BOOT_MAGIC + struct.pack("<q", boot_id) + (KEY_MAGIC + key if key else b"")


def provisioned_region_address(elf):
    """Where the ELF's linker script put the provisioned region."""
    nm = shutil.which("arm-none-eabi-nm") or sys.exit("pil: arm-none-eabi-nm not found (binutils-arm-none-eabi)")
    out = subprocess.run([nm, elf], capture_output=True, text=True, check=True).stdout
    m = re.search(r"^([0-9a-f]+) \w tvo_board_provisioned_region_start$", out, re.M)
    if not m:
        sys.exit(f"pil: {elf} has no provisioned region (tvo_board_provisioned_region_start): not the PIL program?")
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
    parser.add_argument("--boot-file", default="",
                        help="the boot counter file (default: tvo_firmware_node's, under $XDG_STATE_HOME)")
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
    key = read_key(key_file) if key_file else b""
    boot_id = next_boot_id(args.boot_file or default_boot_file(),
                           "--boot-file" if args.boot_file else "the default boot file; choose another with --boot-file")
    region_dir = tempfile.TemporaryDirectory()  # the region's bytes (the key among them), owner-only, gone at exit
    blob_path = os.path.join(region_dir.name, "provisioned_region.bin")
    fd = os.open(blob_path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    with os.fdopen(fd, "wb") as blob:
        blob.write(provisioned_region(boot_id, key))
    provision = ["-device", f"loader,file={blob_path},addr={provisioned_region_address(args.elf):#x},force-raw=on"]
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

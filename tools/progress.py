#!/usr/bin/python3
"""One progress line for the long runs (bench, study, PIL, soak, fuzz): what is running, n of N,
elapsed time and an estimate of what is left, redrawn in place on stderr.

Shown only on a terminal: nothing when stderr is not a TTY, when the environment variable CI is set
(CI runners), when TERM=dumb, or when TVO_PROGRESS=0. The line is cleared when the run ends, so the
tool's own output (tables, summaries) reads the same with or without it.

From Python:
    from progress import Progress            # tools/ on sys.path (the tools' own folder)
    with Progress("bench", total=12) as progress:
        for i, step in enumerate(steps):
            progress.update(i, step.name)    # i steps done, step.name running
            ...
From bash (a command whose length in seconds is known, e.g. a fuzzer with -max_total_time):
    tools/progress.py run --label fuzz --what frame --seconds 600 [--output LOG] -- CMD ARGS...
    (runs CMD, passes its exit code through; the estimate is the time left of --seconds; on a
    terminal CMD's output goes through pipes, line by line, so it never lands on the progress line)
From bash, a build (tools/build, make's "[ 42%] Building ... x.cpp.o" lines):
    tools/progress.py build --label scenario [--output LOG] -- CMD ARGS...
    (runs CMD, passes its exit code through; the line shows make's last percentage and what it
    builds, or the last other line (setup, configure); its output goes to LOG, or around the line)
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import threading
import time

REDRAW_S = 1.0        # the ticker redraws this often, so elapsed time moves during a long step
MIN_INTERVAL_S = 0.25  # at most four redraws a second, however often update() is called
CLEAR_LINE = "\r\x1b[K"


def wanted(stream):
    """True when progress belongs on stream: an interactive terminal, not CI, not switched off."""
    if os.environ.get("TVO_PROGRESS", "") == "0" or os.environ.get("CI"):
        return False
    if os.environ.get("TERM", "") == "dumb":
        return False
    try:
        return stream.isatty()
    except (AttributeError, ValueError):
        return False


def format_duration(seconds):
    seconds = max(0, int(round(seconds)))
    hours, rest = divmod(seconds, 3600)
    minutes, secs = divmod(rest, 60)
    if hours:
        return f"{hours}h{minutes:02d}m"
    if minutes:
        return f"{minutes}m{secs:02d}s"
    return f"{secs}s"


class Progress:
    """A progress line for `total` steps; update(done, what) says how many are done and what runs.

    The estimate of the time left is linear in the steps done (elapsed / done * left), or, when
    `seconds` is given instead of `total`, the time left of that many seconds; estimate=False for
    steps of very different lengths (phases), where a linear estimate would mislead."""

    def __init__(self, label, total=None, seconds=None, stream=None, estimate=True):
        self.label = label
        self.total = total
        self.estimate = estimate
        self.seconds = seconds
        self.stream = stream if stream is not None else sys.stderr
        self.enabled = wanted(self.stream)
        self.done = 0
        self.what = ""
        self.started = time.monotonic()
        self._last_draw = 0.0
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._ticker = None
        if self.enabled:
            self._ticker = threading.Thread(target=self._tick, daemon=True)
            self._ticker.start()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def update(self, done, what=None):
        """done steps are finished; what (if given) is the step running now."""
        self.done = done
        if what is not None:
            self.what = what
        self._draw(force=False)

    def text(self, now=None):
        """The progress line without terminal codes (also what the tests read)."""
        elapsed = (now if now is not None else time.monotonic()) - self.started
        line = f"{self.label}: {self.what}" if self.what else f"{self.label}:"
        if self.seconds:
            line += f" {format_duration(min(elapsed, self.seconds))} of {format_duration(self.seconds)}"
            left = self.seconds - elapsed
        else:
            if self.total:
                line += f" [{min(self.done + 1, self.total)}/{self.total}]"
            line += f", {format_duration(elapsed)} elapsed"
            left = None
            if self.estimate and self.total and self.done > 0:
                left = elapsed / self.done * (self.total - self.done)
        if left is not None:
            line += f", ~{format_duration(left)} left" if left >= 0.5 else ", finishing"
        return line

    def echo(self, text, stream):
        """Writes text (a command's output) to stream without mixing it into the progress line."""
        with self._lock:
            if self.enabled:
                self.stream.write(CLEAR_LINE)
                self.stream.flush()
            stream.write(text)
            stream.flush()
            self._last_draw = 0.0
        self._draw(force=False)

    def call(self, command):
        """subprocess.call(command); on a terminal its output goes through echo(), line by line."""
        if not self.enabled:
            return subprocess.call(command)
        with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                              errors="replace") as proc:
            pumps = [threading.Thread(target=self._pump, args=(pipe, out), daemon=True)
                     for pipe, out in ((proc.stdout, sys.stdout), (proc.stderr, sys.stderr))]
            for pump in pumps:
                pump.start()
            rc = proc.wait()
            for pump in pumps:
                pump.join()
        return rc

    def _pump(self, pipe, out):
        for line in pipe:
            self.echo(line, out)

    def close(self):
        """Stops the ticker and clears the line."""
        self._stop.set()
        if self._ticker is not None:
            self._ticker.join()
            self._ticker = None
        if self.enabled:
            with self._lock:
                self.stream.write(CLEAR_LINE)
                self.stream.flush()
            self.enabled = False

    def _tick(self):
        while not self._stop.wait(REDRAW_S):
            self._draw(force=True)

    def _draw(self, force):
        if not self.enabled:
            return
        with self._lock:
            now = time.monotonic()
            if not force and now - self._last_draw < MIN_INTERVAL_S:
                return
            self._last_draw = now
            width = shutil.get_terminal_size((80, 24)).columns
            self.stream.write(CLEAR_LINE + self.text(now)[: max(width - 1, 10)])
            self.stream.flush()


def run_command(label, what, seconds, command, output=None):
    """Runs command with a time-based progress line (its output kept apart, or all of it into the
    file output); returns its exit code."""
    with Progress(label, seconds=seconds) as progress:
        progress.update(0, what)
        try:
            if output is not None:
                with open(output, "w") as out:
                    return subprocess.call(command, stdout=out, stderr=subprocess.STDOUT)
            return progress.call(command)
        except KeyboardInterrupt:
            return 130
        except OSError as err:
            progress.close()
            print(f"{label}: ERROR: cannot run {command[0]}: {err}", file=sys.stderr)
            return 127


MAKE_LINE = re.compile(r"^\[\s*(\d+)%\]\s*(.*)$")


def build_step(line):
    """What a build's output line says it does, for the progress line: make's "[ 42%] Building CXX
    object host/x.dir/src/sim.cpp.o" -> "[ 42%] sim.cpp", "Linking ... tvo_sim" -> "[ 99%] linking
    tvo_sim"; another non-empty line as it is; None for an empty one."""
    line = line.strip()
    match = MAKE_LINE.match(line)
    if not match:
        return line or None
    percent, rest = match.groups()
    words = rest.split()
    if words and words[0] in ("Building", "Linking") and len(words) > 1:
        name = os.path.basename(words[-1])
        name = name[:-2] if name.endswith(".o") else name
        rest = name if words[0] == "Building" else f"linking {name}"
    return f"[{int(percent):3d}%] {rest}"


def run_build(label, command, output=None):
    """Runs a build with a progress line of its steps (its output into the file output, or around
    the line); returns its exit code."""
    with Progress(label, estimate=False) as progress:
        progress.update(0, "starting")
        try:
            out = open(output, "w") if output is not None else None
            try:
                with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                      errors="replace") as proc:
                    for line in proc.stdout:
                        step = build_step(line)
                        if step is not None:
                            progress.update(0, step)
                        if out is not None:
                            out.write(line)
                            out.flush()
                        else:
                            progress.echo(line, sys.stdout)
                    return proc.wait()
            finally:
                if out is not None:
                    out.close()
        except KeyboardInterrupt:
            return 130
        except OSError as err:
            progress.close()
            print(f"{label}: ERROR: cannot run {command[0]}: {err}", file=sys.stderr)
            return 127


def main():
    parser = argparse.ArgumentParser(description="Runs a command with a progress line (on a terminal only).")
    sub = parser.add_subparsers(dest="action", required=True)
    run = sub.add_parser("run", help="run a command of known length, showing elapsed and time left")
    run.add_argument("--label", required=True, help="the tool's name, e.g. fuzz")
    run.add_argument("--what", default="", help="what runs, e.g. the harness")
    run.add_argument("--seconds", type=float, required=True, help="how long the command is expected to run")
    run.add_argument("--output", help="write the command's stdout and stderr to this file")
    run.add_argument("command", nargs=argparse.REMAINDER, help="-- CMD ARGS...")
    build = sub.add_parser("build", help="run a build, showing make's percentage and what it builds")
    build.add_argument("--label", required=True, help="the tool's name, e.g. scenario")
    build.add_argument("--output", help="write the build's stdout and stderr to this file")
    build.add_argument("command", nargs=argparse.REMAINDER, help="-- CMD ARGS...")
    args = parser.parse_args()
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    if not command:
        parser.error(f"{args.action} needs a command after --")
    if args.action == "build":
        return run_build(args.label, command, args.output)
    if args.seconds <= 0:
        parser.error("--seconds must be positive")
    return run_command(args.label, args.what, args.seconds, command, args.output)


if __name__ == "__main__":
    sys.exit(main())

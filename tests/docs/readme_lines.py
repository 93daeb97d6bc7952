#!/usr/bin/python3
"""Every command line of the READMEs, run as written in a fresh clone (CTest readme_lines).

The lines are read from the READMEs each time (never copied here): every ```sh block of every tracked
README.md, continuation lines joined, comment-only lines left out. A fresh clone of the repository
(HEAD, plus the working tree's uncommitted changes to tracked files) is made once and shared:
  1. the lines a README marks as needing nothing run first, in the bare clone, and must leave no
     build/ behind;
  2. tools/demo, as a new user's first command (it installs what is missing and builds the demo);
  3. every other line, README.md's first, then the other READMEs in path order, each block from the
     clone's root in one shell (a `cd` holds to the block's end), each line's exit code checked.
A line passes with exit code 0; 77 is the project's "skipped, with its reason" (tools/fleet without
root for network namespaces) and is reported as such. Two checks hold for every line after the demo:
it leaves build/ configured without the tests (only tools/test turns them on), and it does not
overwrite a run folder (runs/*/summary.json) that a different line wrote.

A README steers this with HTML comments (invisible when rendered) right above a ```sh block:
  <!-- readme-lines: skip: REASON -->             the block is not run (the reason is printed)
  <!-- readme-lines: skip "PREFIX": REASON -->    nor are its lines that start with PREFIX
  <!-- readme-lines: bare "PREFIX" -->            lines starting with PREFIX also run in the bare clone
  <!-- readme-lines: file NAME from snippet:S --> writes the code between <!-- snippet:S begin/end -->
                                                  of that README to NAME in the clone first (as a user
                                                  saves the snippet the text names)
Nothing may be skipped without a reason; a skip says what runs the same lines instead.

Usage: readme_lines.py REPO WORK_DIR [--lcm-port P] [--list]
  --list        print the lines and what would happen to each; run nothing
  --lcm-port P  LCM_DEFAULT_URL for the lines: udpm://239.255.76.67:P?ttl=0 (this test's own port)
Environment of the lines: HOME is WORK_DIR/home ($HOME/opt/tvo lands there); the TVO_* variables of
the caller are dropped, as on a new user's machine.
"""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

SKIPPED = 77
DIRECTIVE = re.compile(r"<!--\s*readme-lines:\s*(.*?)\s*-->")
BLOCK_TIMEOUT_S = 1800


@dataclass
class Line:
    readme: str
    number: int          # the line's number in its README (the first, for a continued line)
    text: str            # as written (run so: bash reads its comment as one)
    skip: str = None     # the reason, when not run
    bare: bool = False

    @property
    def command(self):
        """The line without its comment: from a # after a blank, outside quotes, as bash reads it."""
        quote = None
        for i, c in enumerate(self.text):
            if quote:
                quote = None if c == quote else quote
            elif c in "'\"":
                quote = c
            elif c == "#" and i > 0 and self.text[i - 1].isspace():
                return self.text[:i].rstrip()
        return self.text


@dataclass
class Block:
    readme: str
    number: int
    lines: list
    files: list = field(default_factory=list)   # (NAME, snippet text)


def snippet(text, name, readme):
    m = re.search(rf"<!-- snippet:{re.escape(name)} begin -->\n```\w*\n(.*?)```\n<!-- snippet:{re.escape(name)} end -->",
                  text, re.S)
    if not m:
        raise SystemExit(f"readme_lines: {readme}: no snippet:{name} for a 'file ... from snippet:{name}' directive")
    return m.group(1)


def parse_directives(comments, readme, text):
    """The block's skip reason, per-prefix skips, bare prefixes and files, from its HTML comments."""
    block_skip, prefix_skips, bare, files = None, [], [], []
    for body in comments:
        if m := re.fullmatch(r'skip:\s*(.+)', body, re.S):
            block_skip = m.group(1)
        elif m := re.fullmatch(r'skip\s+"([^"]+)":\s*(.+)', body, re.S):
            prefix_skips.append((m.group(1), m.group(2)))
        elif m := re.fullmatch(r'bare\s+"([^"]+)"', body):
            bare.append(m.group(1))
        elif m := re.fullmatch(r'file\s+(\S+)\s+from\s+snippet:(\S+)', body):
            files.append((m.group(1), snippet(text, m.group(2), readme)))
        else:
            raise SystemExit(f"readme_lines: {readme}: a readme-lines comment it does not read: '{body}'")
    return block_skip, prefix_skips, bare, files


def extract(repo, readme):
    """The ```sh blocks of one README, with their directives applied."""
    text = (repo / readme).read_text()
    rows = text.splitlines()
    blocks, i = [], 0
    while i < len(rows):
        if rows[i].strip() != "```sh":
            i += 1
            continue
        comments, j = [], i - 1
        while j >= 0 and DIRECTIVE.fullmatch(rows[j].strip()):
            comments.insert(0, DIRECTIVE.fullmatch(rows[j].strip()).group(1))
            j -= 1
        block_skip, prefix_skips, bare, files = parse_directives(comments, readme, text)
        block = Block(readme, i + 1, [], files)
        i += 1
        pending, start = "", None
        while i < len(rows) and rows[i].strip() != "```":
            row = rows[i]
            i += 1
            if not pending and (not row.strip() or row.lstrip().startswith("#")):
                continue  # a comment of its own, or the continuation of the line above's comment
            start = start if pending else i
            if row.rstrip().endswith("\\"):
                pending += row.rstrip()[:-1] + " "
                continue
            command = (pending + row).strip()
            pending = ""
            line = Line(readme, start, command)
            line.skip = block_skip or next((why for prefix, why in prefix_skips if line.command.startswith(prefix)), None)
            line.bare = any(line.command.startswith(prefix) for prefix in bare)
            block.lines.append(line)
        i += 1
        blocks.append(block)
    return blocks


def readmes(repo):
    listed = subprocess.run(["git", "-C", str(repo), "ls-files", "README.md", "*/README.md"],
                            capture_output=True, text=True, check=True).stdout.split()
    return sorted(listed, key=lambda r: (r != "README.md", r))


def fresh_clone(repo, clone):
    shutil.rmtree(clone, ignore_errors=True)
    subprocess.run(["git", "clone", "--quiet", "--no-hardlinks", str(repo), str(clone)], check=True)
    head = subprocess.run(["git", "-C", str(repo), "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
    subprocess.run(["git", "-C", str(clone), "checkout", "--quiet", "--detach", head], check=True)
    diff = subprocess.run(["git", "-C", str(repo), "diff", "HEAD", "--binary"], capture_output=True, check=True).stdout
    if diff:
        subprocess.run(["git", "-C", str(clone), "apply", "--whitespace=nowarn"], input=diff, check=True)
    return head[:12] + (" with the working tree's uncommitted changes" if diff else "")


def environment(work, lcm_port):
    env = {k: v for k, v in os.environ.items() if not k.startswith("TVO_")}
    env["HOME"] = str(work / "home")
    # A Debian user's shell: Debian's python3 first on PATH (here it may be behind pyenv's shims), as the
    # READMEs' Python lines assume and host/python's readme_install test does.
    env["PATH"] = "/usr/bin" + os.pathsep + env.get("PATH", "")
    (work / "home").mkdir(parents=True, exist_ok=True)
    if lcm_port:
        env["LCM_DEFAULT_URL"] = f"udpm://239.255.76.67:{lcm_port}?ttl=0"
    env["TVO_PROGRESS"] = "0"   # no progress lines in the logs
    return env


def tests_configured(clone):
    cache = clone / "build/CMakeCache.txt"
    if not cache.exists():
        return None
    m = re.search(r"^TVO_TESTS:\w+=(\w+)$", cache.read_text(), re.M)
    return m.group(1) if m else None


def run_block(lines, clone, env, log):
    """Runs the lines in one bash from the clone's root: {index: (exit code, seconds, the run folders
    whose summary.json the line wrote)}."""
    marks = log.with_suffix(".rc")
    stamp = log.with_suffix(".stamp")
    script = [f"cd {sh_quote(str(clone))}", "exec 3>" + sh_quote(str(marks))]
    for k, line in enumerate(lines):
        script += [f"__t=$SECONDS; touch {sh_quote(str(stamp))}; echo {sh_quote('$ ' + line.text)}",
                   line.text,
                   f"__rc=$?; __w=$(find {sh_quote(str(clone / 'runs'))} -mindepth 2 -maxdepth 2 -name summary.json "
                   f"-newer {sh_quote(str(stamp))} -printf '%h ' 2>/dev/null)",
                   f"echo \"{k} $__rc $((SECONDS - __t)) $__w\" >&3"]
    with open(log, "w") as out:
        # Its own process group: what a line started in the background (a node with '&') ends with the block.
        shell = subprocess.Popen(["bash", "-c", "\n".join(script)], stdout=out, stderr=subprocess.STDOUT, env=env,
                                 stdin=subprocess.DEVNULL, start_new_session=True)
        try:
            shell.wait(timeout=BLOCK_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            out.write(f"\nreadme_lines: the block ran past {BLOCK_TIMEOUT_S} s and was stopped\n")
        finally:
            try:
                os.killpg(shell.pid, signal.SIGTERM)
            except ProcessLookupError:
                pass
            shell.wait()
    results = {}
    if marks.exists():
        for row in marks.read_text().split("\n"):
            if row:
                k, rc, seconds, *written = row.split()
                results[int(k)] = (int(rc), int(seconds), [Path(w).name for w in written])
    return results


def sh_quote(text):
    return "'" + text.replace("'", "'\\''") + "'"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("repo")
    parser.add_argument("work")
    parser.add_argument("--lcm-port", type=int)
    parser.add_argument("--list", action="store_true")
    args = parser.parse_args()
    repo, work = Path(args.repo).resolve(), Path(args.work).resolve()
    if subprocess.run(["git", "-C", str(repo), "rev-parse", "--is-inside-work-tree"], capture_output=True).returncode:
        print(f"readme_lines: SKIPPED: {repo} is not a git work tree, so there is no fresh clone to make")
        return SKIPPED
    blocks = [b for readme in readmes(repo) for b in extract(repo, readme)]
    lines = [line for b in blocks for line in b.lines]
    if not any(line.command == "tools/demo" for line in lines):
        print("readme_lines: FAIL: no README line is plain tools/demo, the first command this test runs")
        return 1
    if args.list:
        for b in blocks:
            for line in b.lines:
                what = f"skip: {line.skip}" if line.skip else ("bare, then after the demo" if line.bare else "after the demo")
                print(f"{line.readme}:{line.number}: {line.command}\n    {what}")
        return 0

    work.mkdir(parents=True, exist_ok=True)
    clone = work / "clone"
    what = fresh_clone(repo, clone)
    env = environment(work, args.lcm_port)
    print(f"readme_lines: a fresh clone of {what} in {clone}; {len(lines)} lines in {len(blocks)} blocks")
    failures, skipped, ran, started = [], [], [], time.monotonic()

    def report(line, rc, seconds, phase, log):
        where = f"{line.readme}:{line.number}"
        if rc == 0:
            ran.append(line)
            print(f"ok      {seconds:4d} s  {phase}  {where}: {line.command}")
        elif rc == SKIPPED:
            skipped.append((line, "exit 77: " + last_words(log, "SKIPPED")))
            print(f"skipped {seconds:4d} s  {phase}  {where}: {line.command}  ({last_words(log, 'SKIPPED')})")
        else:
            failures.append(f"{where}: exit {rc}: {line.command} (log: {log})")
            print(f"FAIL    {seconds:4d} s  {phase}  {where}: exit {rc}: {line.command}\n{tail(log)}")

    # 1. After nothing: the lines marked bare, in the bare clone.
    bare = [line for line in lines if line.bare and not line.skip]
    if bare:
        log = work / "bare.log"
        results = run_block(bare, clone, env, log)
        for k, line in enumerate(bare):
            rc, seconds, _ = results.get(k, (None, 0, []))
            report(line, rc, seconds, "bare ", log)
        if (clone / "build").exists():
            failures.append(f"a line meant to need nothing built something: {clone / 'build'} exists after "
                            + "; ".join(line.command for line in bare))

    # 2. The new user's first command.
    log = work / "demo.log"
    demo = Line("(setup)", 0, "tools/demo")
    results = run_block([demo], clone, env, log)
    rc, seconds, written = results.get(0, (None, 0, []))
    report(demo, rc, seconds, "first", log)
    if rc != 0:
        print("readme_lines: FAIL: tools/demo failed in the fresh clone; no other line can run as written")
        return 1

    # 3. Every line after the demo, block by block.
    writer = {name: demo.command for name in written}   # run folder: the line that wrote it
    for n, block in enumerate(blocks):
        for line in block.lines:
            if line.skip:
                skipped.append((line, line.skip))
                print(f"skipped          {line.readme}:{line.number}: {line.command}  ({line.skip})")
        todo = [line for line in block.lines if not line.skip]
        if not todo:
            continue
        for name, code in block.files:
            (clone / name).write_text(code)
        log = work / f"block{n:02d}.log"
        results = run_block(todo, clone, env, log)
        for k, line in enumerate(todo):
            rc, seconds, written = results.get(k, (None, 0, []))
            report(line, rc, seconds, "after", log)
            for name in written:  # a variant of a run must not overwrite another's folder
                if writer.get(name, line.command) != line.command:
                    failures.append(f"{line.readme}:{line.number}: '{line.command}' overwrote runs/{name}, written "
                                    f"by '{writer[name]}': each variant needs its own folder")
                writer[name] = line.command
        # No line after the demo turns the tests on in build/ (a reconfigure and the test set's packages).
        if tests_configured(clone) not in (None, "OFF"):
            failures.append(f"{block.readme}:{block.number}: the block left build/ configured with the tests "
                            f"(TVO_TESTS={tests_configured(clone)}): only tools/test turns them on")

    print(f"readme_lines: {len(ran)} lines ran, {len(skipped)} skipped, {len(failures)} failed, "
          f"{time.monotonic() - started:.0f} s")
    for line, why in skipped:
        print(f"  skipped {line.readme}:{line.number}: {line.command}: {why}")
    for f in failures:
        print(f"FAIL: {f}")
    return 1 if failures else 0


def tail(log, n=30):
    rows = Path(log).read_text(errors="replace").splitlines()[-n:]
    return "\n".join("    | " + r for r in rows)


def last_words(log, marker):
    rows = [r for r in Path(log).read_text(errors="replace").splitlines() if marker in r]
    return rows[-1].strip() if rows else "no reason printed"


if __name__ == "__main__":
    sys.exit(main())

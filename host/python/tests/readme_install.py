#!/usr/bin/python3
"""host/python/README.md's "Install" block, run as written, then the module's tests on what it installed.

In WORK_DIR/tree, a copy of the repository's files as a fresh clone has them (git ls-files: tracked and
untracked-not-ignored; no build trees, no .deps), kept between runs with unchanged files untouched so
that pip's CMake build in tree/host/python/build/ rebuilds only what changed; a new .venv every run.
The block runs with `sh -e` from the tree's root, PYTHONPATH unset (the CTest's points at the build
tree), TMPDIR in WORK_DIR, and TVO_LCM_SOURCE_DIR set to the LCM source the repository's tools/setup
recorded, so the copy's `tools/setup python` does not download it again. Then, in the same shell, this
test's own checks: `tvo` and `lcm` come from the venv, obstacles.h was written, and test_module.py
and test_lcm.py pass under the venv's interpreter.

Usage: readme_install.py REPO WORK_DIR UDPM_URL
"""
import os
import re
import shutil
import subprocess
import sys

SKIP_DIRS = {".git", "build", ".deps", "runs", ".venv", "__pycache__"}


def repository_files(repo):
    """The files a fresh clone of repo's working tree has (relative paths)."""
    try:
        out = subprocess.run(["git", "-C", repo, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                             capture_output=True, check=True).stdout
        names = [n for n in out.decode().split("\0") if n]
    except (OSError, subprocess.CalledProcessError):   # not a git work tree: every file but build outputs
        names = []
        for folder, dirs, files in os.walk(repo):
            dirs[:] = [d for d in dirs if d not in SKIP_DIRS and not d.startswith("build-")]
            names += [os.path.relpath(os.path.join(folder, f), repo) for f in files]
    return sorted(n for n in names if os.path.isfile(os.path.join(repo, n)) and not os.path.islink(os.path.join(repo, n)))


def sync(repo, tree, names):
    """tree holds exactly names (plus what builds write into ignored folders), unchanged files untouched."""
    wanted = set(names)
    for name in names:
        src, dst = os.path.join(repo, name), os.path.join(tree, name)
        s = os.stat(src)
        try:
            d = os.stat(dst)
            if d.st_size == s.st_size and int(d.st_mtime) == int(s.st_mtime):
                continue
        except FileNotFoundError:
            os.makedirs(os.path.dirname(dst), exist_ok=True)
        shutil.copy2(src, dst)
    for folder, dirs, files in os.walk(tree):
        dirs[:] = [d for d in dirs if d not in SKIP_DIRS and not d.endswith(".egg-info")]
        for f in files:
            rel = os.path.relpath(os.path.join(folder, f), tree)
            if rel not in wanted:
                os.remove(os.path.join(tree, rel))


def block(readme, name):
    with open(readme, encoding="utf-8") as f:
        m = re.search(rf"<!-- snippet:{name} begin -->\n```\w+\n(.*?)```\n<!-- snippet:{name} end -->", f.read(), re.S)
    if not m:
        sys.exit(f"readme_install.py: {readme} has no block <!-- snippet:{name} begin --> .. end")
    return m.group(1)


def main(argv):
    if len(argv) != 4:
        sys.exit(__doc__)
    repo, work, url = os.path.abspath(argv[1]), os.path.abspath(argv[2]), argv[3]
    tree = os.path.join(work, "tree")
    os.makedirs(tree, exist_ok=True)
    sync(repo, tree, repository_files(repo))
    shutil.rmtree(os.path.join(tree, ".venv"), ignore_errors=True)
    tmp = os.path.join(work, "tmp")
    shutil.rmtree(tmp, ignore_errors=True)
    os.makedirs(tmp)

    env = {k: v for k, v in os.environ.items() if not k.startswith("PYTHON")}
    env["TMPDIR"] = tmp
    record = os.path.join(repo, ".deps", "lcm-python-dir")
    if "TVO_LCM_SOURCE_DIR" not in env and os.path.isfile(record):
        with open(record, encoding="utf-8") as f:
            env["TVO_LCM_SOURCE_DIR"] = f.read().strip()
    env.setdefault("CMAKE_BUILD_PARALLEL_LEVEL", "2")

    tests = os.path.join(repo, "host", "python", "tests")
    checks = f'''
# --- readme_install.py's own checks, in the README's shell (its venv active, its folder) ---
python -c "import sys, tvo, lcm, tvo_lcm
for m in (tvo, lcm, tvo_lcm):
    assert m.__file__.startswith(sys.prefix), (m.__name__, m.__file__, sys.prefix)
print('readme_install: tvo, lcm and tvo_lcm from', sys.prefix)"
test -s obstacles.h
grep -q "obstacles_problem_desc" obstacles.h
python "{tests}/test_module.py"
python "{tests}/test_lcm.py" "{url}"
'''
    install = block(os.path.join(tree, "host", "python", "README.md"), "python-install")
    print(f"readme_install: in {tree}, host/python/README.md's Install block:\n{install}", flush=True)
    script = install + checks
    run = subprocess.run(["sh", "-e", "-c", script], cwd=tree, env=env, check=False)
    print(f"readme_install: exit code {run.returncode}")
    return 0 if run.returncode == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))

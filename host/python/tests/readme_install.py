#!/usr/bin/python3
"""host/python/README.md's "Install" block, run as written, then what it promises, checked.

In WORK_DIR/tree, a copy of the repository's files as a fresh clone has them (git ls-files: tracked and
untracked-not-ignored; no build trees, no .deps), kept between runs with unchanged files untouched; new
venvs every run. The block runs with `sh -e` from the tree's root as a Debian user has it: PATH starting
with the folder of Debian's python3 (this test's interpreter), PYTHONPATH unset (the CTest's points at
the build tree), TMPDIR in WORK_DIR, TVO_LCM_SOURCE_DIR set to the LCM source the repository's
tools/setup recorded (the copy's `tools/setup python` does not download it again), and, with BUILD_DIR,
TVO_PYTHON_BUILD_DIR=BUILD_DIR: pip's build reuses that configured build tree (the CTest's, already
built) instead of configuring and compiling the copy from scratch (minutes on two loaded cores).
Then, in the README's shell: tvo, lcm and tvo_lcm come from the venv, numpy from Debian's folder,
cffi (a Debian package tvo does not load) stays invisible, obstacles.h was written, test_module.py
and test_lcm.py pass under the venv's interpreter. Then apart: the wheel was Debian's setuptools' and
wheel's (bdist_wheel) and the backend without them names tools/setup python; a missing Debian
package's message, the refusal of a non-Debian interpreter (and, when the original PATH has another python3, pip's build
refusing its venv), a --system-site-packages venv, and `pip uninstall tvo` removing every file the
package installed.

Usage: readme_install.py REPO WORK_DIR UDPM_URL [BUILD_DIR]
"""
import glob
import importlib.util
import os
import re
import shutil
import subprocess
import sys
import time

VENVS = ("v", "venv-system", "venv-other")   # the README's and this test's, new every run
SKIP_DIRS = {".git", "build", ".deps", "runs", ".venv", "__pycache__", *VENVS}


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


def say(ok, what):
    print(f"readme_install: {'ok' if ok else 'FAILED'}: {what}", flush=True)
    return ok


def run(command, **kwargs):
    """command's exit code and its output (stdout and stderr together), echoed."""
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, check=False, **kwargs)
    print(done.stdout, end="", flush=True)
    return done.returncode, done.stdout


def site_packages(venv):
    out = subprocess.run([os.path.join(venv, "bin", "python"), "-c", "import sysconfig; print(sysconfig.get_path('platlib'))"],
                         capture_output=True, text=True, check=True).stdout
    return out.strip()


def check_missing_package(venv, empty):
    """The finder's message when Debian's python3-numpy is missing (pointed at an empty folder)."""
    code = f"""
import sys, _tvo_debian_packages as d
sys.meta_path = [f for f in sys.meta_path if not isinstance(f, d.DebianPackages)] + [d.DebianPackages(folder={empty!r})]
try:
    import numpy
except ModuleNotFoundError as e:
    print(e)
"""
    rc, out = run([os.path.join(venv, "bin", "python"), "-c", code])
    return say(rc == 0 and "python3-numpy" in out and "tools/setup python" in out,
               "without Debian's python3-numpy, `import numpy` says which package and tools/setup python")


def check_backend(tree, venv, empty):
    """The wheel pip installed is bdist_wheel's (Debian's setuptools and wheel ran setup.py), and the
    backend, without Debian's setuptools (the finder pointed at an empty folder), names tools/setup python."""
    wheel = glob.glob(os.path.join(site_packages(venv), "tvo-*.dist-info", "WHEEL"))
    generator = ""
    if len(wheel) == 1:
        with open(wheel[0], encoding="utf-8") as f:
            generator = " ".join(line.strip() for line in f if line.startswith("Generator:"))
    ok = say(generator.startswith("Generator: bdist_wheel"), f"the wheel was built by Debian's setuptools ({generator or wheel})")
    # -S: no site-packages, as in pip's isolated build (the venv's own setuptools would answer first)
    code = f"""
import sys; sys.path.insert(0, '.')
import _tvo_debian_packages as debian
debian.DEBIAN_DIR = {empty!r}
import debian_setuptools
"""
    rc, out = run([sys.executable, "-S", "-c", code], cwd=os.path.join(tree, "host", "python"))
    return say(rc != 0 and "python3-setuptools" in out and "tools/setup python" in out,
               "without Debian's python3-setuptools, the build backend says which package and tools/setup python") and ok


def check_other_interpreter(tree, env, original_path):
    """A venv of another interpreter is refused by pip's build, naming /usr/bin/python3."""
    sys.path.insert(0, os.path.join(tree, "host", "python"))   # the copy's setup.py and its finder module
    spec = importlib.util.spec_from_file_location("tvo_setup", os.path.join(tree, "host", "python", "setup.py"))
    setup_py = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(setup_py)   # not __main__: defines, builds nothing
    problem = setup_py.interpreter_problem("/opt/python-3.11", "cpython", "/usr/lib/python3/dist-packages") or ""
    ok = say("/usr/bin/python3 -m venv v" in problem and "/opt/python-3.11" in problem,
             "setup.py's interpreter_problem names a non-Debian base and the venv line to use")
    other = shutil.which("python3", path=original_path)
    base = subprocess.run([other, "-c", "import sys; print(sys.base_prefix)"], capture_output=True, text=True,
                          check=False).stdout.strip() if other else "/usr"
    if base == "/usr":
        print("readme_install: the original PATH's python3 is Debian's: no other interpreter's venv to refuse")
        return ok
    venv = os.path.join(tree, "venv-other")
    if subprocess.run([other, "-m", "venv", venv], check=False).returncode != 0:
        print(f"readme_install: {other} ({base}) makes no venv: its refusal is not exercised")
        return ok
    rc, out = run([os.path.join(venv, "bin", "pip"), "install", "./host/python"], cwd=tree, env=env)
    return say(rc != 0 and "/usr/bin/python3 -m venv v" in out and base in out,
               f"pip install ./host/python in a venv of {other} ({base}) stops, naming /usr/bin/python3") and ok


def check_system_site_packages(tree, env, python):
    venv = os.path.join(tree, "venv-system")
    rc, _ = run(["sh", "-e", "-c", f"{python} -m venv --system-site-packages {venv}\n"
                 f"{venv}/bin/pip install ./host/python\n"
                 f"{venv}/bin/python -c 'import sys, tvo, cffi, numpy; assert tvo.__file__.startswith(sys.prefix); "
                 "print(tvo.Reason.STALE)'"], cwd=tree, env=env)
    return say(rc == 0, "a venv with --system-site-packages installs and imports tvo (and sees every Debian package)")


def check_uninstall(venv):
    """`pip uninstall tvo` removes every file the wheel's RECORD lists, the finder's .pth with them."""
    site = site_packages(venv)
    records = glob.glob(os.path.join(site, "tvo-*.dist-info", "RECORD"))
    if len(records) != 1:
        return say(False, f"one tvo-*.dist-info/RECORD in {site} (found {records})")
    with open(records[0], encoding="utf-8") as f:
        files = [line.split(",")[0] for line in f if line.strip()]
    listed = all(name in files for name in ("tvo_debian_packages.pth", "_tvo_debian_packages.py"))
    rc, _ = run([os.path.join(venv, "bin", "pip"), "uninstall", "-y", "tvo"])
    left = [f for f in files if os.path.lexists(os.path.join(site, f))]
    rc_numpy, out = run([os.path.join(venv, "bin", "python"), "-c", "import numpy"])
    return say(rc == 0 and listed and not left and rc_numpy != 0 and "python3-numpy" not in out,
               f"pip uninstall tvo removed its {len(files)} files (the .pth and the finder listed: {listed}; "
               f"left: {left[:5]}), and the venv no longer imports Debian's numpy")


def main(argv):
    if len(argv) not in (4, 5):
        sys.exit(__doc__)
    repo, work, url = os.path.abspath(argv[1]), os.path.abspath(argv[2]), argv[3]
    build_dir = os.path.abspath(argv[4]) if len(argv) == 5 else None
    if sys.base_prefix != "/usr":
        sys.exit(f"readme_install.py: run it with Debian's /usr/bin/python3 (this is {sys.executable}, base {sys.base_prefix})")
    tree = os.path.join(work, "tree")
    os.makedirs(tree, exist_ok=True)
    sync(repo, tree, repository_files(repo))
    for venv in VENVS:
        shutil.rmtree(os.path.join(tree, venv), ignore_errors=True)
    tmp = os.path.join(work, "tmp")
    shutil.rmtree(tmp, ignore_errors=True)
    os.makedirs(os.path.join(tmp, "empty"))

    # A Debian user's shell: Debian's python3 first on PATH (here it may be behind pyenv's shims).
    original_path = os.environ.get("PATH", "")
    env = {k: v for k, v in os.environ.items() if not k.startswith("PYTHON")}
    env["PATH"] = os.path.dirname(sys.executable) + os.pathsep + original_path
    env["TMPDIR"] = tmp
    record = os.path.join(repo, ".deps", "lcm-python-dir")
    if "TVO_LCM_SOURCE_DIR" not in env and os.path.isfile(record):
        with open(record, encoding="utf-8") as f:
            env["TVO_LCM_SOURCE_DIR"] = f.read().strip()
    if build_dir:
        env["TVO_PYTHON_BUILD_DIR"] = build_dir
    env.setdefault("CMAKE_BUILD_PARALLEL_LEVEL", "2")

    tests = os.path.join(repo, "host", "python", "tests")
    checks = f'''
# --- readme_install.py's own checks, in the README's shell (its venv active, its folder) ---
python -c "import sys, tvo, lcm, tvo_lcm, numpy, _tvo_debian_packages as debian
for m in (tvo, lcm, tvo_lcm):
    assert m.__file__.startswith(sys.prefix), (m.__name__, m.__file__, sys.prefix)
assert numpy.__file__.startswith(debian.DEBIAN_DIR + '/'), numpy.__file__
print('readme_install: tvo, lcm and tvo_lcm from', sys.prefix, '; numpy from', numpy.__file__)"
if python -c "import cffi" 2>/dev/null; then
  echo "readme_install: the venv imports Debian's cffi: it should see only numpy, _cffi_backend and cryptography"; exit 1
fi
test -s obstacles.h
grep -q "obstacles_problem_desc" obstacles.h
python "{tests}/test_module.py"
python "{tests}/test_lcm.py" "{url}"
'''
    install = block(os.path.join(tree, "host", "python", "README.md"), "python-install")
    print(f"readme_install: in {tree}, host/python/README.md's Install block"
          f"{' (pip builds in ' + build_dir + ')' if build_dir else ''}:\n{install}", flush=True)
    started = time.monotonic()
    readme = subprocess.run(["sh", "-e", "-c", install + checks], cwd=tree, env=env, check=False)
    ok = say(readme.returncode == 0, f"the Install block and its checks (exit code {readme.returncode}, "
                                     f"{time.monotonic() - started:.0f} s)")
    venv = os.path.join(tree, "v")
    if ok:
        ok = check_backend(tree, venv, os.path.join(tmp, "empty")) and ok
        ok = check_missing_package(venv, os.path.join(tmp, "empty")) and ok
        ok = check_uninstall(venv) and ok
    ok = check_other_interpreter(tree, env, original_path) and ok
    ok = check_system_site_packages(tree, env, sys.executable) and ok
    print(f"readme_install: {'passed' if ok else 'FAILED'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))

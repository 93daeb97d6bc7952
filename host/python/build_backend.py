"""`pip install ./host/python`'s build backend (PEP 517, kept in this folder: pyproject.toml's
backend-path). It needs nothing from a package index (requires = [], no setuptools, no wheel), so
`python3 -m venv v && v/bin/pip install ./host/python` works offline with Debian's python3, with or
without --system-site-packages. It builds the `tvo` package with the repository's own CMake (target
tvo_python_package), installs component tvo_python into a staging folder and zips that as a wheel.

The venv must be one of Debian's interpreter (its base /usr): the package loads Debian's numpy, cffi
runtime and cryptography (_tvo_debian_packages.py), built for that interpreter only. CMake runs the
build's Python steps (cffi's C, LCM's patch) with that base interpreter, which sees Debian's packages.

Environment: TVO_PYTHON_BUILD_DIR, a CMake build folder of this repository to build in (e.g. build/ of
tools/build: reused as configured, configured here if new; default host/python/build/<SOABI>/);
CMAKE_BUILD_PARALLEL_LEVEL, the build's jobs (default: every core).
"""
import base64
import hashlib
import os
import re
import shutil
import subprocess
import sys
import sysconfig
import tempfile
import zipfile

import _tvo_debian_packages

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
NAME = "tvo"
SUMMARY = "The tvo-flat firmware's motion-control core (time-varying optimization) from Python"


def fail(message):
    sys.exit(f"tvo build_backend.py: {message}")


def version():
    """The project's version, written once in firmware/cmake/tvo_version.cmake."""
    path = os.path.join(REPO, "firmware", "cmake", "tvo_version.cmake")
    try:
        with open(path, encoding="utf-8") as f:
            return re.search(r"set\(tvo_version ([0-9.]+)\)", f.read()).group(1)
    except (OSError, AttributeError):
        fail(f"no version in {path}: build from host/python inside the tvo-flat repository (pip older "
             "than 21.3 copies the folder away from the C core: use Debian's pip)")


def interpreter_problem(base_prefix, implementation, debian_dir):
    """Why an interpreter whose base is base_prefix cannot take the package, or None if it can."""
    if implementation == "cpython" and base_prefix == "/usr" and os.path.isdir(debian_dir):
        return None
    packages = ", ".join(_tvo_debian_packages.MODULES.values())
    return (f"this venv's interpreter comes from {base_prefix} ({implementation}), not from Debian "
            f"(/usr/bin/python3). tvo uses Debian's {packages} (tools/setup python), built for Debian's "
            "interpreter only. Make the venv with Debian's:\n"
            "    /usr/bin/python3 -m venv v && v/bin/pip install ./host/python")


def check_interpreter():
    problem = interpreter_problem(sys.base_prefix, sys.implementation.name, _tvo_debian_packages.DEBIAN_DIR)
    if problem:
        fail(problem)


def wheel_tag():
    """cpXY-cpXY-platform: the extensions are this interpreter's (CPython, its version and platform)."""
    python = "cp%d%d" % sys.version_info[:2]
    abi = python + ("d" if sysconfig.get_config_var("Py_DEBUG") else "")
    return f"{python}-{abi}-{sysconfig.get_platform().replace('-', '_').replace('.', '_')}"


def dist_info_files():
    """The .dist-info's METADATA and WHEEL. Debian's packages are Requires-External, not
    Requires-Dist: pip would look for those on an index; the installed finder loads Debian's."""
    metadata = [
        "Metadata-Version: 2.1", f"Name: {NAME}", f"Version: {version()}", f"Summary: {SUMMARY}",
        "License: Apache-2.0", "Requires-Python: >=3.9",
    ] + [f"Requires-External: {package}" for package in _tvo_debian_packages.MODULES.values()]
    wheel = ["Wheel-Version: 1.0", "Generator: tvo build_backend.py", "Root-Is-Purelib: false", f"Tag: {wheel_tag()}"]
    return {"METADATA": "\n".join(metadata) + "\n", "WHEEL": "\n".join(wheel) + "\n"}


def dist_info_name():
    return f"{NAME}-{version()}.dist-info"


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    check_interpreter()
    folder = os.path.join(metadata_directory, dist_info_name())
    os.makedirs(folder, exist_ok=True)
    for name, text in dist_info_files().items():
        with open(os.path.join(folder, name), "w", encoding="utf-8") as f:
            f.write(text)
    return dist_info_name()


def run(command, env):
    print("tvo build_backend.py:", " ".join(command), flush=True)
    try:
        subprocess.run(command, check=True, env=env)
    except FileNotFoundError:
        fail("cmake not found (Debian package cmake; tools/setup python installs it)")
    except subprocess.CalledProcessError as e:
        fail(f"'{' '.join(command[:2])}' failed with exit code {e.returncode} (the messages above say why; "
             "tools/setup python installs what the build needs)")


def cmake_build(staging):
    """The package's files, as CMake installs component tvo_python, into staging."""
    base_python = os.path.join(sys.base_prefix, "bin", "python%d.%d" % sys.version_info[:2])
    given = os.environ.get("TVO_PYTHON_BUILD_DIR")
    build_dir = os.path.abspath(given or os.path.join(HERE, "build", sysconfig.get_config_var("SOABI")))
    # pip's build isolation puts a sitecustomize that hides site-packages on PYTHONPATH: CMake's
    # Python steps need Debian's packages, so they run without it.
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    configured = os.path.isfile(os.path.join(build_dir, "CMakeCache.txt")) and (
        os.path.isfile(os.path.join(build_dir, "Makefile")) or os.path.isfile(os.path.join(build_dir, "build.ninja")))
    if not given or not configured:   # a build folder of the user's is reused as configured
        run(["cmake", "-S", REPO, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release", "-DTVO_TESTS=OFF",
             f"-DPython3_EXECUTABLE={base_python}"], env)
    jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
    run(["cmake", "--build", build_dir, "--target", "tvo_python_package", "--parallel", jobs], env)
    run(["cmake", "--install", build_dir, "--component", "tvo_python", "--prefix", staging, "--strip"], env)
    suffix = sysconfig.get_config_var("EXT_SUFFIX")
    for precision in ("f32", "f64"):
        if not os.path.isfile(os.path.join(staging, "tvo", f"_core_{precision}{suffix}")):
            found = sorted(f for f in os.listdir(os.path.join(staging, "tvo")) if f.startswith("_core_"))
            fail(f"{build_dir} built no tvo/_core_{precision}{suffix} for this interpreter ({sys.version.split()[0]}; "
                 f"it holds {found or 'none'}): configure it with -DPython3_EXECUTABLE={base_python}")


def record_line(path, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{path},sha256={digest},{len(data)}"


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    check_interpreter()
    name = f"{NAME}-{version()}-{wheel_tag()}.whl"
    staging = tempfile.mkdtemp(prefix="tvo-wheel-")
    try:
        cmake_build(staging)
        dist_info = dist_info_name()
        records = []
        with zipfile.ZipFile(os.path.join(wheel_directory, name), "w", zipfile.ZIP_DEFLATED) as wheel:
            for folder, dirs, files in os.walk(staging):
                dirs.sort()
                for f in sorted(files):
                    path = os.path.join(folder, f)
                    arcname = os.path.relpath(path, staging).replace(os.sep, "/")
                    wheel.write(path, arcname)   # keeps the mode: tvo/bin/tvo_scenario_export stays executable
                    with open(path, "rb") as data:
                        records.append(record_line(arcname, data.read()))
            extra = dist_info_files()
            with open(os.path.join(REPO, "LICENSE"), encoding="utf-8") as f:
                extra["LICENSE"] = f.read()
            for file_name, text in extra.items():
                arcname = f"{dist_info}/{file_name}"
                wheel.writestr(arcname, text)
                records.append(record_line(arcname, text.encode()))
            records.append(f"{dist_info}/RECORD,,")
            wheel.writestr(f"{dist_info}/RECORD", "\n".join(records) + "\n")
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return name

"""`pip install ./host/python`, run by Debian's setuptools (pyproject.toml, debian_setuptools.py): the
`tvo` package built by the repository's own CMake (target tvo_python_package: the same sources, flags
and cffi extensions as `tools/build`), with `tvo_lcm` (the message types) and LCM's own `lcm` module.

build_ext configures the project (Release, no tests) in host/python/build/<SOABI>/, runs the build's
Python steps (cffi's C, LCM's patch) under the venv's base interpreter, Debian's, which sees Debian's
cffi, builds the target and installs its component tvo_python into setuptools' build_lib, which
bdist_wheel then packs. The component includes tvo_debian_packages.pth and its finder, which give a
venv Debian's numpy, cffi runtime and cryptography at run time. A venv of any other interpreter is
refused before anything is built: Debian's packages are built for Debian's interpreter only.

Environment: TVO_PYTHON_BUILD_DIR, a CMake build folder of this repository to build in (e.g. build/ of
tools/build: reused as configured, configured here if new); CMAKE_BUILD_PARALLEL_LEVEL, the build's
jobs (default: every core).
"""
import os
import re
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Distribution, setup
from setuptools.command.build_ext import build_ext

import _tvo_debian_packages  # this folder's (pyproject.toml's backend-path)

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


def fail(message):
    sys.exit(f"tvo setup.py: {message}")


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


def run(command, env):
    print("tvo setup.py:", " ".join(command), flush=True)
    try:
        subprocess.run(command, check=True, env=env)
    except FileNotFoundError:
        fail("cmake not found (Debian package cmake; tools/setup python installs it)")
    except subprocess.CalledProcessError as e:
        fail(f"'{' '.join(command[:2])}' failed with exit code {e.returncode} (the messages above say why; "
             "tools/setup python installs what the build needs)")


class BinaryDistribution(Distribution):
    """Compiled code, one interpreter and platform: a cpXY platform wheel, not a pure-Python one."""

    def has_ext_modules(self):
        return True


class CMakeBuild(build_ext):
    """The package's files, as the project's CMake installs component tvo_python, into build_lib."""

    def run(self):
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
        # build_lib holds only what this installs (no packages of setuptools' own): emptied first, so
        # a file the package no longer has is not packed from an earlier build.
        staging = os.path.abspath(self.build_lib)
        shutil.rmtree(staging, ignore_errors=True)
        run(["cmake", "--install", build_dir, "--component", "tvo_python", "--prefix", staging, "--strip"], env)
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        for precision in ("f32", "f64"):
            if not os.path.isfile(os.path.join(staging, "tvo", f"_core_{precision}{suffix}")):
                found = sorted(f for f in os.listdir(os.path.join(staging, "tvo")) if f.startswith("_core_"))
                fail(f"{build_dir} built no tvo/_core_{precision}{suffix} for this interpreter ({sys.version.split()[0]}; "
                     f"it holds {found or 'none'}): configure it with -DPython3_EXECUTABLE={base_python}")


def main():
    problem = interpreter_problem(sys.base_prefix, sys.implementation.name, _tvo_debian_packages.DEBIAN_DIR)
    if problem:   # before anything is built: pip's first call (get_requires_for_build_wheel) stops here
        fail(problem)
    setup(
        name="tvo",
        version=version(),
        description="The tvo-flat firmware's motion-control core (time-varying optimization) from Python",
        license="Apache-2.0",
        license_files=["../../LICENSE"],   # the repository's, into the wheel's .dist-info
        python_requires=">=3.9",
        # no install_requires: numpy, cffi's runtime and cryptography are Debian's (the finder), never
        # fetched by pip
        packages=[],      # no discovery (src/ is C): the CMake install puts tvo, tvo_lcm and lcm in build_lib
        py_modules=[],
        distclass=BinaryDistribution,
        cmdclass={"build_ext": CMakeBuild},
        zip_safe=False,
    )


if __name__ == "__main__":   # setuptools runs it so; readme_install.py imports interpreter_problem
    main()

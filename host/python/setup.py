"""`pip install ./host/python`: the `tvo` module built against the firmware's C core by the project's
own CMake (the same sources, flags and cffi extensions as `tools/build`), with the message types for
Python (`tvo_lcm`, generated from lcm_types/*.lcm) and, when `tools/setup python` fetched its source,
LCM's own Python module (`lcm`).

Offline, with Debian's packages only (host/python/README.md):
    /usr/bin/python3 -m venv --system-site-packages .venv   # the venv sees python3-cffi, -numpy, -wheel
    .venv/bin/pip install ./host/python
pip builds with the venv's setuptools when `wheel` is importable (python3-wheel); it must build in this
folder of the repository (pip does, since 21.3), which holds the C core it compiles.
CMAKE_BUILD_PARALLEL_LEVEL sets the build's jobs (default: every core).
"""
import os
import re
import subprocess
import sys

from setuptools import Distribution, setup
from setuptools.command.build_ext import build_ext

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


def version():
    """The project's version, written once in firmware/cmake/tvo_version.cmake."""
    path = os.path.join(REPO, "firmware", "cmake", "tvo_version.cmake")
    try:
        with open(path, encoding="utf-8") as f:
            return re.search(r"set\(tvo_version ([0-9.]+)\)", f.read()).group(1)
    except (OSError, AttributeError):
        sys.exit(f"tvo setup.py: no version in {path}: build from host/python inside the tvo-flat repository "
                 "(pip older than 21.3 copies the folder away from the C core: upgrade pip or use Debian's)")


class BinaryDistribution(Distribution):
    """Compiled code, one interpreter and platform: a platform wheel, not a pure-Python one."""

    def has_ext_modules(self):
        return True


class CMakeBuild(build_ext):
    """Configures the repository's CMake project (no tests), builds target tvo_python_package and
    installs its component tvo_python (host/python/CMakeLists.txt says what it holds) into build_lib."""

    def run(self):
        build_dir = os.path.join(os.path.abspath(self.build_temp), "cmake")
        configure = ["cmake", "-S", REPO, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release", "-DTVO_TESTS=OFF",
                     f"-DPython3_EXECUTABLE={sys.executable}"]
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        steps = [configure,
                 ["cmake", "--build", build_dir, "--target", "tvo_python_package", "--parallel", jobs],
                 ["cmake", "--install", build_dir, "--component", "tvo_python",
                  "--prefix", os.path.abspath(self.build_lib)]]
        for command in steps:
            print("tvo setup.py:", " ".join(command), flush=True)
            try:
                subprocess.run(command, check=True)
            except FileNotFoundError:
                sys.exit("tvo setup.py: cmake not found (Debian package cmake; tools/setup python installs it)")
            except subprocess.CalledProcessError as e:
                sys.exit(f"tvo setup.py: '{' '.join(command[:2])}' failed with exit code {e.returncode} "
                         "(the messages above say why; tools/setup python installs what the build needs)")


setup(
    name="tvo",
    version=version(),
    description="The tvo-flat firmware's motion-control core (time-varying optimization) from Python",
    license="Apache-2.0",
    python_requires=">=3.9",
    install_requires=["numpy", "cffi"],   # Debian's python3-numpy and python3-cffi, seen by the venv
    packages=[],      # no discovery (src/ is C): the CMake install puts tvo, tvo_lcm and lcm in build_lib
    py_modules=[],
    distclass=BinaryDistribution,
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)

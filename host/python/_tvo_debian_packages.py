"""Debian's numpy, cffi's runtime and cryptography for a venv of Debian's python3 made without
--system-site-packages. `pip install ./host/python` installs this module and tvo_debian_packages.pth,
whose `import` line runs it when the interpreter starts: it appends one finder to sys.meta_path that
answers only for the top-level modules of MODULES, only from Debian's dist-packages, and only when no
other finder found them (a copy installed in the venv wins). The rest of the system's packages stay
out of the venv. These are Debian's builds for Debian's interpreter, the venv's base, which is the only
one build_backend.py accepts. `pip uninstall tvo` removes both files.
"""
import importlib.machinery
import os
import sys

# What tvo imports from Debian (top-level module: Debian package): numpy; the runtime of its cffi
# extensions; tvo.auth's ChaCha20-Poly1305. build_backend.py writes them as Requires-External.
MODULES = {
    "numpy": "python3-numpy",
    "_cffi_backend": "python3-cffi-backend",
    "cryptography": "python3-cryptography",
}
# Where Debian installs its python3-* packages for its /usr/bin/python3.
DEBIAN_DIR = os.path.join(sys.base_prefix, "lib", "python3", "dist-packages")


class DebianPackages:
    """A meta path finder for MODULES in folder (a package's submodules then follow its __path__)."""

    def __init__(self, folder=DEBIAN_DIR):
        self.folder = folder

    def find_spec(self, name, path=None, target=None):
        if name not in MODULES:
            return None
        spec = importlib.machinery.PathFinder.find_spec(name, [self.folder])
        if spec is None:
            raise ModuleNotFoundError(
                f"No module named {name!r}: this venv ({sys.prefix}) takes it from Debian's {MODULES[name]}, "
                f"which is not in {self.folder}: tools/setup python installs it "
                f"(or: apt-get install {MODULES[name]})", name=name)
        return spec


if not any(isinstance(finder, DebianPackages) for finder in sys.meta_path):
    sys.meta_path.append(DebianPackages())

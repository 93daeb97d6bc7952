"""Named modules from Debian's python3-* packages, and no other, for a venv of Debian's python3.

Run time: `pip install ./host/python` installs this module and tvo_debian_packages.pth, whose line
calls install() when the interpreter starts: one finder appended to sys.meta_path that answers only
for the top-level modules of MODULES (numpy, cffi's runtime, cryptography), only from Debian's
folder, and only when no other finder found them (a copy installed in the venv wins). The rest of the
system's packages stay out of a venv made without --system-site-packages. These are Debian's builds
for Debian's interpreter, the only one setup.py accepts. `pip uninstall tvo` removes both files.
Build time: debian_setuptools.py (pyproject.toml's backend) installs one for Debian's setuptools.
"""
import importlib.machinery
import importlib.metadata
import sys

# What tvo imports from Debian at run time (top-level module: Debian package): numpy; the runtime of
# its cffi extensions; tvo.auth's ChaCha20-Poly1305.
MODULES = {
    "numpy": "python3-numpy",
    "_cffi_backend": "python3-cffi-backend",
    "cryptography": "python3-cryptography",
}
# Where Debian installs its python3-* packages for its /usr/bin/python3.
DEBIAN_DIR = "/usr/lib/python3/dist-packages"


class DebianPackages:
    """A meta path finder for modules (top-level name: Debian package) in folder (a package's
    submodules then follow its __path__), and for the metadata of the distributions named (their
    entry points: setuptools' commands and wheel's bdist_wheel are found that way)."""

    def __init__(self, modules=MODULES, folder=None, distributions=()):
        self.modules = dict(modules)
        self.folder = folder or DEBIAN_DIR
        self.distributions = frozenset(distributions)

    def find_spec(self, name, path=None, target=None):
        if name not in self.modules:
            return None
        spec = importlib.machinery.PathFinder.find_spec(name, [self.folder])
        if spec is None:
            package = self.modules[name]
            raise ModuleNotFoundError(
                f"No module named {name!r}: tvo takes it from Debian's {package}, which is not in "
                f"{self.folder}: tools/setup python installs it (or: apt-get install {package})", name=name)
        return spec

    def find_distributions(self, context=importlib.metadata.DistributionFinder.Context()):
        if not self.distributions or (context.name is not None and context.name.lower() not in self.distributions):
            return iter(())   # the run time's finder names none: Debian's folder is not scanned
        found = importlib.metadata.MetadataPathFinder.find_distributions(
            importlib.metadata.DistributionFinder.Context(name=context.name, path=[self.folder]))
        return (d for d in found if d.metadata["Name"].lower() in self.distributions)


def install(modules=MODULES, distributions=()):
    """Appends the finder for modules (once: a second call with the same modules does nothing)."""
    if not any(isinstance(f, DebianPackages) and f.modules == modules for f in sys.meta_path):
        sys.meta_path.append(DebianPackages(modules, distributions=distributions))

"""pip's build backend for ./host/python (pyproject.toml): Debian's setuptools (python3-setuptools,
with python3-wheel's bdist_wheel), imported from Debian's folder and nothing else of it, so that pip's
isolated build needs no index (requires = []). setup.py says what the build does."""
import sys

import _tvo_debian_packages as debian

DISTRIBUTIONS = ("setuptools", "wheel")
debian.install({"setuptools": "python3-setuptools", "pkg_resources": "python3-setuptools",
                "_distutils_hack": "python3-setuptools", "wheel": "python3-wheel"}, DISTRIBUTIONS)
try:
    from setuptools import build_meta
    from setuptools.build_meta import *  # noqa: F401,F403 (PEP 517's hooks)
    import pkg_resources
except ModuleNotFoundError as e:
    sys.exit(f"tvo's build needs Debian's setuptools: {e}")
# wheel's bdist_wheel asks pkg_resources for setuptools' version: Debian's dists are made known to it
# (not added: that would put all of Debian's folder on sys.path); a venv's own copy wins.
for dist in pkg_resources.find_distributions(debian.DEBIAN_DIR):
    if dist.key in DISTRIBUTIONS:
        pkg_resources.working_set.by_key.setdefault(dist.key, dist)


def get_requires_for_build_wheel(config_settings=None):
    """setuptools' list but `wheel`, which is Debian's python3-wheel here: pip fetches nothing."""
    return [r for r in build_meta.get_requires_for_build_wheel(config_settings) if r != "wheel"]

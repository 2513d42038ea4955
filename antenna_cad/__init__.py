"""antenna_cad: physics spec of a microwave antenna -> solids, cutting templates and a cut list.

Distributed as ``make-lens``; the version is the installed distribution's (pyproject.toml).
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("make-lens")
except PackageNotFoundError:        # a source tree used without installing it
    __version__ = "0+source"

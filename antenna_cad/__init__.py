"""antenna_cad: physics spec of a microwave antenna -> solids, cutting templates and a cut list."""

__version__ = "0.1.0"

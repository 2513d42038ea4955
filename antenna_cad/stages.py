"""Whether the plan being made goes on to the CAD stage: the CAD-free ``validate --fast`` plans
without it, so a fabrication plan that is itself a mesh (a printed lattice) stays analytic there —
its limits and fill checks made, its meshing and the checks on the mesh left to a build or a full
validate. Set by :func:`antenna_cad.pipeline.prepare`; read by the kind adapters."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar

_WITH_CAD: ContextVar[bool] = ContextVar("antenna_cad_plan_with_cad", default=True)


def with_cad() -> bool:
    """Whether the plan being made goes on to the CAD stage (default: yes)."""
    return _WITH_CAD.get()


@contextmanager
def planning(cad: bool) -> Iterator[None]:
    """Plans made inside go on to the CAD stage when ``cad``."""
    token = _WITH_CAD.set(cad)
    try:
        yield
    finally:
        _WITH_CAD.reset(token)

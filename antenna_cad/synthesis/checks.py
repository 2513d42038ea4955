"""Physics check records shared by every synthesis module.

A design is a value plus a list of :class:`Check`: each names a rule, the measured figure, the
limit and a status. Impossible physics raises :class:`DesignError` naming the number that broke.
"""

from __future__ import annotations

import traceback
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Literal

import numpy as np

Status = Literal["pass", "warn", "fail", "skip"]   # skip: a stage that did not run (never a pass)


class DesignError(ValueError):
    """A physically impossible design. ``field`` is the spec path the user should change."""

    def __init__(self, field: str, message: str):
        super().__init__(f"{field}: {message}")
        self.field = field
        self.message = message


@contextmanager
def solving(field: str, stage: str) -> Iterator[None]:
    """Run a numerical stage quietly: numpy/scipy warnings are not printed, and a numerical failure
    (division by zero, singular matrix, math domain, spline or geometry error) becomes a
    DesignError naming ``field``, the spec block whose numbers the stage could not solve."""
    with np.errstate(all="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            yield
        except (DesignError, OSError):     # I/O errors are the caller's to report
            raise
        except Exception as exc:    # noqa: BLE001 — any failure of the numerics is reported, never a traceback
            where = traceback.extract_tb(exc.__traceback__)[-1].name
            detail = " ".join(str(exc).split())[:80] or "no detail"
            raise DesignError(field, f"the {stage} cannot be solved for these values "
                                     f"({type(exc).__name__} in {where}: {detail}); change {field}") from None


@dataclass(frozen=True)
class Check:
    name: str          # short id, e.g. "rim_incidence_vs_tir"
    status: Status
    value: float       # the measured figure, in ``unit``
    limit: float       # the threshold it is compared with
    unit: str          # "deg", "mm", "dB", "" ...
    message: str       # one line a user can act on

    @staticmethod
    def upper(name: str, value: float, limit: float, unit: str, what: str,
              warn_margin: float = 0.0) -> "Check":
        """Pass when ``value <= limit - warn_margin``, warn inside the margin, fail above ``limit``."""
        if value > limit:
            status: Status = "fail"
        elif value > limit - warn_margin:
            status = "warn"
        else:
            status = "pass"
        u = f" {unit}" if unit else ""
        return Check(name, status, float(value), float(limit), unit,
                     f"{what}: {value:.4g}{u} (limit {limit:.4g}{u})")

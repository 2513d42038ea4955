"""Physics check records shared by every synthesis module.

A design is a value plus a list of :class:`Check`: each names a rule, the measured figure, the
limit and a status. Impossible physics raises :class:`DesignError` naming the number that broke.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

Status = Literal["pass", "warn", "fail"]


class DesignError(ValueError):
    """A physically impossible design. ``field`` is the spec path the user should change."""

    def __init__(self, field: str, message: str):
        super().__init__(f"{field}: {message}")
        self.field = field
        self.message = message


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

"""Mission parameters: the knobs of the paper's Eq. 16 / Eq. 22 and of the pre-optimisation.

A frozen dataclass, validated on construction, in the units people use (days, km,
m/s).  Defaults are the paper's application case (Part V).
"""

from __future__ import annotations

import dataclasses
import numbers
from dataclasses import dataclass

from .orbits import J2

DRIFT_INCLINATION_RULES = ("table3", "free")


class MissionError(ValueError):
    """A mission parameter is out of range or inconsistent with the others."""


@dataclass(frozen=True)
class Mission:
    """Parameters of a debris collecting mission (paper Part II-B, III-I, IV-B, V).

    Parameters
    ----------
    n : int
        Number of debris to remove (paper: 5).
    tmax_days : float
        Maximum mission duration T_max [days] (paper: 1 year).
    deorbit_days : float
        Duration T_deorb of the operations at each debris [days] (paper: 0).
    operations_dv_mps : float
        Cost C_k of the operations at each debris [m/s] (paper: 0, deorbit-kit scenario).
    min_transfer_days : float
        Minimum transfer duration T_min [days] (paper: 0 in Eq. 16).
    drift_altitude_km : tuple of float
        Lower and upper altitude bounds of the drift orbits above R_T [km] (paper: 400-1200).
    preopt_days : float
        Transfer duration bound T0 of the pre-optimisation [days] (paper: 2 months).
    dv_max_mps : float
        Edges whose pre-optimised cost exceeds this are dropped [m/s] (paper's ΔVmax).
    drift_inclination : {"table3", "free"}
        Drift inclination rule: the paper's Table 3 (fastest RAAN correction), or
        ``"free"``: whichever of the two debris inclinations is cheaper.
    j2 : float
        Zonal coefficient used by all the transfer physics (DESIGN §3).
    """

    n: int = 5
    tmax_days: float = 365.25
    deorbit_days: float = 0.0
    operations_dv_mps: float = 0.0
    min_transfer_days: float = 0.0
    drift_altitude_km: tuple[float, float] = (400.0, 1200.0)
    preopt_days: float = 61.0
    dv_max_mps: float = 1000.0
    drift_inclination: str = "table3"
    j2: float = J2

    def __post_init__(self):
        object.__setattr__(self, "drift_altitude_km", tuple(self.drift_altitude_km))
        problems = list(self._problems())
        if problems:
            raise MissionError("invalid mission: " + "; ".join(problems))

    def _problems(self):
        if isinstance(self.n, bool) or not isinstance(self.n, numbers.Integral):
            yield f"n must be an integer, got {self.n!r}"
        elif self.n < 2:
            yield f"n must be >= 2 (a mission visits at least two debris), got {self.n}"
        numeric = ("tmax_days", "preopt_days", "dv_max_mps", "j2", "deorbit_days",
                   "operations_dv_mps", "min_transfer_days")  # fmt: skip
        wrong_type = {name for name in numeric if not _is_real(getattr(self, name))}
        for name in sorted(wrong_type):
            yield f"{name} must be a number, got {getattr(self, name)!r}"
        for name in ("tmax_days", "preopt_days", "dv_max_mps", "j2"):
            if name not in wrong_type and not getattr(self, name) > 0:
                yield f"{name} must be > 0, got {getattr(self, name)!r}"
        for name in ("deorbit_days", "operations_dv_mps", "min_transfer_days"):
            if name not in wrong_type and not getattr(self, name) >= 0:
                yield f"{name} must be >= 0, got {getattr(self, name)!r}"
        if wrong_type:
            return
        bounds = self.drift_altitude_km
        if len(bounds) != 2:
            yield f"drift_altitude_km must be (low, high), got {bounds!r}"
        elif not 0 < bounds[0] < bounds[1]:
            yield f"drift_altitude_km must satisfy 0 < low < high, got {bounds!r}"
        if self.drift_inclination not in DRIFT_INCLINATION_RULES:
            yield (
                f"drift_inclination must be one of {DRIFT_INCLINATION_RULES}, "
                f"got {self.drift_inclination!r}"
            )
        if isinstance(self.n, numbers.Integral) and self.n >= 2 and self.tmax_days > 0:
            # operations at every debris (the last included) and n - 1 transfers
            floor = self.n * self.deorbit_days + (self.n - 1) * self.min_transfer_days
            if floor >= self.tmax_days:
                yield (
                    f"n * deorbit_days + (n - 1) * min_transfer_days = {floor:g} days leaves no "
                    f"time for transfers within tmax_days = {self.tmax_days:g}"
                )

    def check_candidates(self, n_candidates: int) -> None:
        """Raise :class:`MissionError` if the catalog has fewer than ``n`` debris."""
        if self.n > n_candidates:
            raise MissionError(f"n = {self.n} exceeds the {n_candidates} candidate debris")

    def replace(self, **changes) -> Mission:
        """A copy with some fields changed (validated again)."""
        return dataclasses.replace(self, **changes)

    def to_dict(self) -> dict:
        """Plain dict of the parameters (lists for tuples), e.g. for JSON output."""
        out = dataclasses.asdict(self)
        out["drift_altitude_km"] = list(self.drift_altitude_km)
        return out


def _is_real(value) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)

"""Campaign parameters: K missions launched on given days, each debris removed at most once.

A removal programme (the paper's motivation, Part I: about five large debris a year, for
years) is a campaign: mission k is an ordinary :class:`~sdc_cvx.inputs.mission.Mission`
that starts on its launch day ``d_k`` (days after the catalog's start date, the same
day 0 as a single mission), with every debris' RAAN carried to ``d_k`` by its own J2
rate.  Missions may overlap in time (several vehicles).  No debris is removed twice;
``must_remove`` debris are removed by some mission.  The campaign's cost is the sum of
its missions' total ΔV (operations included).

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

import dataclasses
import numbers
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from ..errors import MissionError, listing
from .mission import MAX_TMAX_DAYS, Mission, _ids_text, _is_id, _is_sequence
from .values import MAX_VALUE, RESCALE
from .vehicle import dv_ceiling_mps

DEFAULT_PERIOD_DAYS = 365.25
"""Days between two launches of ``Campaign.yearly`` (one a year)."""
MAX_CAMPAIGN_DAYS = MAX_TMAX_DAYS
"""The last day a campaign may fly [days after the start]: 10 years (the model leaves out
drag and the debris' own decay, which change the orbits over longer spans); a mission's
launch day plus its ``tmax_days`` stays within it, as a single mission's ``tmax_days`` does."""
MAX_LAUNCH_DAY = MAX_CAMPAIGN_DAYS
"""The last launch day allowed [days after the start]."""
OBJECTIVES = ("min-dv", "max-value", "value-per-dv")
"""``min-dv``: ``n`` debris per mission (or between ``n_min`` and ``n``) at the least
total ΔV; ``max-value``: the
most value removed, each mission within its ΔV budget and between ``n_min`` and ``n``
debris, and among campaigns of equal value the least ΔV; ``value-per-dv``: under the same
budgets and ranges, the least ``Σ ΔV − price · Σ value`` (``price_per_value_mps``)."""


@dataclass(frozen=True)
class Campaign:
    """K missions on given launch days, from one catalog (``docs/design.md`` §10).

    Build it with :meth:`of` (every mission from one :class:`Mission`, with per-launch
    ``n`` and ``tmax_days``) or :meth:`yearly`; the constructor takes one mission per
    launch.

    Parameters
    ----------
    launch_days : tuple of float
        Launch day of each mission [days after the catalog's start], increasing.
    missions : tuple of Mission
        The mission flown from each launch day (its ``tmax_days`` counts from it).
    must_remove : tuple of str
        Debris ids that some mission must remove (one id may be given as a string).
    remove_all : bool
        Every candidate must be removed (``must_remove`` all of the catalog's ids; the
        missions' counts must add up: ``sum(n_min) <= candidates <= sum(n)``).
    objective : {"min-dv", "max-value"}
        See :data:`OBJECTIVES`.
    dv_budget_mps : tuple of float
        ``max-value``: each mission's total ΔV budget [m/s] (one per launch).  When every
        mission's vehicle has a tank (``dry_mass_kg``, ``propellant_kg``, ``isp_s``), each
        mission must also fit it (:attr:`tank_limited`), and without budgets they are the
        most ΔV the tank can fly (:func:`~sdc_cvx.inputs.vehicle.dv_ceiling_mps`).
    n_min : tuple of int
        The fewest debris of each mission (one per launch; default its ``n``, the most):
        each mission then removes between ``n_min`` and ``n``.
    values : tuple of (str, float)
        ``max-value``: the value of removing each debris (by id; a debris not named is
        worth 0); empty: every debris is worth 1 (the most debris removed).
    price_per_value_mps : float, optional
        ``value-per-dv``: the ΔV a unit of value is worth [m/s] (> 0).

    Raises
    ------
    MissionError
        Launch days not increasing, out of [0, 10 years], a mission ending after 10
        years (launch day plus ``tmax_days``), a count that does not match,
        or a mission option that a campaign cannot honour per mission (``must_include``
        and ``first``: a debris is removed once; use ``must_remove``).
    """

    launch_days: tuple[float, ...]
    missions: tuple[Mission, ...]
    must_remove: tuple[str, ...] = ()
    remove_all: bool = False
    objective: str = "min-dv"
    dv_budget_mps: tuple[float, ...] = ()
    n_min: tuple[int, ...] = ()
    values: tuple[tuple[str, float], ...] = ()
    price_per_value_mps: float | None = None
    budgets_from_tank: bool = field(default=False, init=False)
    """The budgets are the vehicles' tanks' ΔV ceilings, not given."""

    def __post_init__(self):
        if isinstance(self.launch_days, str):  # said, not split into its characters
            raise MissionError(f"invalid campaign: launch_days must be numbers [days], got "
                               f"{self.launch_days!r} (a string)")  # fmt: skip
        if isinstance(self.launch_days, numbers.Real):
            object.__setattr__(self, "launch_days", (self.launch_days,))
        if _is_id(self.must_remove):  # one id, as Mission's must_include takes it
            object.__setattr__(self, "must_remove", (self.must_remove,))
        if _is_sequence(self.must_remove):  # a generator is read once
            object.__setattr__(self, "must_remove", tuple(self.must_remove))
        if not _is_sequence(self.must_remove) or not all(map(_is_id, self.must_remove)):
            wrong = ([k for k in self.must_remove if not _is_id(k)]
                     if _is_sequence(self.must_remove) else [self.must_remove])  # fmt: skip
            raise MissionError(f"invalid campaign: must_remove must be debris ids (strings or "
                               f"integers) or one id, got {listing(map(repr, wrong))}")  # fmt: skip
        object.__setattr__(self, "launch_days", tuple(self.launch_days))
        object.__setattr__(self, "missions", tuple(self.missions))
        object.__setattr__(self, "must_remove", tuple(str(k) for k in self.must_remove))
        count = len(self.launch_days)
        for name in ("dv_budget_mps", "n_min"):
            value = getattr(self, name)
            if isinstance(value, numbers.Real) and not isinstance(value, bool):
                value = (value,)
            value = tuple(value)
            object.__setattr__(self, name, value * count if len(value) == 1 else value)
        if self.tank_limited and not self.dv_budget_mps:
            object.__setattr__(self, "dv_budget_mps",
                               tuple(dv_ceiling_mps(m.vehicle) for m in self.missions))
            object.__setattr__(self, "budgets_from_tank", True)
        if isinstance(self.values, Mapping):
            object.__setattr__(self, "values", tuple(self.values.items()))
        object.__setattr__(self, "values", tuple((str(k), v) for k, v in self.values))
        problems = list(self._problems()) + list(self._value_problems())
        if problems:
            raise MissionError("invalid campaign: " + "; ".join(problems))

    def _problems(self):
        days = self.launch_days
        if not days:
            yield "launch_days must name at least one launch day"
            return
        bad = [d for d in days if not _is_real(d) or not 0 <= d <= MAX_LAUNCH_DAY]
        if bad:
            given = (f"; {len(bad)} of the {len(days)} given are not: " if len(bad) > 1
                     else ", got ")  # a count, not a line of thousands of characters
            yield (
                f"launch_days must be numbers in [0, {MAX_LAUNCH_DAY:g}] days (10 years: "
                f"the model leaves out drag and decay){given}{listing(bad)}"
            )
            return
        if any(b <= a for a, b in zip(days[:-1], days[1:], strict=True)):
            yield f"launch_days must increase strictly, got {listing(days)}"
        if len(self.missions) != len(days):
            yield f"{len(days)} launch days but {len(self.missions)} missions"
        for k, mission in enumerate(self.missions, start=1):
            if not isinstance(mission, Mission):
                yield f"mission {k} must be a Mission, got {type(mission).__name__}"
                continue
            if mission.must_include:
                yield (
                    f"mission {k}: must_include is a single mission's option; a campaign "
                    "removes each debris once: use must_remove"
                )
            if mission.first is not None:
                yield f"mission {k}: first cannot be set in a campaign (use injection)"
            if k <= len(days) and days[k - 1] + mission.tmax_days > MAX_CAMPAIGN_DAYS:
                yield (
                    f"mission {k} ends by day {days[k - 1] + mission.tmax_days:g} (launch "
                    f"day {days[k - 1]:g} + tmax_days {mission.tmax_days:g}), after "
                    f"{MAX_CAMPAIGN_DAYS:g} days (10 years: the model leaves out drag and "
                    "decay); launch earlier or shorten the mission"
                )
        if len(set(self.must_remove)) != len(self.must_remove):
            yield f"must_remove names a debris twice: {list(self.must_remove)}"
        if not isinstance(self.remove_all, bool):
            yield f"remove_all must be true or false, got {self.remove_all!r}"
        elif self.remove_all and self.must_remove:
            yield "remove_all removes every candidate: leave must_remove out"

    def _value_problems(self):
        count = len(self.launch_days)
        if self.objective not in OBJECTIVES:
            yield f"objective must be one of {', '.join(OBJECTIVES)}, got {self.objective!r}"
            return
        yield from self._range_problems(count)
        if self.objective == "min-dv":
            for name in ("dv_budget_mps", "values", "price_per_value_mps"):
                if getattr(self, name):
                    yield (f"{name} are for objective = 'max-value' or 'value-per-dv' (min-dv "
                           "removes n per mission)")  # fmt: skip
            return
        price = self.price_per_value_mps
        if self.objective == "value-per-dv" and not (_is_real(price) and np.isfinite(price)
                                                     and price > 0):  # fmt: skip
            yield (f"objective = 'value-per-dv' needs price_per_value_mps, the ΔV a unit of "
                   f"value is worth (a number > 0 [m/s]), got {price!r}")  # fmt: skip
        elif self.objective == "max-value" and price is not None:
            yield "price_per_value_mps is for objective = 'value-per-dv'"
        budgets = self.dv_budget_mps
        if len(budgets) != count:
            yield (f"objective = {self.objective!r} needs dv_budget_mps, one per launch (or "
                   f"one for all) [m/s], got {list(budgets) or 'none'}; or a [vehicle] with "
                   "dry_mass_kg, propellant_kg and isp_s, whose tank bounds each "
                   "mission")  # fmt: skip
        elif not all(_is_real(b) and np.isfinite(b) and b > 0 for b in budgets):
            yield f"dv_budget_mps must be numbers > 0 [m/s], got {list(budgets)}"
        bad_values = [(k, v) for k, v in self.values
                      if not (_is_real(v) and np.isfinite(v) and v >= 0)]  # fmt: skip
        if bad_values:
            yield f"values must be numbers >= 0, got {bad_values[:5]}"
        elif any(v > MAX_VALUE for _, v in self.values):
            large = [(k, v) for k, v in self.values if v > MAX_VALUE]
            yield (f"values must be at most {MAX_VALUE:g} (the MILP's coefficients), got "
                   f"{large[:5]}: {RESCALE}")  # fmt: skip
        elif self.values and not any(v for _, v in self.values):
            yield (f"values are all 0 ({len(self.values)} debris): such values mean nothing "
                   "(every choice of debris is worth 0); give the debris that matter a value "
                   "> 0")  # fmt: skip
        if self.must_remove or self.remove_all:
            yield ("must_remove and remove_all are for objective = 'min-dv' (max-value chooses "
                   "what to remove)")  # fmt: skip

    def _range_problems(self, count: int):
        if not self.n_min:
            return
        # a value objective may leave a launch unused (0) or fly one debris (the launch
        # alone); a min-dv campaign removes n_min at least, each mission two at least
        low = 0 if self.objective != "min-dv" else 2
        bad = len(self.n_min) != count or not all(
            isinstance(k, numbers.Integral) and not isinstance(k, bool) and low <= k <= m.n
            for k, m in zip(self.n_min, self.missions, strict=False))  # fmt: skip
        if bad:  # the ranges as written: one for all launches, or one per launch
            pairs = [[k, m.n] for k, m in zip(self.n_min, self.missions, strict=False)]
            got = (f"n = {pairs[:1] if pairs.count(pairs[0]) == count else pairs}"
                   if len(self.n_min) == count else f"n_min {list(self.n_min)} for n_max "
                   f"{[m.n for m in self.missions]}")  # fmt: skip
            why = " (objective = 'min-dv': a mission removes two debris at least)" if low else ""
            yield (f"n ranges must be [n_min, n_max] with {low} <= n_min <= n_max, one per "
                   f"launch, got {got}{why}")  # fmt: skip
            return
        injected = [k + 1 for k, (few, m) in enumerate(zip(self.n_min, self.missions,
                                                           strict=True))
                    if few == 1 and isinstance(m, Mission) and m.injection is not None]  # fmt: skip
        if injected:
            yield (f"mission {', '.join(map(str, injected))}: n_min = 1 with an injection "
                   "orbit (a mission of one debris is then a transfer, not searched): "
                   "n_min = 0 or >= 2, or no injection")  # fmt: skip

    @property
    def tank_limited(self) -> bool:
        """A value objective whose every mission must fit its vehicle's tank (each
        vehicle with ``dry_mass_kg``, ``propellant_kg`` and ``isp_s``)."""
        return self.objective != "min-dv" and bool(self.missions) and all(
            isinstance(m, Mission) and m.vehicle is not None and m.vehicle.can_budget()
            and m.vehicle.propellant_kg is not None for m in self.missions)  # fmt: skip

    def fewest(self, k: int) -> int:
        """The fewest debris mission ``k`` (0-based) removes."""
        return self.n_min[k] if self.n_min else self.missions[k].n

    def removing(self, ids, launches=None, *, ranges: bool = True) -> Campaign:
        """The min-ΔV campaign of ``launches`` (indices, default all) that removes exactly
        the debris ``ids``: every one a ``must_remove``, each mission's excluded debris
        kept where they are among them; with ``ranges``, each mission between its fewest
        and its most debris, else its most.  The searches over a part of a campaign use
        it (a first campaign of high value, a window of launches shared out again)."""
        ids = tuple(str(k) for k in ids)
        launches = range(len(self.launch_days)) if launches is None else launches
        missions = tuple(self.missions[k].replace(exclude=tuple(
            d for d in self.missions[k].exclude if d in ids)) for k in launches)  # fmt: skip
        return dataclasses.replace(
            self, launch_days=tuple(self.launch_days[k] for k in launches), missions=missions,
            objective="min-dv", must_remove=ids, remove_all=False, dv_budget_mps=(),
            n_min=tuple(self.fewest(k) for k in launches) if ranges else (), values=(),
            price_per_value_mps=None)  # fmt: skip

    def value_of(self, ids) -> np.ndarray:
        """The value of removing each of ``ids`` (1 each without values; 0 if not named)."""
        if not self.values:
            return np.ones(len(ids))
        table = dict(self.values)
        return np.array([float(table.get(str(k), 0.0)) for k in ids])

    # ------------------------------------------------------------------ constructors
    @classmethod
    def of(cls, launch_days: Sequence[float], mission: Mission | None = None, *,
           n: int | Sequence[int] | None = None,
           tmax_days: float | Sequence[float] | None = None,
           must_remove: Sequence[str] = (), **value_options) -> Campaign:  # fmt: skip
        """One mission per launch day, each ``mission`` with its own ``n`` and ``tmax_days``.

        Parameters
        ----------
        launch_days : sequence of float
            [days after the catalog's start].
        mission : Mission, optional
            Every mission's parameters (default ``Mission()``).
        n, tmax_days : int / float, or a sequence with one per launch, optional
            Debris per mission and duration limit [days]; default ``mission``'s.  An
            ``n`` may be a range ``[n_min, n_max]`` (``[[n_min, n_max]]``: the same for
            every launch).
        must_remove : sequence of str
        value_options
            ``remove_all``, ``objective``, ``dv_budget_mps``, ``values`` (see the class).
        """
        for name, value in (("launch_days", launch_days), ("n", n), ("tmax_days", tmax_days)):
            if isinstance(value, str):  # said, not split into its characters
                raise MissionError(f"invalid campaign: {name} must be a number or a sequence "
                                   f"of numbers, got {value!r} (a string)")  # fmt: skip
        mission = Mission() if mission is None else mission
        days = (launch_days,) if isinstance(launch_days, numbers.Real) else tuple(launch_days)
        if isinstance(n, Sequence) and any(isinstance(k, Sequence) and not isinstance(k, str)
                                           for k in n):  # fmt: skip
            ranges = [tuple(k) if isinstance(k, Sequence) else (k, k) for k in n]
            if any(len(pair) != 2 for pair in ranges):
                raise MissionError(f"invalid campaign: n ranges must be [n_min, n_max] pairs, "
                                   f"got {list(n)}")  # fmt: skip
            if len(ranges) == 1:  # one range for every launch
                ranges *= len(days)
            value_options = {"n_min": tuple(pair[0] for pair in ranges), **value_options}
            n = [pair[1] for pair in ranges]
        counts = _per_launch("n", n, mission.n, len(days))
        limits = _per_launch("tmax_days", tmax_days, mission.tmax_days, len(days))
        try:
            missions = tuple(mission.replace(n=c, tmax_days=t)
                             for c, t in zip(counts, limits, strict=True))  # fmt: skip
        except MissionError as err:
            raise MissionError(f"invalid campaign: {err}") from None
        return cls(days, missions, must_remove, **value_options)

    @classmethod
    def yearly(cls, missions: int, mission: Mission | None = None, *,
               first_launch_day: float = 0.0, period_days: float = DEFAULT_PERIOD_DAYS,
               **options) -> Campaign:  # fmt: skip
        """``missions`` launches ``period_days`` apart from ``first_launch_day``.

        Other keywords (``n``, ``tmax_days``, ``must_remove``) as in :meth:`of`.
        """
        if isinstance(missions, bool) or not isinstance(missions, numbers.Integral) \
                or missions < 1:  # fmt: skip
            raise MissionError(f"invalid campaign: missions must be an integer >= 1, "
                               f"got {missions!r}")  # fmt: skip
        if not (_is_real(period_days) and period_days > 0):
            raise MissionError(f"invalid campaign: period_days must be > 0, got {period_days!r}")
        if not _is_real(first_launch_day):
            raise MissionError(
                f"invalid campaign: first_launch_day must be a number, got {first_launch_day!r}"
            )
        days = [first_launch_day + k * period_days for k in range(missions)]
        return cls.of(days, mission, **options)

    # ------------------------------------------------------------------ use
    def __len__(self) -> int:
        return len(self.launch_days)

    @property
    def debris_removed(self) -> int:
        """Debris removed by the whole campaign at least (the sum of the missions' n, or
        of their fewest with ranges)."""
        return sum(self.fewest(k) for k in range(len(self.missions)))

    @property
    def most_removed(self) -> int:
        """Debris removed by the whole campaign at most (the sum of the missions' n)."""
        return sum(m.n for m in self.missions)

    def counts_text(self) -> str:
        """Each mission's debris, ``n`` or ``n_min-n`` (e.g. ``"5, 4-5"``)."""
        return ", ".join(str(m.n) if self.fewest(k) == m.n else f"{self.fewest(k)}-{m.n}"
                         for k, m in enumerate(self.missions))  # fmt: skip

    def required(self, catalog) -> tuple[str, ...]:
        """The ids some mission must remove: ``must_remove``, or with ``remove_all`` every
        candidate of ``catalog`` (a Catalog or its ids) that some mission may remove."""
        if not self.remove_all:
            return self.must_remove
        excluded = set.intersection(*(set(m.exclude) for m in self.missions))
        return tuple(k for k in (str(k) for k in getattr(catalog, "ids", catalog))
                     if k not in excluded)  # fmt: skip

    def check_candidates(self, catalog) -> None:
        """Raise :class:`MissionError` if the campaign cannot fit the catalog.

        Each mission's own check (``Mission.check_candidates``: ``catalog`` is the
        :class:`~sdc_cvx.inputs.catalog.Catalog`, or its ids), ``must_remove`` ids that
        exist and are not excluded from every mission, enough candidates for all the
        missions together, and values (if given) that name at least one candidate.
        """
        ids = [str(k) for k in getattr(catalog, "ids", catalog)]
        known = set(ids)
        problems = []
        for k, mission in enumerate(self.missions, start=1):
            try:
                mission.check_candidates(catalog)
            except MissionError as err:
                problems.append(f"mission {k} (launch day {self.launch_days[k - 1]:g}): {err}")
        unknown = [d for d in self.must_remove if d not in known]
        if unknown:
            problems.append(f"must_remove names debris not in the catalog: {_ids_text(unknown)}")
        nowhere = [d for d in self.must_remove if d in known
                   and all(d in m.exclude for m in self.missions)]  # fmt: skip
        if nowhere:
            problems.append(f"must_remove debris excluded from every mission: {', '.join(nowhere)}")
        if len(self.must_remove) > self.most_removed:
            problems.append(
                f"must_remove names {len(self.must_remove)} debris but the missions remove "
                f"{self.most_removed} at most"
            )
        usable = known - set.intersection(*(set(m.exclude) for m in self.missions))
        if self.debris_removed > len(usable):
            problems.append(
                f"the missions remove {self.debris_removed} debris in all "
                f"({self.counts_text()}) but the catalog has {len(usable)} candidates: each "
                "debris is removed once"
            )
        elif self.remove_all and len(usable) > self.most_removed:
            problems.append(
                f"remove_all: the catalog has {len(usable)} candidates but the missions remove "
                f"{self.most_removed} at most ({self.counts_text()}): add missions or raise n"
            )
        if self.values and known.isdisjoint(name for name, _ in self.values):
            sample = ", ".join(repr(name) for name, _ in self.values[:3])
            problems.append(
                f"none of the {len(self.values)} ids of the values ({sample}, ...) is a "
                f"candidate (such as {', '.join(map(repr, ids[:3]))}): every mission would "
                "remove nothing of value; check the values file's id column (values_columns)")
        elif self.values and not any(v > 0 for name, v in self.values if name in known):
            named = [name for name, _ in self.values if name in known]
            problems.append(
                f"the {len(named)} candidate(s) the values name ({_ids_text(named)}) are all "
                "worth 0: every mission would remove nothing of value; give the debris that "
                "matter a value > 0")
        if problems:
            raise MissionError("; ".join(problems))

    def to_dict(self) -> dict:
        """Plain dict: launch days, ``n`` and ``tmax_days`` per mission, must_remove, and
        each mission's parameters."""
        return {
            "launch_days": list(self.launch_days),
            "n": [m.n for m in self.missions],
            "tmax_days": [m.tmax_days for m in self.missions],
            "must_remove": list(self.must_remove),
            "missions": [m.to_dict() for m in self.missions],
        } | ({"remove_all": True} if self.remove_all else {}) | (
            {"n_min": [self.fewest(k) for k in range(len(self.missions))]} if self.n_min
            else {}) | ({} if self.objective == "min-dv" else {
            "objective": self.objective, "dv_budget_mps": list(self.dv_budget_mps),
            "dv_budget_from": "tank" if self.budgets_from_tank else "given",
            "n_min": [self.fewest(k) for k in range(len(self.missions))],
            "values": dict(self.values)}) | ({} if self.price_per_value_mps is None else {
            "price_per_value_mps": self.price_per_value_mps})  # fmt: skip


def _per_launch(name, value, default, count):
    if value is None:
        return [default] * count
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return [value] * count
    values = list(value)
    if len(values) != count:
        raise MissionError(
            f"invalid campaign: {name} has {len(values)} values for {count} launch days "
            f"(give one per launch, or one number for all), got {values}"
        )
    return values


def _is_real(value) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)

"""Mean rates the phasing can trust: measured on the orbits as they are flown.

The phasing (:mod:`sdc_cvx.physics.phasing`) needs where the target will be after a coast
of weeks.  First-order secular J2 rates are not good enough for that: over a 50-day coast
(about 720 revolutions at 800 km) a mean motion wrong by 1e-6 of itself (a second-order
J2 term, or a semi-major axis 5 m off) puts the vehicle 30 km from the debris, and SGP4's
debris move with J2², J3, J4 and drag terms besides (issue 26, item 4).  So the phasing
uses rates *measured*:

- ``rates="fitted"`` (the default): each target's mean RAAN and argument of latitude
  from its own SGP4 states averaged over one orbit, at the two ends of the leg's window
  and every :data:`FIT_STEP_DAYS` between, give where it is over the leg (drag lowers a
  debris and speeds its argument of latitude up: at 760 km, B* 3e-4, a line through the
  ends of a year puts a debris 140 degrees from where SGP4 has it in the middle); the
  drift orbit's rates are those of a one-day numerical propagation of it (as factors on
  the first-order rates, which carry the dependence on the radius the phasing searches).
- ``rates="model"``: each target where SGP4 has it when the leg starts, then carried by
  the first-order J2 rates of the catalog's mean elements, as the planner has them: the
  replay then shows what the model's rates alone miss.

A mean element here is the average over one orbit of the osculating one, sampled
uniformly in time: short-period J2 terms (about 10 km in a, 0.05 deg in the argument of
latitude at 800 km) average out, as the mean anomaly runs uniformly.  All SI (m, s, rad).

References
----------
.. [1] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
   Microcosm Press, 2013, §9.6 (secular J2 effects) and §9.7 (short-periodic effects).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..physics.elements import secular_rates, state_to_elements
from ..physics.phasing import MeanOrbit
from .frames import equatorial_basis
from .propagation import ForceModel, orbit_average, propagate

RATE_MODES = ("fitted", "model")
SAMPLES = 64
"""Samples of one orbit in a mean state."""
DRIFT_FIT_DAYS = 1.0
"""Length of the propagation that measures a drift orbit's rates [days]."""
FIT_STEP_DAYS = 5.0
"""Step between a target's mean states over a leg's window [days]: where drag is
strongest in the catalogues (760 km, B* 3e-4), 3 km at most between two states followed
linearly."""


class MeanState(NamedTuple):
    """Mean (orbit-averaged) elements at the middle ``t`` [s] of one sampled orbit."""

    t: float
    a: float
    inc: float
    raan: float
    arglat: float


def mean_state(times, r, v, *, mu: float, pole) -> MeanState:
    """Orbit-averaged a, i, RAAN and argument of latitude of states sampled uniformly
    over one period (``times`` [s], ``r`` [m], ``v`` [m/s] arrays (m, 3)).

    a, i and RAAN are :func:`~sdc_cvx.flight.propagation.orbit_average`'s (the RAAN in
    [0, 2 pi)); the angles are in the equator of ``pole``; the argument of latitude is the mean of
    the unwrapped samples, which is the mean one at the middle of the samples (a line fit
    through them passes there; its periodic terms average out over the period).
    """
    averaged = orbit_average(r, v, mu=mu, pole=pole)  # a, i and RAAN
    basis = equatorial_basis(pole)
    elements = state_to_elements(np.asarray(r) @ basis.T, np.asarray(v) @ basis.T, mu=mu)
    return MeanState(t=float(np.mean(times)), a=averaged.a, inc=averaged.inc,
                     raan=averaged.raan, arglat=float(np.mean(np.unwrap(elements.arglat))))


def propagated_mean_state(r, v, t: float, model: ForceModel, pole) -> MeanState:
    """The mean state of the orbit through ``(r, v)`` at ``t`` [s], by propagating it over
    one orbit: twice, the second time over the period of the first's mean elements (an
    osculating radius is kilometres from the mean one; a window 1e-3 too long leaves some
    30 m of short-period terms in the mean ``a``, 10 km of drift a month later)."""
    rate = secular_rates(np.linalg.norm(r), 0.0, 0.0, j2=model.j2, mu=model.mu,
                         r_eq=model.r_eq).arglat  # fmt: skip
    for _ in range(2):
        times = _one_orbit(t, 2.0 * np.pi / rate)
        arc = propagate(r, v, t, times[-1], model, pole=pole, t_eval=times)
        state = mean_state(arc.t, arc.r, arc.v, mu=model.mu, pole=pole)
        rate = secular_rates(state.a, 0.0, state.inc, j2=model.j2, mu=model.mu,
                             r_eq=model.r_eq).arglat  # fmt: skip
    return state


def _one_orbit(t_start: float, period: float) -> np.ndarray:
    return t_start + np.linspace(0.0, period, SAMPLES, endpoint=False)


def _through(states: list[MeanState], guess: MeanOrbit) -> MeanOrbit:
    """The mean orbit whose RAAN and argument of latitude pass through the first and the
    last of ``states``, with how far from those lines the states between are (its
    ``wander``; none for two states).  The whole revolutions from one state to the next
    are counted with the rate of the span before (the first with the ``guess``'s)."""
    t = np.array([state.t for state in states])
    lines, wander = {}, [t]
    for name, rate in (("raan", guess.raan_rate), ("arglat", guess.arglat_rate)):
        angle = [getattr(states[0], name)]
        for k in range(1, len(states)):
            step = getattr(states[k], name) - getattr(states[k - 1], name)
            step += 2.0 * np.pi * np.round((rate * (t[k] - t[k - 1]) - step) / (2.0 * np.pi))
            angle.append(angle[-1] + step)
            rate = step / (t[k] - t[k - 1])
        angle = np.array(angle)
        slope = (angle[-1] - angle[0]) / (t[-1] - t[0])
        lines[name], lines[f"{name}_rate"] = angle[0] - slope * t[0], slope
        wander.append(angle - (angle[0] + slope * (t - t[0])))
    return guess._replace(a=states[0].a, inc=states[0].inc, **lines,
                          wander=tuple(wander) if len(states) > 2 else None)  # fmt: skip


def fitted_orbit(ephemeris, position: int, t_start: float, t_end: float, guess: MeanOrbit,
                 model: ForceModel, pole) -> MeanOrbit:  # fmt: skip
    """Debris ``position``'s mean orbit over [t_start, t_end] [s], fitted to its SGP4 states.

    Mean states at the two ends and every :data:`FIT_STEP_DAYS` between: the RAAN and the
    argument of latitude on the line through the two ends, and how far from it each
    state is (:class:`~sdc_cvx.physics.phasing.MeanOrbit`'s ``wander``, followed linearly
    between the states; :func:`_through`).  ``guess``, its first-order model, counts the
    revolutions of the first span, each span's rate those of the next: drag speeds a
    debris' argument of latitude up by some 1e-3 rad/day in :data:`FIT_STEP_DAYS` at
    760 km, too much to count a year's revolutions at once.
    """
    period = 2.0 * np.pi / guess.arglat_rate
    last = max(t_end - period, t_start + period)
    count = max(int(np.ceil((last - t_start) / (FIT_STEP_DAYS * 86400.0))), 1) + 1
    states = []
    for t in np.linspace(t_start, last, count):
        times = _one_orbit(t, period)
        r, v = ephemeris.state(position, times)
        states.append(mean_state(times, r, v, mu=model.mu, pole=pole))
    return _through(states, guess)


def placed_orbit(ephemeris, position: int, t_start: float, guess: MeanOrbit, model: ForceModel,
                 pole) -> MeanOrbit:  # fmt: skip
    """Debris ``position`` where SGP4 has it at ``t_start`` [s] (mean state, one orbit), then
    carried by ``guess``'s rates (``rates="model"``: where the model alone sends it)."""
    period = 2.0 * np.pi / guess.arglat_rate
    times = _one_orbit(t_start, period)
    r, v = ephemeris.state(position, times)
    now = mean_state(times, r, v, mu=model.mu, pole=pole)
    return guess._replace(a=now.a, inc=now.inc, raan=now.raan - guess.raan_rate * now.t,
                          arglat=now.arglat - guess.arglat_rate * now.t)


def drift_factors(a: float, inc: float, t: float, model: ForceModel, pole) -> tuple[float, float]:
    """The RAAN and argument-of-latitude rates of a circular orbit as the force model flies
    it, over the first-order rates at its mean elements (:data:`DRIFT_FIT_DAYS` of it)."""
    from ..physics.elements import elements_to_state

    basis = equatorial_basis(pole)
    r0, v0 = elements_to_state(a, 0.0, inc, 0.0, 0.0, 0.0, mu=model.mu)
    r0, v0 = np.asarray(r0) @ basis, np.asarray(v0) @ basis  # to GCRF
    guess = secular_rates(a, 0.0, inc, j2=model.j2, mu=model.mu, r_eq=model.r_eq)
    end = t + DRIFT_FIT_DAYS * 86400.0
    arc = propagate(r0, v0, t, end, model, pole=pole)
    states = [propagated_mean_state(r0, v0, t, model, pole),
              propagated_mean_state(arc.r1, arc.v1, end, model, pole)]  # fmt: skip
    start = MeanOrbit(a, 0.0, inc, 0.0, 0.0, float(guess.raan), float(guess.arglat))
    measured = _through(states, start)
    mean = secular_rates(states[0].a, 0.0, states[0].inc, j2=model.j2, mu=model.mu,
                         r_eq=model.r_eq)  # fmt: skip
    return measured.raan_rate / float(mean.raan), measured.arglat_rate / float(mean.arglat)

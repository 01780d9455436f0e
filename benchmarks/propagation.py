"""Numerical propagation: which integrator, at which tolerance, and the OEM sample step.

Usage: python benchmarks/propagation.py [--days 50] [--skip-slow]

1. A 50-day coast at 800 km, 98.6 deg, J2 only (about 720 orbits), by
   ``scipy.integrate.ode("dop853")`` (Hairer's step loop in compiled code),
   ``solve_ivp("DOP853")`` (the same method, a Python step loop), ``odeint`` (LSODA) and
   ``ode("vode", adams)``, each at a few tolerances: seconds, right-hand side calls,
   steps/s (DOP853: 12 calls a step) and the final position error against DOP853 at
   rtol 3e-14 (its own error: the difference to rtol 1e-13, printed first).  The same
   right-hand side for all: :func:`sdc_cvx.flight.propagation._rhs`.
2. :func:`sdc_cvx.flight.propagation.propagate` itself (the Fortran DOP853, every step
   kept, Hermite interpolation) at its defaults, with and without OEM samples.
3. The OEM's Lagrange interpolation error on an 800 km circular orbit against the step
   and the degree: the largest error between samples, in the middle of a segment
   (centred windows) and at its ends (one-sided windows).

The module docstrings of :mod:`sdc_cvx.flight.propagation` and :mod:`sdc_cvx.flight.oem`
quote one output (a shared 2-core machine).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import ode, odeint, solve_ivp

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

from readme_examples import machine  # noqa: E402

from sdc_cvx.flight.oem import OEM_DEGREE, OEM_STEP_S  # noqa: E402
from sdc_cvx.flight.propagation import ForceModel, _rhs, propagate  # noqa: E402

FORCE = ForceModel()
POLE = np.array([0.0, 0.0, 1.0])


def initial_state(altitude=800e3, inc_deg=98.6):
    a = FORCE.r_eq + altitude
    speed = math.sqrt(FORCE.mu / a)
    inc = math.radians(inc_deg)
    return np.array([a, 0.0, 0.0, 0.0, speed * math.cos(inc), speed * math.sin(inc)])


def counted(rhs):
    calls = [0]

    def f(t, y):
        calls[0] += 1
        return rhs(t, y)

    return f, calls


def fortran_dop853(y0, span, rtol, atol, name="dop853", **options):
    f, calls = counted(_rhs(FORCE, POLE))
    solver = ode(f).set_integrator(name, rtol=rtol, atol=atol, nsteps=10**9, **options)
    solver.set_initial_value(y0, 0.0)
    start = time.perf_counter()
    y = solver.integrate(span)
    return y, time.perf_counter() - start, calls[0]


def ivp_dop853(y0, span, rtol, atol):
    rhs = _rhs(FORCE, POLE)
    f, calls = counted(lambda t, y: np.array(rhs(t, y)))
    start = time.perf_counter()
    sol = solve_ivp(f, (0.0, span), y0, method="DOP853", rtol=rtol, atol=atol)
    return sol.y[:, -1], time.perf_counter() - start, calls[0]


def lsoda(y0, span, rtol, atol):
    rhs = _rhs(FORCE, POLE)
    f, calls = counted(lambda y, t: rhs(t, y))
    start = time.perf_counter()
    y = odeint(f, y0, [0.0, span], rtol=rtol, atol=atol, mxstep=10**8)
    return y[-1], time.perf_counter() - start, calls[0]


def integrators(days: float, skip_slow: bool) -> None:
    y0, span = initial_state(), days * 86400.0
    ref, seconds, calls = fortran_dop853(y0, span, 3e-14, 1e-9)
    check, _, _ = fortran_dop853(y0, span, 1e-13, 1e-7)
    print(f"\n{days:g}-day coast at 800 km, 98.6 deg, J2: reference DOP853 rtol 3e-14 "
          f"({seconds:.2f} s, {calls} calls); rtol 1e-13 differs by "
          f"{np.linalg.norm(check[:3] - ref[:3]):.3f} m")  # fmt: skip
    print(f"{'integrator':28s} {'rtol':>7s} {'atol':>7s} {'seconds':>8s} {'calls':>9s} "
          f"{'steps/s':>9s} {'error m':>10s}")  # fmt: skip
    runs = [("ode dop853 (Fortran loop)", fortran_dop853, rtol, atol)
            for rtol, atol in ((1e-10, 1e-4), (1e-11, 1e-5), (3e-12, 1e-6), (1e-12, 1e-5),
                               (1e-12, 1e-6), (1e-12, 1e-7))]  # fmt: skip
    runs += [("solve_ivp DOP853", ivp_dop853, 1e-12, 1e-6)]
    runs += [("ode vode adams", lambda *a: fortran_dop853(*a, name="vode", method="adams",
                                                          order=12), 1e-13, 1e-10)]  # fmt: skip
    if not skip_slow:
        runs += [("solve_ivp DOP853", ivp_dop853, 1e-11, 1e-5)]
        runs += [("odeint LSODA", lsoda, rtol, rtol * 1e6) for rtol in (1e-11, 1e-13)]
    for label, run, rtol, atol in runs:
        y, seconds, calls = run(y0, span, rtol, atol)
        steps = calls / 12 if "DOP853" in label.upper() else float("nan")
        print(f"{label:28s} {rtol:7.0e} {atol:7.0e} {seconds:8.2f} {calls:9d} "
              f"{steps / seconds:9.0f} {np.linalg.norm(y[:3] - ref[:3]):10.3f}")  # fmt: skip
    for label, t_eval in (("propagate()", None),
                          (f"propagate(), OEM samples {OEM_STEP_S:g} s",
                           np.arange(0.0, span, OEM_STEP_S))):  # fmt: skip
        start = time.perf_counter()
        arc = propagate(y0[:3], y0[3:], 0.0, span, FORCE, pole=POLE, t_eval=t_eval)
        seconds = time.perf_counter() - start
        print(f"{label:38s} {seconds:6.2f} s, {arc.steps} steps ({arc.steps / seconds:.0f}/s), "
              f"{arc.nfev} calls, error {np.linalg.norm(arc.r1 - ref[:3]):.3f} m")  # fmt: skip


def lagrange(t_nodes, values, t, degree):
    """Lagrange interpolation of ``values`` (n, 3) at ``t`` on the ``degree + 1`` nodes
    nearest to each time (a centred window, clamped at the ends)."""
    n = len(t_nodes)
    out = np.empty((len(t), 3))
    for j, tj in enumerate(t):
        k = int(np.searchsorted(t_nodes, tj)) - (degree + 1) // 2
        k = min(max(k, 0), n - degree - 1)
        xs = t_nodes[k : k + degree + 1]
        weights = [np.prod([(tj - xs[m]) / (xs[i] - xs[m]) for m in range(degree + 1) if m != i])
                   for i in range(degree + 1)]  # fmt: skip
        out[j] = np.asarray(weights) @ values[k : k + degree + 1]
    return out


def oem_steps() -> None:
    y0 = initial_state()
    span = 4 * 3600.0
    print("\nLagrange interpolation error on an 800 km circular orbit [m], between samples: "
          "middle of a segment / its first interval")  # fmt: skip
    steps = (30.0, 60.0, 120.0, 180.0, 240.0, 300.0)
    print(f"{'degree':>6s} " + " ".join(f"{f'{s:g} s':>17s}" for s in steps))
    for degree in (5, 7, 9, 11):
        cells = []
        for step in steps:
            nodes = np.arange(0.0, span + step / 2, step)
            fine = np.linspace(0.0, nodes[-1], 4001)
            arc = propagate(y0[:3], y0[3:], 0.0, nodes[-1] + 1.0, FORCE, pole=POLE,
                            t_eval=np.union1d(nodes, fine))  # fmt: skip
            at = {t: r for t, r in zip(arc.t, arc.r, strict=True)}
            samples = np.array([at[t] for t in nodes])
            truth = np.array([at[t] for t in fine])
            error = np.linalg.norm(lagrange(nodes, samples, fine, degree) - truth, axis=1)
            middle = (fine > nodes[degree]) & (fine < nodes[-degree - 1])
            cells.append(f"{error[middle].max():8.3g} / {error[fine < nodes[1]].max():6.3g}")
        print(f"{degree:6d} " + " ".join(f"{c:>17s}" for c in cells))
    print(f"(the OEM: degree {OEM_DEGREE}, step {OEM_STEP_S:g} s)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--days", type=float, default=50.0)
    parser.add_argument("--skip-slow", action="store_true", help="no LSODA, one solve_ivp")
    args = parser.parse_args()
    print("\n".join(machine()))
    integrators(args.days, args.skip_slow)
    oem_steps()


if __name__ == "__main__":
    main()

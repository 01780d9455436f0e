"""``flight.png`` read from the figure's data, not its pixels (issue 48, item 19)."""

from __future__ import annotations

from datetime import datetime
from types import SimpleNamespace

import numpy as np
import pandas as pd

from sdc_cvx.flight import plot


def flight(phasing, misses_km):
    """A stand-in of a flown two-leg impulsive plan: what the figure reads of a Flight."""
    rows = enumerate(zip(phasing, misses_km, ("B", "C"), strict=True))
    meetings = [SimpleNamespace(phasing_dv_mps=p, correction_dv_mps=0.05, target=t,
                                miss_km=m, epoch_s=(k + 1) * 50 * 86400.0)
                for k, (p, m, t) in rows]  # fmt: skip
    legs = [SimpleNamespace(drift_a_km=7050.0, departure_day=10.0 + 50 * k,
                            arrival_day=50.0 * (k + 1)) for k in range(2)]  # fmt: skip
    plan = SimpleNamespace(
        accel_mps2=None, legs=legs, tmax_days=120.0, plan_end_day=100.0,
        start=datetime(2020, 5, 26, 8, 51),
        catalog=SimpleNamespace(frame=pd.DataFrame({"a_km": [7000.0, 7010.0, 7020.0]})),
    )  # fmt: skip
    days = np.linspace(0.0, 100.0, 2000)
    return SimpleNamespace(
        rendezvous=meetings, plan=plan, force=SimpleNamespace(r_eq=6378137.0, mu=3.986e14),
        status="flown", flown_dv_mps=90.0, planned_dv_flown_mps=96.0, complete=True,
        worst_miss_km=max(misses_km), altitude_profile=lambda: (days, 640.0 + 0 * days),
    )  # fmt: skip


def drawn(monkeypatch, tmp_path, flown):
    figures = []
    monkeypatch.setattr(plot, "write_figure", lambda fig, *args: figures.append(fig))
    plot.flight_figure(flown, tmp_path / "flight.png")
    (fig,) = figures
    fig.canvas.draw()  # the limits and the layout as written
    return fig


def test_a_miss_is_drawn_at_or_above_the_zero_of_the_dv_it_is_drawn_beside(monkeypatch,
                                                                          tmp_path):  # fmt: skip
    """The SSO flight: phasing -5.88 m/s on leg 2, misses under a millimetre: on a second
    axis of the ΔV panel, the miss axis's zero sat at the panel's bottom, -6 m/s, and both
    misses were drawn far below the ΔV's zero line."""
    fig = drawn(monkeypatch, tmp_path, flight([-0.11, -5.88], [5.2e-8, 7.1e-7]))
    bars = [ax for ax in fig.axes if ax.patches]
    marked = [ax for ax in fig.axes
              if any(line.get_marker() == "o" and len(line.get_xdata()) == 2
                     for line in ax.get_lines())]  # fmt: skip
    assert len(bars) == 1 and len(marked) == 1
    dv_ax, miss_ax = bars[0], marked[0]
    assert miss_ax.get_ylim()[0] >= 0.0  # no room for a miss below zero
    dv_box, miss_box = dv_ax.get_position(), miss_ax.get_position()
    if dv_box.overlaps(miss_box):  # one panel: a zero for both
        dv_zero = dv_ax.transData.transform((0.0, 0.0))[1]
        miss_zero = miss_ax.transData.transform((0.0, 0.0))[1]
        assert abs(dv_zero - miss_zero) < 1.0, (dv_zero, miss_zero)

"""A short flight replayed by physics that is not the package's (issue 46, "How we will know").

A real run folder (``sdc_cvx run`` then ``fly``, as processes) of two SSO rocket bodies
within 12 days; then ``benchmarks/independent_replay.py`` with the integrator, frames and
ephemeris of ``benchmarks/replay_physics.py`` (two-body + J2 by DOP853, the pole of date and
TEME -> GCRS by skyfield, SGP4 by the ``sgp4`` library on the TLE lines read there; nothing
of sdc_cvx): the leg flown open-loop from the debris through the impulses of
``maneuvers.csv`` meets the next debris within issue 46's 100 m and 0.1 m/s, and stays on
the OEM's states; the impulses add up to ``flight.json``'s total, within 1.03 times the plan.

Seen to fail: with the package's J2 0.1 % off (``ForceModel.j2`` 1.0837e-3 in a copy of the
tree) the package still met its debris in its own world, the replay missed it by 20.6 km
and 22 m/s (the package's own misses: metres and mm/s here, from the 31 mas between its
IAU 1976/1980 pole of date and skyfield's IAU 2006/2000A one).
"""

import json

import numpy as np
import pytest

from tests.conftest import computed_once, shared_file
from tests.test_cli import cli_process

TLE = "sso_rocket_bodies_2020/sso_rb.tle"
pytestmark = [pytest.mark.slow, pytest.mark.requires_shared_data(TLE)]
SCENARIO = """\
[catalog]
path = {path}

[mission]
n = 2
tmax_days = 12
"""


@pytest.fixture(scope="module")
@computed_once
def flown(tmp_path_factory):
    """The folder flown, read by the independent replay (``load``)."""
    pytest.importorskip("skyfield.api", reason="the replay's TEME -> GCRS (pip install skyfield)")
    from benchmarks import independent_replay

    work = tmp_path_factory.mktemp("replayed")
    scenario = work / "two.toml"
    scenario.write_text(SCENARIO.format(path=json.dumps(str(shared_file(TLE)))), encoding="utf-8")
    folder = work / "run"
    run = cli_process("run", str(scenario), "--out", str(folder), "--quiet")
    assert run.returncode == 0, run.stderr
    fly = cli_process("fly", str(folder))
    assert fly.returncode == 0, fly.stderr
    return independent_replay, independent_replay.load(folder)


def test_the_leg_flown_independently_meets_the_debris_within_100_m_and_0_1_mps(flown):
    replay, f = flown
    assert len(f.t_meet) == len(f.solution["legs"]) == 1
    states, worst, _ = replay.fly_legs(f, replay.leg_rhs(f), compare=True)
    for target, (miss_m, miss_mps) in zip(f.targets, replay.rendezvous_misses(f, states),
                                          strict=True):  # fmt: skip
        assert miss_m < 100.0 and miss_mps < 0.1, (target, miss_m, miss_mps)
    # the replay stays on the OEM's states all along (each within the replay's own metres)
    assert worst[0] < 100.0 and worst[1] < 0.1, worst


def test_the_oem_meets_the_debris_where_sgp4_and_skyfield_place_it(flown):
    _, f = flown
    for k, t in enumerate(f.t_meet):
        j = int(np.argmin(np.abs(f.seg_start - t)))
        assert abs(f.seg_start[j] - t) < 1e-5
        r, v = f.goal_states[k]
        assert np.linalg.norm(f.oem.states[j][0, :3] - r) < 100.0
        assert np.linalg.norm(f.oem.states[j][0, 3:] - v) < 0.1


def test_the_impulses_add_up_to_the_flown_total_within_the_goal(flown):
    _, f = flown
    total = float(np.linalg.norm(f.dv, axis=1).sum())
    assert total == pytest.approx(f.summary["flown_dv_mps"], rel=1e-9)
    assert total <= 1.03 * f.solution["total_dv_mps"]

"""GTOC9's Kessler Run under its own rules (issue 47): the campaign the search finds for J.

Runs :func:`sdc_cvx.gtoc9.search.search_campaign` on all 123 debris for ``--time-limit``
seconds and prints: each mission's debris, dates, ΔV, launch mass m0 and cost; the
campaign's status (complete or not), missions, debris removed, ΔV, J, its lower bound in
the planner's model and the gap; the seconds to the best campaign and in all; the peak
memory; and the best open campaigns published (MTS-DP, Tsinghua, JGCD 2024: their ΔV
estimated by Shen & Casalino's method, not flown), beside ours.  Our missions are planned
in the paper's drift-leg model with the eccentricity priced, not flown.

    python benchmarks/gtoc9_kessler.py                   # 900 s of search
    python benchmarks/gtoc9_kessler.py --time-limit 3600 --beam 200

The machine it ran on is printed first: compare times within one run.
"""

from __future__ import annotations

import argparse
import os
import platform
import resource
import time

PUBLISHED = (
    ("MTS-DP, 9 missions (Tsinghua, JGCD 2024)", 9, 22612.0, 645.88),
    ("MTS-DP, 10 missions (Tsinghua, JGCD 2024)", 10, 26039.0, 741.26),
)
"""name, missions, ΔV [m/s] (estimated, not flown), J [MEUR] (c = 55 MEUR a mission)."""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--time-limit", type=float, default=900.0, help="seconds of search")
    parser.add_argument("--beam", type=int, default=150)
    args = parser.parse_args()
    from sdc_cvx.gtoc9.legs import Gtoc9Legs
    from sdc_cvx.gtoc9.rules import DEFAULT_RULES as rules
    from sdc_cvx.gtoc9.search import SearchSettings, search_campaign

    print(f"# {platform.node()}, {os.cpu_count()} cores, load "
          f"{' '.join(f'{x:.1f}' for x in os.getloadavg())}, {time.strftime('%Y-%m-%d %H:%M')}")
    started = time.perf_counter()
    legs = Gtoc9Legs.build()
    print(f"legs priced: {len(legs.origin)} in {time.perf_counter() - started:.1f} s")
    best_at = [0.0]
    last = [None]

    def say(text: str) -> None:
        if "best" in text and last[0] != text.split("best ")[1].split(";")[0]:
            last[0] = text.split("best ")[1].split(";")[0]
            best_at[0] = time.perf_counter() - started
        print(text, flush=True)

    campaign = search_campaign(legs, settings=SearchSettings(beam=args.beam),
                               time_limit_s=args.time_limit, say=say)  # fmt: skip
    seconds = time.perf_counter() - started
    start = legs.start_mjd2000
    print("\nmission | debris | launch - end [MJD2000] | ΔV [m/s] | m0 [kg] | cost [MEUR] | ids")
    for k, m in enumerate(campaign.missions, start=1):
        print(f"{k:7d} | {len(m.debris):6d} | {start + m.launch:8.1f} - {start + m.end:8.1f} | "
              f"{m.dv:8.1f} | {m.m0(rules):7.1f} | {m.cost(rules):11.2f} | "
              f"{' '.join(map(str, m.debris))}")
    status = "complete" if campaign.complete(legs.count) else "incomplete"
    print(f"\n{status}: {len(set(campaign.removed))} of {legs.count} debris, "
          f"{len(campaign.missions)} missions, ΔV {campaign.dv:.1f} m/s, J = "
          f"{campaign.cost(rules):.2f} MEUR; lower bound {campaign.lower_bound:.2f} MEUR "
          f"(planner's model), gap {100 * campaign.gap(rules):.1f} %")
    print(f"best found at {best_at[0]:.0f} s; {seconds:.0f} s in all; peak memory "
          f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e3:.0f} MB")
    print("\npublished (all 123 debris) | missions | ΔV [m/s] | J [MEUR]")
    for name, missions, dv, j in PUBLISHED:
        print(f"{name} | {missions} | {dv:.0f} | {j:.2f}")


if __name__ == "__main__":
    main()

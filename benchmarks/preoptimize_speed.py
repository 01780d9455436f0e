"""Pre-optimisation time (paper Part IV-B) for the paper case and synthetic SSO catalogs.

Usage: python benchmarks/preoptimize_speed.py [--repeat 5]
Prints the best-of-``repeat`` wall time per catalog size and the edges kept.
"""

import argparse
import time

from sdc_cvx import Catalog, Mission, preoptimize
from sdc_cvx.inputs.synthetic import sso_catalog


def best_time(catalog, mission, repeat):
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        table = preoptimize(catalog, mission)
        times.append(time.perf_counter() - start)
    return min(times), table


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    mission = Mission()
    cases = [("paper Table 5", Catalog.paper_case())]
    cases += [(f"synthetic SSO N={n}", sso_catalog(n, seed=1)) for n in (30, 60, 123)]
    print(f"{'catalog':<24}{'N':>5}{'pairs':>8}{'kept':>7}{'seconds':>10}{'us/pair':>9}")
    for name, catalog in cases:
        seconds, table = best_time(catalog, mission, args.repeat)
        pairs = len(table.frame)
        print(
            f"{name:<24}{len(catalog):>5}{pairs:>8}{table.counts()['kept']:>7}"
            f"{seconds:>10.4f}{1e6 * seconds / pairs:>9.1f}"
        )


if __name__ == "__main__":
    main()

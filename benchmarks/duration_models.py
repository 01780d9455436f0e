"""The paper's secant duration (Eq. 17-18) against its two half-segments (Fig. 14).

Usage: python benchmarks/duration_models.py [--sizes 30]

For the paper case and synthetic SSO catalogs, prints iterations, HiGHS nodes,
wall time and final ΔV with each duration model.  The paper expects the
half-segments to need fewer iterations for a larger model (Part IV-G); measure
before changing the default.
"""

import argparse
import time

from sdc_cvx import Catalog, Mission, SequentialSettings, solve
from sdc_cvx.inputs.synthetic import sso_catalog


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="*", default=[30])
    args = parser.parse_args()
    cases = [("paper Table 5", Catalog.paper_case())]
    cases += [(f"synthetic N={n}", sso_catalog(n, seed=1)) for n in args.sizes]
    print(f"{'case':<18}{'model':<14}{'iters':>6}{'nodes':>7}{'seconds':>9}{'dV m/s':>9}  path")
    for name, catalog in cases:
        for model in ("secant", "two_segments"):
            start = time.perf_counter()
            sol = solve(catalog, Mission(), settings=SequentialSettings(duration_model=model))
            seconds = time.perf_counter() - start
            nodes = sum(r.nodes or 0 for r in sol.iterations)
            print(
                f"{name:<18}{model:<14}{len(sol.iterations):>6}{nodes:>7}{seconds:>9.2f}"
                f"{sol.total_dv_mps:>9.2f}  {'->'.join(sol.path)}"
            )


if __name__ == "__main__":
    main()

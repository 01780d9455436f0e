"""The whole public catalogue of May 2020, read and filtered, and its example clusters solved.

Usage: python benchmarks/clusters.py [--repeat 3] [--examples sl16,sl8_83,...] [--out FILE]
                                     [--figure FILE]

Needs ``../shared/data/catalog_2020/all_2020.tle`` (19,084 objects; outside the
repository).  Prints, after a header naming the machine (CPU, cores, load, versions):

1. reading the whole file (``read_catalog(..., on_invalid="set aside")``: every element
   set parsed and checked, those that are not orbits of this model set aside) and
   filtering it with each example's selection, in seconds (the best of ``--repeat``),
   with the counts kept and set aside.  Issue 20's goal: under 3 s;
2. ``find_clusters`` on the rocket bodies (``catalog --type rocket-body --clusters``),
   and the figure (``--figure``, default ``benchmarks/results/clusters.png``);
3. each example scenario of ``examples/cluster_*.toml`` solved as ``run`` does
   (:meth:`Scenario.select_candidates`, then ``sdc_cvx.solve`` with the scenario's
   solver options: the certified search), with its answer, lower bound, gap, status and
   seconds (reading the whole file again, selection and solve; the run folder's figures
   are not drawn).

``benchmarks/results/clusters.txt`` is one such output (a shared 2-core machine).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))  # readme_examples.machine

from readme_examples import machine  # noqa: E402

from sdc_cvx import solve  # noqa: E402
from sdc_cvx.inputs.clusters import clusters_table, find_clusters  # noqa: E402
from sdc_cvx.inputs.formats import read_catalog  # noqa: E402
from sdc_cvx.inputs.selection import select  # noqa: E402
from sdc_cvx.study.scenario import Scenario  # noqa: E402

ROOT = HERE.parent
WHOLE = ROOT.parent / "shared" / "data" / "catalog_2020" / "all_2020.tle"
EXAMPLES = {
    "sl16": ROOT / "examples" / "cluster_sl16_71deg.toml",
    "sl8_83": ROOT / "examples" / "cluster_sl8_83deg.toml",
    "sl8_74": ROOT / "examples" / "cluster_sl8_74deg.toml",
    "sso_rb": ROOT / "examples" / "cluster_sso_rocket_bodies.toml",
}


def best_of(repeat: int, work):
    """``(result, best seconds)`` of ``work()`` run ``repeat`` times."""
    seconds, result = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        result = work()
        seconds.append(time.perf_counter() - start)
    return result, min(seconds)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--examples", default=",".join(EXAMPLES))
    parser.add_argument("--out", type=Path, default=None, help="Also write the output here.")
    parser.add_argument("--figure", type=Path, default=HERE / "results" / "clusters.png")
    options = parser.parse_args()
    if not WHOLE.is_file():
        sys.exit(f"{WHOLE} is missing (the shared data, outside the repository)")
    lines = machine() + [""]

    def say(line: str = "") -> None:
        print(line, flush=True)
        lines.append(line)

    print("\n".join(lines), end="", flush=True)
    catalog, read_s = best_of(options.repeat, lambda: read_catalog(WHOLE, on_invalid="set aside"))
    aside = 0 if catalog.invalid is None else len(catalog.invalid)
    say(f"read     {read_s:6.2f} s  {WHOLE.name}: {len(catalog) + aside} element sets, "
        f"{len(catalog)} orbits, {aside} set aside (not orbits of this model)")  # fmt: skip
    scenarios = {key: Scenario.load(EXAMPLES[key]) for key in options.examples.split(",")}
    for key, scenario in scenarios.items():
        (kept, report), filter_s = best_of(
            options.repeat, lambda s=scenario: s.selection.apply(catalog)
        )
        warned = int((report["checks"] == "invalid").sum())
        say(f"filter   {filter_s:6.2f} s  {key}: kept {len(kept)} ({warned} invalid in the "
            f"selection); read + filter {read_s + filter_s:.2f} s")  # fmt: skip
    (found, rocket_bodies), clusters_s = best_of(
        options.repeat,
        lambda: (find_clusters(kb := select(catalog, types="rocket-body")[0]), kb),
    )
    say(f"clusters {clusters_s:6.2f} s  rocket bodies (select + find_clusters): "
        f"{len(rocket_bodies)} objects, {len(found.table)} groups of 10 or more")  # fmt: skip
    say(clusters_table(found))
    if options.figure is not None:
        from sdc_cvx.report.clusters import plot_clusters

        plot_clusters(rocket_bodies, found).savefig(options.figure, dpi=110)
        shown = options.figure
        if shown.resolve().is_relative_to(ROOT):
            shown = shown.resolve().relative_to(ROOT)
        say(f"figure   {shown}")
    say()
    for key, scenario in scenarios.items():
        start = time.perf_counter()
        kept, _ = scenario.select_candidates()
        solution = solve(kept, scenario.mission, solver=scenario.solver)
        seconds = time.perf_counter() - start
        gap = solution.gap_rel * 100 if solution.gap_rel is not None else float("nan")
        say(f"{key:<7} {seconds:6.1f} s  N = {len(kept)}, n = {scenario.mission.n}, T_max "
            f"{scenario.mission.tmax_days:g} d: {solution.total_dv_mps:.2f} m/s, bound "
            f"{solution.lower_bound_mps:.2f}, gap {solution.gap_mps:.2f} m/s ({gap:.2f} %), "
            f"{solution.status}; path {' -> '.join(solution.path)}")  # fmt: skip
    if options.out is not None:
        options.out.write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()

"""The figure of ``catalog --clusters``: where the targets of a catalogue are.

Left, altitude against inclination (every object of the selection in grey, each group of
:func:`sdc_cvx.inputs.clusters.find_clusters` in colour with its number); right, RAAN at
the start date against J2 RAAN rate (Eq. 7), the plane in which the drift strategy works:
members of a group with distinct rates can close their RAAN gaps.
"""

from __future__ import annotations

from matplotlib import colormaps
from matplotlib.figure import Figure

from ..inputs.catalog import Catalog
from ..inputs.clusters import Clusters

__all__ = ["plot_clusters"]


def plot_clusters(catalog: Catalog, clusters: Clusters, *, most: int = 10) -> Figure:
    """Altitude against inclination, and RAAN against J2 rate, the groups in colour.

    Parameters
    ----------
    catalog : Catalog
        The objects :func:`~sdc_cvx.inputs.clusters.find_clusters` was given.
    clusters : Clusters
        Its answer.
    most : int
        Groups drawn in colour (the largest; the others in grey).

    Returns
    -------
    matplotlib.figure.Figure
    """
    frame = catalog.frame
    figure = Figure(figsize=(12.0, 5.0), layout="constrained")
    left, right = figure.subplots(1, 2)
    altitude = frame["altitude_km"].to_numpy(dtype=float)
    inc = frame["inc_deg"].to_numpy(dtype=float)
    rate = frame["raan_rate_deg_per_day"].to_numpy(dtype=float)
    raan = frame["raan_deg"].to_numpy(dtype=float)
    other = clusters.labels == 0
    left.scatter(inc[other], altitude[other], s=2, color="0.75", label="in no group")
    right.scatter(rate[other], raan[other], s=2, color="0.75")
    colours = colormaps["tab10"]
    for row in clusters.table.itertuples():
        members = clusters.labels == row.cluster
        colour = colours((row.cluster - 1) % 10) if row.cluster <= most else "0.5"
        label = f"{row.cluster}: {row.objects} objects" if row.cluster <= most else None
        left.scatter(inc[members], altitude[members], s=6, color=colour, label=label)
        right.scatter(rate[members], raan[members], s=6, color=colour)
        if row.cluster <= most:
            left.annotate(str(row.cluster), (inc[members].mean(), altitude[members].max()),
                          ha="center", va="bottom", fontsize=8)  # fmt: skip
    left.set_xlabel("inclination [deg]")
    left.set_ylabel("altitude a - R_T [km]")
    left.set_title(f"{len(frame)} objects, {len(clusters.table)} groups")
    left.legend(fontsize=7, markerscale=2, loc="best")
    right.set_xlabel("J2 RAAN rate [deg/day]")
    right.set_ylabel("RAAN at the start date [deg]")
    start = "" if catalog.start is None else f" at {catalog.start:%Y-%m-%d %H:%M} UTC"
    right.set_title(f"RAAN{start} against J2 rate")
    right.set_ylim(0.0, 360.0)
    return figure

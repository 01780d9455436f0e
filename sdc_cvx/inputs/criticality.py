"""The Criticality of Spacecraft Index (CSI): a debris' value as the risk its breakup poses.

Rossi, Valsecchi and Alessi [1]_ rank abandoned objects in low Earth orbit by

    CSI = (M / M0) (D(h) / D0) (L(h) / L0) (1 + k Γ(i)) / (1 + k),

with ``M`` the object's mass, ``D(h)`` the spatial density of objects where it flies,
``L(h)`` its orbital lifetime and ``Γ(i) = (1 - cos i) / 2`` (an inclined orbit meets
more of the population), ``k = 0.6``; ``M0 = 10 000 kg`` and ``D0 = 6.8e-8`` objects per
km³ normalise it.  The lifetime factor is the fit of Bombardelli et al. [2]_,
``ln L = a h^b + c`` (h in km) over its value at ``h_ref = 1031.5 km``, capped at 1
(above it an object stays up for centuries either way).  An eccentric orbit spends a
fraction of its period in each altitude shell (from Kepler's equation), and its density
factor is the sum of those fractions times each shell's density (the "fractional CSI"
of [2]_, summed).  The constants are those of Gisolfi's implementation [3]_.

Every input comes from the catalogue itself, except the masses, which a user gives
(``[catalog] values = "csi"`` with ``masses = "FILE.csv"``): ``D(h)`` is the density of
the objects of the catalogue read (each spread over the shells its orbit crosses, as
above), so it is the density of *catalogued* objects, about 10 cm and larger.

References
----------
.. [1] A. Rossi, G. B. Valsecchi and E. M. Alessi, "The Criticality of Spacecraft Index",
   Advances in Space Research 56(3), 449–460, 2015.
.. [2] C. Bombardelli et al., Advances in Space Research, 2017 (ScienceDirect PII
   S0273117717302491): the fractional CSI and the lifetime fit.
.. [3] L. Gisolfi, the Fragmentation Environmental Index code (2023), after his master's
   thesis, University of Padua: ``fractional_csi``, ``life``.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ..physics.orbits import R_EARTH

M0_KG = 10_000.0
"""Reference mass [kg]."""
D0_PER_KM3 = 6.8e-8
"""Reference spatial density [objects / km³]."""
LIFE_FIT = (6.5215, 0.2583, -33.8481)
"""``(a, b, c)`` of ``ln L = a h^b + c``, h the altitude [km] ([2]_)."""
LIFE_REF_KM = 1031.5
"""Altitude [km] whose lifetime normalises the lifetime factor (which is capped at 1)."""
K_INCLINATION = 0.6
"""Weight of the inclination factor ``Γ(i)``."""
SHELL_KM = 25.0
"""Width [km] of the altitude shells of the catalogue's spatial density."""
SHELLS_KM = (100.0, 3000.0)
"""Altitudes [km] the shells cover (an object's time outside them counts for nothing)."""


def lifetime_factor(altitude_km):
    """``L(h) / L0`` [-]: the lifetime fit at ``altitude_km`` over its value at
    :data:`LIFE_REF_KM`, at most 1."""
    a, b, _ = LIFE_FIT  # c cancels in the ratio
    h = np.maximum(np.asarray(altitude_km, dtype=float), 0.0)
    return np.minimum(np.exp(a * (h**b - LIFE_REF_KM**b)), 1.0)


def inclination_factor(inc_deg):
    """``(1 + k Γ(i)) / (1 + k)`` [-] with ``Γ(i) = (1 - cos i) / 2``: 1 for a polar or
    retrograde orbit, ``1 / (1 + k)`` for an equatorial one."""
    gamma = 0.5 * (1.0 - np.cos(np.radians(np.asarray(inc_deg, dtype=float))))
    return (1.0 + K_INCLINATION * gamma) / (1.0 + K_INCLINATION)


def time_below(a_km, e, radius_km):
    """Fraction [-] of an orbit's period spent below ``radius_km`` (radii from the Earth's
    centre): ``(E - e sin E) / pi`` with ``cos E = (a - R) / (a e)`` between perigee and
    apogee (Kepler's equation), 0 below perigee, 1 above apogee; a circular orbit is a
    step at its radius."""
    a, e = np.asarray(a_km, dtype=float), np.maximum(np.asarray(e, dtype=float), 1e-12)
    with np.errstate(divide="ignore", invalid="ignore"):
        cos_e = np.clip((a - np.asarray(radius_km, dtype=float)) / (a * e), -1.0, 1.0)
    anomaly = np.arccos(cos_e)
    return (anomaly - e * np.sin(anomaly)) / np.pi


def shell_fractions(a_km, e, edges_km):
    """Fraction [-] of each orbit's period in each altitude shell, shape (objects, shells):
    the shells between consecutive ``edges_km`` (altitudes)."""
    radii = R_EARTH / 1e3 + np.asarray(edges_km, dtype=float)
    below = time_below(np.asarray(a_km, float)[:, None], np.asarray(e, float)[:, None],
                       radii[None, :])  # fmt: skip
    return np.diff(below, axis=1)


def spatial_density(a_km, e, edges_km):
    """Objects per km³ in each altitude shell: every orbit spread over the shells by the
    time it spends in each (:func:`shell_fractions`), over the shell's volume."""
    radii = R_EARTH / 1e3 + np.asarray(edges_km, dtype=float)
    volumes = 4.0 / 3.0 * np.pi * np.diff(radii**3)
    return shell_fractions(a_km, e, edges_km).sum(axis=0) / volumes


def criticality_index(mass_kg, a_km, e, inc_deg, edges_km, density_per_km3):
    """The CSI [-] of objects (module docstring), given the spatial density of each shell.

    Parameters
    ----------
    mass_kg, a_km, e, inc_deg : array_like
        The objects' masses, semi-major axes, eccentricities and inclinations.
    edges_km : array_like
        Shell edges [km of altitude].
    density_per_km3 : array_like
        Objects per km³ in each shell (:func:`spatial_density`).
    """
    a_km = np.asarray(a_km, dtype=float)
    density = shell_fractions(a_km, e, edges_km) @ np.asarray(density_per_km3, dtype=float)
    return (np.asarray(mass_kg, dtype=float) / M0_KG * density / D0_PER_KM3
            * lifetime_factor(a_km - R_EARTH / 1e3) * inclination_factor(inc_deg))  # fmt: skip


def csi_values(catalog, masses: Mapping[str, float], density_from=None) -> dict[str, float]:
    """``{id: CSI}`` of every object of ``catalog`` that ``masses`` names [kg], the spatial
    density from ``density_from`` (a :class:`~sdc_cvx.inputs.catalog.Catalog`, default
    ``catalog``: the whole catalogue read, not only the candidates)."""
    source = catalog if density_from is None else density_from
    edges = np.arange(SHELLS_KM[0], SHELLS_KM[1] + SHELL_KM, SHELL_KM)
    density = spatial_density(source.frame["a_km"], source.frame["e"], edges)
    frame = catalog.frame[catalog.frame["id"].astype(str).isin(set(map(str, masses)))]
    mass = [float(masses[str(k)]) for k in frame["id"].astype(str)]
    index = criticality_index(mass, frame["a_km"], frame["e"], frame["inc_deg"], edges, density)
    return dict(zip(frame["id"].astype(str), map(float, index), strict=True))


def missing_masses(ids, masses: Mapping[str, float]) -> list[str]:
    """The ids ``masses`` does not name (their CSI cannot be computed)."""
    return [str(k) for k in ids if str(k) not in masses]

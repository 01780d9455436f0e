"""Transfer models by name: the leg physics the planners use, chosen once.

:func:`transfer_model` gives the model a mission names (``Mission.transfer``):
``"impulsive"`` (:class:`~sdc_cvx.physics.leg_bounds.ImpulsiveModel`, the paper's
Hohmann-drift-Hohmann legs) or ``"low-thrust"``
(:class:`~sdc_cvx.physics.low_thrust.LowThrustModel`).  What every model provides, the
one signature the rooms of the package use (the pvlib ``ModelChain`` shape [2]_), is
:class:`~sdc_cvx.physics.model_protocol.TransferModel` (re-exported here).

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
.. [2] W. F. Holmgren, C. W. Hansen and M. A. Mikofski, "pvlib python: a python package
   for modeling solar energy systems", Journal of Open Source Software 3(29), 884, 2018
   (the ModelChain pattern).
"""

from __future__ import annotations

from .leg_bounds import IMPULSIVE, ImpulsiveModel
from .low_thrust import LowThrustModel
from .model_protocol import TransferModel

TRANSFER_MODELS = ("impulsive", "low-thrust")
"""Names of the transfer models (``Mission.transfer``)."""


def transfer_model(name: str = "impulsive", *, accel_mps2: float | None = None) -> TransferModel:
    """The transfer model called ``name``.

    Parameters
    ----------
    name : {"impulsive", "low-thrust"}
    accel_mps2 : float, optional
        Thrust acceleration [m/s^2]; required by ``"low-thrust"``.

    Raises
    ------
    ValueError
        Unknown name, or a low-thrust model without an acceleration.
    """
    if name == "impulsive":
        return IMPULSIVE
    if name == "low-thrust":
        if accel_mps2 is None:
            raise ValueError("the low-thrust transfer model needs the vehicle's acceleration "
                             "(accel_mps2, or thrust_n with its masses)")  # fmt: skip
        return LowThrustModel(float(accel_mps2))
    raise ValueError(f"transfer must be one of {TRANSFER_MODELS}, got {name!r}")


__all__ = ["TRANSFER_MODELS", "ImpulsiveModel", "LowThrustModel", "TransferModel",
           "transfer_model"]  # fmt: skip

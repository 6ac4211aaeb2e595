"""FMI 2.0 co-simulation units (FMUs) of seahelm ships (optional extra ``seahelm[fmu]``).

:func:`~seahelm.fmu.build.build_fmu` (``seahelm fmu SHIP -o ship.fmu``) writes an FMU whose
slave (:class:`~seahelm.fmu.slave.ShipSlave`, through pythonfmu) steps a
:class:`~seahelm.Simulator` of the ship with the master's commands: inputs the actuator's
commands, outputs position, heading, speeds and yaw rate, with units and start values; a few
parameters (initial position and heading, integration step, wind). Run it with fmpy, OSP's
libcosim or any FMI 2.0 master whose Python has seahelm installed.
"""

from __future__ import annotations

from .build import build_fmu, model_identifier

__all__ = ["build_fmu", "model_identifier"]

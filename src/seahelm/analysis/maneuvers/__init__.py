"""Standard manoeuvres and their metrics, over batches of runs.

Manoeuvres (each one batch through the compiled engine, returning a
:class:`~seahelm.analysis.maneuvers.result.ManeuverResult` with the runs and a metrics table
as :mod:`xarray` Datasets; see :mod:`seahelm.analysis.maneuvers.common`):

:func:`turning_circle`
    turning circles and the initial turning test (:mod:`.turning_circle`);
:func:`zigzag`
    zig-zag tests, any δ/ψ pair, either first side (:mod:`.zigzag`; metrics of a recorded
    heading: :func:`zigzag_metrics`);
:func:`direct_spiral`, :func:`reverse_spiral`
    Dieudonné's simulated spiral and Bech's reverse spiral from the equilibria, the r–δ curve
    and its hysteresis loop (:mod:`.spiral`); :func:`spirals` runs both up to one rudder
    angle;
:func:`pull_out`
    rudder to zero after steady turns to both sides (:mod:`.pullout`);
:func:`crash_stop`
    the stopping test, full astern with the rudder amidships (:mod:`.stopping`; an ``mmg`` ship
    is given its engine by :func:`stopping_ship`; metrics of records: :func:`stopping_metrics`).

The IMO MSC.137(76) check on top of these is :mod:`seahelm.analysis.imo`.

Metrics of recorded runs that the scenario runner uses (:mod:`.metrics`): :func:`settling_time`,
:func:`overshoot`, :func:`turning_diameter`, :func:`rudder_reversals`,
:func:`path_following_metrics`, :func:`summarize` (and the metrics' units:
:func:`summary_units`). Of any recorded track (a simulated or a measured one):
:func:`turning_metrics`, the advance, transfer and tactical diameter of a turn
(:mod:`.advance_transfer`), and :func:`heading_metrics`, a heading autopilot's course keeping
(:mod:`.course_keeping`).
"""

from __future__ import annotations

from ...errors import deprecated_names
from .advance_transfer import TurningMetrics, heading_change_crossing, turning_metrics
from .common import (
    default_time_step,
    maneuver_ship,
)
from .course_keeping import heading_metrics
from .metrics import (
    overshoot,
    path_following_metrics,
    rudder_reversals,
    settling_time,
    summarize,
    summary_units,
    turning_diameter,
)
from .pullout import pull_out
from .result import ManeuverResult, metrics_rows
from .stopping import crash_stop, stopping_metrics, stopping_ship
from .spiral import DEFAULT_SPIRAL_RUDDERS_DEG, direct_spiral, reverse_spiral, spiral_loop, spirals
from .turning_circle import track_distance, turning_circle
from .zigzag import ZigZagMetrics, zigzag, zigzag_metrics

__all__ = [
    "ManeuverResult",
    "default_time_step",
    "maneuver_ship",
    "metrics_rows",
    "turning_circle",
    "track_distance",
    "zigzag",
    "zigzag_metrics",
    "ZigZagMetrics",
    "direct_spiral",
    "reverse_spiral",
    "spiral_loop",
    "spirals",
    "DEFAULT_SPIRAL_RUDDERS_DEG",
    "pull_out",
    "crash_stop",
    "stopping_ship",
    "stopping_metrics",
    "settling_time",
    "overshoot",
    "turning_diameter",
    "rudder_reversals",
    "summarize",
    "summary_units",
    "path_following_metrics",
    "turning_metrics",
    "TurningMetrics",
    "heading_change_crossing",
    "heading_metrics",
]

#: ``ManeuverShip``, the old name of :class:`~seahelm.ships.Ship`: deprecated (a warning on
#: access).
__getattr__ = deprecated_names(__name__, {"ManeuverShip": ("seahelm.ships", "Ship",
                                                          "seahelm.Ship")})

"""seahelm.analysis.equilibria: equilibria of ship models, solved one way.

:mod:`.equilibrium`
    the one-run functions (approach, self-propulsion rps, steady turn, spiral point,
    straight-run speed), each a batch of one of the batched solvers;
:mod:`.batch_equilibrium`, :mod:`.batch_steady_turn`
    the batched Newton solvers (per-run status and message);
:mod:`.fallback`
    scipy's one-run solves, the fallback inside them;
:mod:`.plant`
    the one :class:`~seahelm.analysis.equilibria.plant.Plant` that resolves the signals (one run: a batch of one);
:mod:`.approach`, :mod:`.approach_cache`
    the one :class:`~.approach.Approach` type and the cache of solved approaches;
:mod:`.constant_speed`, :mod:`.heel`
    constant-speed steering models' equilibria, the steady heel of a model with roll;
:mod:`.linearisation`
    the linear model (A, B, C, D) at an equilibrium.

Before issue 47 these were modules of :mod:`seahelm.analysis`; the old paths
(``seahelm.analysis.equilibrium`` ...) still import, with a DeprecationWarning.
"""

"""seahelm.analysis.equilibria: equilibria of ship models, solved one way.

:mod:`.plant` resolves the signals the solvers need (one :class:`~.plant.Plant` for one run
or a batch; one run is a batch of one).
"""

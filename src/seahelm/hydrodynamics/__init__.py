"""seahelm.hydrodynamics: a ship's manoeuvring coefficients from its main particulars.

Published empirical estimates, each a function of the particulars with its source, equation
and validity range (outside it: :class:`~seahelm.errors.ValidityRangeWarning`, an error under
:class:`~seahelm.errors.strict_validity`). The formulas know nothing of ships files or
simulation; :mod:`seahelm.ships.estimate` assembles them into a :class:`~seahelm.ships.Ship`.
"""

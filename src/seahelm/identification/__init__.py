"""seahelm.identification: the reduced steady-turn model of Romanov & Chirkova.

:mod:`~seahelm.identification.steady_turns` (steady turns of Voitkunsky's model, reduced
coefficients in closed form), :mod:`~seahelm.identification.reduced_forms` (forms of the
reduced equation, the fit result), :mod:`~seahelm.identification.fitting` (least squares,
robust, the paper's brute force) and :mod:`~seahelm.identification.segments` (steady turns
from a log).
"""

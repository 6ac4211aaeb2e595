"""seahelm.identification.reduced: the reduced steady-turn model of Romanov & Chirkova.

:mod:`~seahelm.identification.reduced.turns` (steady turns of Voitkunsky's model, reduced
coefficients in closed form), :mod:`~seahelm.identification.reduced.forms` (forms of the
reduced equation, the fit result), :mod:`~seahelm.identification.reduced.fitting` (least
squares, robust, the paper's brute force), :mod:`~seahelm.identification.reduced.criteria`
(the paper's criteria) and :mod:`~seahelm.identification.reduced.segments` (steady turns from
a log; the log itself is read by :func:`seahelm.identification.records.read_turn_log`).
"""

"""Platonov & Platonova: full averaging of the motion of a CPP ship in regular waves.

The ship is a component (:mod:`seahelm.vessels.cpp_ship`, eq. (5)-(12)). The paper's averaging
theory for control-affine periodic systems, eq. (1)-(4), and its application to the ship are
here:

* :mod:`seahelm.studies.platonov.averaging` — full averaging and the averaged control set of a
  control-affine periodic system (nothing in it depends on the ship);

* :mod:`seahelm.studies.platonov.control_set` — the admissible control set V (eq. (14)-(16)),
  with the printed eq. (15) as a registry object next to the clipped maximiser;
* :mod:`seahelm.studies.platonov.flat_set` — the flat approximation Y (eq. (24), printed and
  corrected) and its Hausdorff distance to V;
* :mod:`seahelm.studies.platonov.averaged_system` — the averaged system eq. (13) (printed and
  corrected ς2/ς3 assignment) and the check of the averaging theorem by simulation;
* :mod:`seahelm.studies.platonov.figures` — Figs. 1 and 2 (V, and Y in either reading) and the
  averaging error against ε.
"""

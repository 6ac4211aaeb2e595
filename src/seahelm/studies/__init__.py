"""Paper reproductions on top of the reusable components, one module per paper.

A study holds what only its paper needs: the paper's ship data, its printed variants (as
objects next to the corrected ones, in a small registry), summary tables, scenario builders
and metrics tables. The components it builds on (vessels, actuators, control, environment,
identification, analysis, simulation) know nothing about it; only the studies and the CLI
import ``seahelm.studies`` (``tests/test_import_graph.py``).

* :mod:`seahelm.studies.lvov2014` — wind and wave compensation of a course autopilot;
* :mod:`seahelm.studies.platonov` — full averaging of a CPP ship in waves (Platonov & Platonova);
* :mod:`seahelm.studies.romanov_chirkova` — steering-model identification from three steady
  turns: the printed eq. (5) criterion next to proper ones, the paper's procedure on a model
  ship (Romanov & Chirkova);
* :mod:`seahelm.studies.shushlyapin2017` — the catamaran's strong manoeuvres: the ship as
  printed (sway eq. (3), resistance eq. (6)-(7)) next to the listing, the published results
  (Shushlyapin et al.);
* :mod:`seahelm.studies.sushchenko2010` — sea-wave disturbances: Table 2, the third spectrum
  and the shaping filters as printed, the paper's figure (Sushchenko & Lutsko).
"""

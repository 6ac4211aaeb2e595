"""Marine craft in six degrees of freedom (Fossen 2021, *Handbook of Marine Craft Hydrodynamics
and Motion Control*, 2nd ed., ch. 2, 3, 6, 7).

One rigid-body model for every 6-DOF craft, written once:

* :mod:`.rigid_body` — the compiled kernels: rotation matrices and the Euler-angle (zyx) and
  unit-quaternion kinematics, the Coriolis–centripetal vector C(ν)ν from a mass matrix, the
  restoring forces g(η), cross-flow drag, the 6 × 6 solve;
* :mod:`.params` — :class:`SixDofParams`: mass properties, added mass, damping, restoring,
  thrusters and fins, validated (a mass matrix that is not symmetric positive definite, a
  thruster outside the hull or with zero thrust coefficient are refused);
* :mod:`.model` — the right-hand side M ν̇_r + C(ν_r)ν_r + D(ν_r)ν_r + g(η) = τ + τ_env
  (states relative to the water, the position moves with the current), the outputs, and
  :func:`six_dof_model`, which registers a craft's thruster and fin layout as a
  :class:`~seahelm.vessels.base.VesselModel`;
* :mod:`.thrusters` — thrust k n|n|, allocation by weighted pseudo-inverse with saturation;
* :mod:`.otter` — the Otter USV (Fossen's published model) and its ship file's numbers.

A new craft is data (a ship file with :class:`SixDofParams`) and, if its thrusters and fins
differ from an existing craft's, one :func:`six_dof_model` line naming them.
"""

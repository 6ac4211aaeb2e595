"""Generic numerics under the components: no ship, no paper (quadrature over a period, sampling,
explicit Runge–Kutta tableaus and their batched step, one-sided Jacobians at a kink, …)."""

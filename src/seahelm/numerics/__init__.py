"""Generic numerics under the components: no ship, no paper (quadrature over a period, …)."""

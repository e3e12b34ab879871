"""The numerics every part of the physics uses: dot products, lengths and sums in a
fixed order, and the roots of low-degree polynomials (IEEE-fixed operations only)."""

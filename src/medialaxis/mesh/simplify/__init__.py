"""Simplified medial meshes: Q-MAT's quadric error on spheres and the coverage simplification, measured by the
exact two-sided envelope distance."""

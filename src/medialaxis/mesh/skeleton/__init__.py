"""Curve skeletons by the diffusion flow (the contracting mesh, its graph, centring), their re-pruning by branch and
skeleton-driven deformation."""

"""3D surface meshes: Voronoi medial surfaces and curve skeletons by diffusion flow."""

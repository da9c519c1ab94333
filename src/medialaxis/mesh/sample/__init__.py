"""The surface sample (spacing from the local feature size, thin parts sampled finer) and its Delaunay
tetrahedralisation, with the exact closest-point queries on the input surface."""

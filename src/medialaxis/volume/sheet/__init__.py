"""The mid-surface mesh from the medial voxels: polygonization, dents at junctions, extension to the plate ends."""

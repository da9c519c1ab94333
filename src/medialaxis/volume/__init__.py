"""3D volumes (CT scans): medial voxels and mid-surfaces of thin-plate parts."""

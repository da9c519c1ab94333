"""Views and files for other programs: plots, 3D pages, mesh files, shapely/trimesh/networkx/pyvista/napari objects,
pixel skeletons."""

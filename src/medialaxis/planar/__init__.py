"""2D medial axes of images and polygons (Voronoi of boundary samples, lambda pruning)."""

from medialaxis.planar.pipeline import Stages, planar_stages, reprune, voronoi_medial_axis

__all__ = ["voronoi_medial_axis", "planar_stages", "reprune", "Stages"]

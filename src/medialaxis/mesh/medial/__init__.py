"""The medial complex: the Voronoi facets inside the solid, selected by lambda with the solid's topology kept,
compacted, and re-pruned without recomputing."""

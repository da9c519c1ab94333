"""Planar inputs to regions: images (grey, colour, label), vector geometries and their files."""

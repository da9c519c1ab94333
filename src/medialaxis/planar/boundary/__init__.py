"""The boundary sample: simplified rings, corners, Canny edges, adaptive sampling and its refinement."""

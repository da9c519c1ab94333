"""The input surface made the surface of a solid: loading and repair, degenerate faces, crossings cut by the
generalized winding number, holes capped."""

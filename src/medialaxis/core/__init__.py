"""Shared core: the result type, graph utilities, I/O, metrics."""

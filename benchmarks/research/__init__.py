"""Shape-distance terms measured and moved out of the package (issue 17); used by ``bench_compare.py``.

- :mod:`research.path_similarity`: Bai and Latecki's skeleton paths and the
  "previous default" distance (paths + 0.6 axis context);
- :mod:`research.path_kernels`: their compiled pairwise step and references;
- :mod:`research.axis_context`: the unordered axis context;
- :mod:`research.dce`: Discrete Curve Evolution pruning.

The figures that retired them are in :mod:`research.path_similarity`.
"""

"""Point location of the incremental Delaunay tetrahedralisation (:mod:`medialaxis.mesh.sample.delaunay`).

A stochastic visibility walk, a scan of every tetrahedron when it fails, and
a software prefetch (LLVM's ``llvm.prefetch``) that the walk and the cavity
search of :mod:`medialaxis.mesh.sample._delaunay_kernels` use to fetch the
rows they are about to read while they compute on the current one. A
prefetch is a hint to the processor: it changes no result, only when the
memory arrives (the walk and the cavity search of the uv ellipsoid's 221k
samples: 21% and 49% of the insertion, most of it waiting for rows).
"""

from __future__ import annotations

from llvmlite import ir
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

from medialaxis._jit import njit
from medialaxis.mesh.sample._predicates import _inf_pos, _orient_sub

#: Steps of the walk before a scan of all tetrahedra.
MAX_WALK = 1 << 16


@intrinsic
def prefetch(typingctx, arr, i):  # type: ignore[no-untyped-def]
    """Ask the processor to bring row ``i`` of ``arr`` into its caches (for reading); returns nothing.

    >>> import numpy as np
    >>> @njit
    ... def first(a):
    ...     prefetch(a, 1)
    ...     return a[0, 0]
    >>> int(first(np.arange(8).reshape(2, 4)))
    0
    """
    if not isinstance(arr, types.Array) or not isinstance(i, types.Integer):
        return None
    sig = types.none(arr, i)

    def codegen(context, builder, signature, args):  # type: ignore[no-untyped-def]
        ary = context.make_array(signature.args[0])(context, builder, args[0])
        idx = context.cast(builder, args[1], signature.args[1], types.intp)
        offset = builder.mul(idx, builder.extract_value(ary.strides, 0))
        ptr = builder.gep(builder.bitcast(ary.data, ir.IntType(8).as_pointer()), [offset])
        i32 = ir.IntType(32)
        fnty = ir.FunctionType(ir.VoidType(), [ptr.type, i32, i32, i32])
        fn = cgutils.get_or_insert_function(builder.module, fnty, "llvm.prefetch.p0")
        builder.call(fn, [ptr, i32(0), i32(3), i32(1)])  # read, keep in every cache level, data
        return context.get_dummy_value()

    return sig, codegen


# ----------------------------------------------------------------------------
# point location
# ----------------------------------------------------------------------------


@njit(cache=True, nogil=True)
def _walk(P, tet, t, p, inf, rng):  # type: ignore[no-untyped-def]
    """Stochastic visibility walk from the finite tetrahedron ``t`` towards ``p``.

    Returns a finite tetrahedron with ``p`` not strictly beyond any of its
    faces, an infinite one (entered across its hull face, which ``p`` is
    then strictly beyond), or -1 after ``MAX_WALK`` steps.
    """
    prev = -1
    for _ in range(MAX_WALK):
        for k in range(4):  # the next tetrahedron is one of these: fetch them while testing the faces
            prefetch(tet, tet[t, 4 + k] >> 2)
        rng[0] = rng[0] * 6364136223846793005 + 1442695040888963407
        r = (rng[0] >> 33) & 3
        moved = False
        for kk in range(4):
            k = (kk + r) & 3
            u = tet[t, 4 + k] >> 2
            if u == prev:
                continue
            if _orient_sub(P, tet, t, k, p) < 0:
                prev = t
                t = u
                moved = True
                break
        if not moved:
            return t
        if _inf_pos(tet, t, inf) >= 0:
            return t
    return -1


@njit(cache=True, nogil=True)
def _scan(P, tet, nt, p, inf):  # type: ignore[no-untyped-def]
    """Point location by a scan of every tetrahedron (when the walk fails); -1 if none holds ``p``."""
    for t in range(nt):
        if tet[t, 0] < 0 or _inf_pos(tet, t, inf) >= 0:
            continue
        inside = True
        for k in range(4):
            if _orient_sub(P, tet, t, k, p) < 0:
                inside = False
                break
        if inside:
            return t
    for t in range(nt):
        if tet[t, 0] < 0:
            continue
        ip = _inf_pos(tet, t, inf)
        if ip >= 0 and _orient_sub(P, tet, t, ip, p) > 0:
            return t
    return -1

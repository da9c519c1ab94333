"""Betti numbers of the open interior of a solid bounded by a closed, outward-oriented triangle surface.

The medial axis of a bounded open set has the homotopy type of the set
(Lieutier 2004, "Any open bounded subset of R^n has the same homotopy type
as its medial axis"), so the medial surface's Betti numbers are the
*interior's*. Where the solid touches itself at a point or along an edge,
the interior and the closed solid differ: two cubes sharing a vertex are one
closed solid but two open ones; a cube with two cavities that touch at a
point holds two cavities but its interior one (their closures meet); a solid
whose through-hole narrows to a point is a ball but its interior a torus.

The count, independent of the routes it checks: the interior deformation
retracts onto the solid shrunk by a small distance, whose boundary is the
input surface with each touch resolved as the shrinking resolves it.

* An edge shared by 2k faces: sorted around the edge, consecutive faces
  bound solid and empty wedges in turn; the two faces of each solid wedge
  are joined (the wedges separate).
* A vertex whose faces form several fans (the link in a small sphere around
  it is several disjoint circles): the sphere minus the circles is cut into
  regions, solid and empty in turn. The shrunk interior holds each solid
  region R near the vertex, so the fans bounding the same R are joined
  through a copy of R (a sphere with m holes): a solid pinch (regions of
  one circle each) splits the fans, an empty one (the complement touching
  itself: an annulus of solid) joins two by a tube. Whether a point of the
  sphere lies on a circle's solid side is decided by the sign of the solid
  angle that the cone over the circle subtends from near the vertex.

The resolved surface is a disjoint union of closed oriented surfaces; each
bounds its solid on the inside (positive signed volume: an outer boundary)
or a cavity (negative). Every component of a bounded solid has exactly one
outer boundary, and in R^3 the first Betti number of a compact 3-manifold is
the total genus of its boundary (Alexander duality), so
``(b0, b1, b2) = (outer boundaries, total genus, cavity boundaries)``.
"""

from __future__ import annotations

import numpy as np


class _Union:
    def __init__(self, n: int) -> None:
        self.parent = np.arange(n)

    def find(self, i: int) -> int:
        root = i
        while self.parent[root] != root:
            root = self.parent[root]
        while self.parent[i] != root:
            self.parent[i], i = root, self.parent[i]
        return int(root)

    def join(self, i: int, j: int) -> None:
        self.parent[self.find(i)] = self.find(j)


def _pair_around_edges(v: np.ndarray, f: np.ndarray) -> list[tuple[int, int, int, int]]:
    """``(face, face, a, b)``: the faces joined across each edge ``(a, b)`` (those of one solid wedge)."""
    e = np.vstack([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    face = np.tile(np.arange(len(f)), 3)
    third = np.concatenate([f[:, 2], f[:, 0], f[:, 1]])
    key = np.sort(e, axis=1)
    order = np.lexsort((key[:, 1], key[:, 0]))
    key, face, third, e = key[order], face[order], third[order], e[order]
    starts = np.flatnonzero(np.r_[True, np.any(key[1:] != key[:-1], axis=1), True])
    normal = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    pairs = []
    for s, t in zip(starts[:-1], starts[1:]):
        a, b = key[s]
        if t - s == 2:
            pairs.append((int(face[s]), int(face[s + 1]), int(a), int(b)))
            continue
        if (t - s) % 2:
            raise ValueError(f"edge {a}-{b} has {t - s} faces: the surface is not closed")
        axis = (v[b] - v[a]) / np.linalg.norm(v[b] - v[a])
        ref = v[third[s]] - v[a]
        ref = ref - ref.dot(axis) * axis
        ref /= np.linalg.norm(ref)
        side = np.cross(axis, ref)
        arm = v[third[s:t]] - v[a]
        ang = np.arctan2(arm @ side, arm @ ref) % (2 * np.pi)
        k = np.argsort(ang)
        fs, ang = face[s:t][k], ang[k]
        mid = (ang + np.diff(np.r_[ang, ang[0] + 2 * np.pi]) / 2)[0]  # the wedge after the first face
        w = np.cos(mid) * ref + np.sin(mid) * side
        shift = 0 if normal[fs[0]].dot(w) < 0 else 1  # solid behind the first face: it and the next bound a wedge
        fs = np.roll(fs, -shift)
        pairs.extend((int(fs[i]), int(fs[i + 1]), int(a), int(b)) for i in range(0, len(fs), 2))
    return pairs


def _on_solid_side(x: np.ndarray, ua: np.ndarray, ub: np.ndarray, eps: float = 1e-6) -> bool:
    """Whether direction ``x`` lies on the solid side of the link circle of arcs ``ua[i] -> ub[i]`` (unit vectors).

    The unit cone over the circle (apex at the origin, faces oriented away
    from the solid side R), closed by the part of the unit sphere over R,
    bounds the cone over R outward; seen from ``eps * x`` the lid subtends
    the area A(R) up to O(eps), so the cone subtends 4 pi - A(R) > 0 from
    the solid side and -A(R) < 0 from the other.
    """
    a, b, c = ua - eps * x, ub - eps * x, np.broadcast_to(-eps * x, ua.shape)
    la, lb, lc = (np.linalg.norm(w, axis=1) for w in (a, b, c))
    num = np.einsum("ij,ij->i", a, np.cross(b, c))
    den = la * lb * lc + np.einsum("ij,ij->i", a, b) * lc + np.einsum("ij,ij->i", b, c) * la
    den += np.einsum("ij,ij->i", c, a) * lb
    return bool(np.arctan2(num, den).sum() > 0)


def _solid_regions(p: int, fans: list[np.ndarray], v: np.ndarray, f: np.ndarray) -> list[list[int]]:
    """The fans at vertex ``p`` grouped by the solid region of the small sphere around ``p`` they bound.

    Disjoint circles on a sphere cut it into regions told apart by the side
    of each circle they lie on; a point just off each circle on its solid
    side (off its widest arc) stands for the solid region that circle bounds.
    """
    arcs, probes = [], []
    for faces in fans:
        tri = f[faces]
        k = np.argmax(tri == p, axis=1)  # rotate each face so that p comes first: arcs a -> b keep the orientation
        a, b = tri[np.arange(len(tri)), (k + 1) % 3], tri[np.arange(len(tri)), (k + 2) % 3]
        ua = v[a] - v[p]
        ub = v[b] - v[p]
        ua /= np.linalg.norm(ua, axis=1)[:, None]
        ub /= np.linalg.norm(ub, axis=1)[:, None]
        arcs.append((ua, ub))
        angle = np.arccos(np.clip(np.einsum("ij,ij->i", ua, ub), -1, 1))
        i = int(np.argmax(angle))
        n = np.cross(ua[i], ub[i])
        mid = (ua[i] + ub[i]) / np.linalg.norm(ua[i] + ub[i])
        y = mid - 1e-3 * angle[i] * n / np.linalg.norm(n)  # the faces point away from the solid
        probes.append(y / np.linalg.norm(y))
    side = np.array([[_on_solid_side(y, *arc) for arc in arcs] for y in probes])
    if not side.diagonal().all():
        raise ValueError(f"vertex {p}: a probe off a fan's arc is not on its solid side")
    groups: dict[bytes, list[int]] = {}
    for i in range(len(fans)):
        groups.setdefault(side[i].tobytes(), []).append(i)
    return list(groups.values())


def interior_betti(vertices, faces) -> tuple[int, int, int]:
    """``(components, genus, cavities)`` of the open interior of the solid ``faces`` bounds (outward-facing).

    Vertices at one position are welded first (a cut solid keeps a pinch as
    two vertex ids at one point).
    """
    v = np.asarray(vertices, np.float64)
    v, inv = np.unique(v, axis=0, return_inverse=True)
    f = inv.ravel()[np.asarray(faces)]
    nf = len(f)
    corner = _Union(3 * nf)  # corner (face, slot) -> 3 * face + slot
    slot = {}
    for fi, tri in enumerate(f):
        for s, vid in enumerate(tri):
            slot[fi, int(vid)] = 3 * fi + s
    sheet = _Union(nf)
    for g, h, a, b in _pair_around_edges(v, f):
        corner.join(slot[g, a], slot[h, a])
        corner.join(slot[g, b], slot[h, b])
        sheet.join(g, h)
    fan_of = np.array([corner.find(i) for i in range(3 * nf)])
    fans_at: dict[int, dict[int, list[int]]] = {}
    for i, root in enumerate(fan_of):
        fans_at.setdefault(int(f.flat[i]), {}).setdefault(int(root), []).append(i // 3)
    sheet_of = np.array([sheet.find(i) for i in range(nf)])
    names = {s: k for k, s in enumerate(np.unique(sheet_of))}
    sheet_of = np.array([names[s] for s in sheet_of])
    # twice the Euler characteristic of each sheet of the split surface: 2 (F - E) = -F, plus 2 per fan (vertex)
    chi2 = -np.bincount(sheet_of, minlength=len(names)).astype(np.int64)
    np.add.at(chi2, sheet_of[np.unique(fan_of) // 3], 2)
    joined = _Union(len(names))
    for p, fans in fans_at.items():
        if len(fans) < 2:
            continue
        lists = [np.array(sorted(set(x))) for x in fans.values()]
        for group in _solid_regions(p, lists, v, f):
            if len(group) > 1:  # joined through a sphere with m holes: chi + 2 - 2m
                chi2[sheet_of[lists[group[0]][0]]] += 2 * (2 - 2 * len(group))
                for g in group[1:]:
                    joined.join(sheet_of[lists[g][0]], sheet_of[lists[group[0]][0]])
    tri = v[f]
    volume = np.bincount(sheet_of, np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])), len(names))
    final = np.array([joined.find(i) for i in range(len(names))])
    components = genus = cavities = 0
    for root in np.unique(final):
        total = int(chi2[final == root].sum())  # 2 chi = 4 - 4 g
        if total % 4:
            raise ValueError("a resolved boundary surface of odd Euler characteristic")
        genus += (4 - total) // 4
        if volume[final == root].sum() > 0:
            components += 1
        else:
            cavities += 1
    return components, genus, cavities

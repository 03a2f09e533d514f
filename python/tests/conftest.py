# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
"""Shared fixtures: small meshes built in NumPy and a brute-force reference SDF."""

import os

import numpy as np
import pytest


def icosphere(subdivisions=2, radius=1.0):
    """An icosphere (outward, closed) built here, independently of ebgeom's generator."""
    t = (1.0 + 5 ** 0.5) / 2
    v = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t],
         [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    f = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
         [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8],
         [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    v = [list(np.asarray(p, float) / np.linalg.norm(p)) for p in v]
    for _ in range(subdivisions):
        cache, nf = {}, []

        def mid(a, b):
            k = (min(a, b), max(a, b))
            if k not in cache:
                m = (np.asarray(v[a]) + np.asarray(v[b])) / 2
                v.append(list(m / np.linalg.norm(m)))
                cache[k] = len(v) - 1
            return cache[k]

        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nf += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
        f = nf
    return np.asarray(v) * radius, np.asarray(f, dtype=np.int64)


def cube(lo=(-1, -1, -1), hi=(1, 1, 1)):
    """A closed outward cube of 12 triangles."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    c = np.array([[(hi if (i >> a) & 1 else lo)[a] for a in range(3)] for i in range(8)])
    f = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4], [2, 6, 3],
                  [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]], dtype=np.int64)
    return c, f


def point_triangle_distance(p, a, b, c):
    """Exact distance from points p (N, 3) to triangle abc (Ericson's closest point, vectorised)."""
    ab, ac = b - a, c - a
    ap = p - a
    d1, d2 = ap @ ab, ap @ ac
    bp = p - b
    d3, d4 = bp @ ab, bp @ ac
    cp = p - c
    d5, d6 = cp @ ab, cp @ ac
    va = d3 * d6 - d5 * d4
    vb = d5 * d2 - d1 * d6
    vc = d1 * d4 - d3 * d2
    denom = va + vb + vc
    with np.errstate(divide="ignore", invalid="ignore"):
        v = vb / denom
        w = vc / denom
    q = a + np.outer(v, ab) + np.outer(w, ac)  # interior
    # regions, in the same priority as Ericson
    m = (d1 <= 0) & (d2 <= 0)
    q[m] = a
    m2 = ~m & (d3 >= 0) & (d4 <= d3)
    q[m2] = b
    done = m | m2
    m3 = ~done & (vc <= 0) & (d1 >= 0) & (d3 <= 0)
    q[m3] = a + np.outer(d1[m3] / (d1[m3] - d3[m3]), ab)
    done |= m3
    m4 = ~done & (d6 >= 0) & (d5 <= d6)
    q[m4] = c
    done |= m4
    m5 = ~done & (vb <= 0) & (d2 >= 0) & (d6 <= 0)
    q[m5] = a + np.outer(d2[m5] / (d2[m5] - d6[m5]), ac)
    done |= m5
    m6 = ~done & (va <= 0) & ((d4 - d3) >= 0) & ((d5 - d6) >= 0)
    t6 = (d4[m6] - d3[m6]) / ((d4[m6] - d3[m6]) + (d5[m6] - d6[m6]))
    q[m6] = b + np.outer(t6, c - b)
    return np.linalg.norm(p - q, axis=1)


def brute_unsigned(points, v, f):
    """min over triangles of the exact point-triangle distance (float64)."""
    p = np.asarray(points, float)
    best = np.full(len(p), np.inf)
    for a, b, c in f:
        best = np.minimum(best, point_triangle_distance(p, v[a], v[b], v[c]))
    return best


def winding_number(points, v, f):
    """Generalized winding number (Van Oosterom-Strackee solid angles / 4 pi)."""
    p = np.asarray(points, float)
    w = np.zeros(len(p))
    for i, j, k in f:
        a, b, c = v[i] - p, v[j] - p, v[k] - p
        la, lb, lc = (np.linalg.norm(x, axis=1) for x in (a, b, c))
        det = np.einsum("ij,ij->i", a, np.cross(b, c))
        den = (la * lb * lc + np.einsum("ij,ij->i", a, b) * lc + np.einsum("ij,ij->i", b, c) * la
               + np.einsum("ij,ij->i", c, a) * lb)
        w += 2 * np.arctan2(det, den)
    return w / (4 * np.pi)


@pytest.fixture
def sphere_mesh():
    return icosphere(2)


@pytest.fixture
def cube_mesh():
    return cube()


@pytest.fixture
def cli():
    exe = os.environ.get("EBGEOM_CLI")
    if not exe or not os.path.exists(exe):
        pytest.skip("the ebgeom CLI is not built (EBGEOM_CLI unset)")
    return exe


@pytest.fixture
def source_dir():
    d = os.environ.get("EBGEOM_SOURCE_DIR",
                       os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
    return d

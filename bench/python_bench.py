#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
"""Python overhead and a Python peer, in one process on the same points.

1. ebgeom from Python (`sdf(points)`: argument checks, output allocation, GIL release) against
   the same C++ batch query timed inside the extension (`evaluate` into a preallocated buffer),
   on the same points, rounds interleaved; medians and the ratio.
2. Open3D's `RaycastingScene.compute_signed_distance` (Debian python3-open3d), when installed, on
   the same points: time, and on an open mesh the sign errors against ebgeom's exact winding
   sign (`sign="winding"`); skipped (and said so) when Open3D is missing.

Usage (from a build with the Python package, e.g. the dev preset):
  PYTHONPATH=build/dev/python /usr/bin/python3 bench/python_bench.py MESH [--points N]
      [--rounds R] [--threads T] [--precision float|double]
"""

import argparse
import statistics
import sys
import time

import numpy as np

import ebgeom
from ebgeom import _ebgeom


def median_time(fn, rounds):
    ts = []
    for _ in range(rounds):
        t0 = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mesh")
    ap.add_argument("--points", type=int, default=1_000_000)
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--precision", default="float")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--sign-points", type=int, default=20_000,
                    help="points checked against the exact (O(triangles) per point) winding sign")
    o = ap.parse_args()

    mesh = ebgeom.read_mesh(o.mesh)
    info = mesh.info()
    sdf = ebgeom.MeshSdf(mesh, precision=o.precision)
    lo, hi = (np.asarray(x) for x in sdf.bounds())
    pad = 0.1 * (hi - lo)
    rng = np.random.default_rng(o.seed)
    pts = (lo - pad + (hi - lo + 2 * pad) * rng.random((o.points, 3))).astype(sdf.dtype)
    print(f"mesh {o.mesh}: {info['triangles']} triangles, watertight {info['watertight']}, "
          f"sign {sdf.sign_mode} ({sdf.sign_reason})")
    print(f"{o.points} points uniform in the box + 10%, {o.precision}, threads {o.threads} "
          f"(0 = all cores), {o.rounds} interleaved rounds, medians")

    # 1. Python vs C++ (interleaved: one call of each per round)
    sdf(pts[:1000])
    py_t, cpp_t = [], []
    for _ in range(o.rounds):
        t0 = time.perf_counter()
        sdf(pts, threads=o.threads)
        py_t.append(time.perf_counter() - t0)
        cpp_t.append(_ebgeom._time_cpp_eval(sdf._impl, pts, o.threads))
    mp, mc = statistics.median(py_t), statistics.median(cpp_t)
    print(f"  ebgeom C++ evaluate      {mc * 1e3:9.2f} ms  ({o.points / mc / 1e6:.2f} M points/s)")
    print(f"  ebgeom Python sdf(pts)   {mp * 1e3:9.2f} ms  ({o.points / mp / 1e6:.2f} M points/s)"
          f"  overhead {100 * (mp / mc - 1):+.1f}%")
    print(f"  target (overhead <= 5% at 1M points): {'met' if mp <= 1.05 * mc else 'NOT met'}"
          + ("" if o.points >= 1_000_000 else f" (at {o.points} points)"))

    # 2. Open3D
    try:
        import open3d as o3d
    except ImportError:
        print("  Open3D: skipped (python3-open3d is not installed)")
        return 0
    tm = o3d.t.geometry.TriangleMesh()
    tm.vertex.positions = o3d.core.Tensor(np.asarray(sdf.vertices, dtype=np.float32))
    tm.triangle.indices = o3d.core.Tensor(np.asarray(sdf.triangles, dtype=np.uint32))
    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(tm)
    # Sanity check of the peer's inside test: a ray from the centre of a closed box must cross it.
    box = o3d.t.geometry.RaycastingScene()
    box.add_triangles(o3d.t.geometry.TriangleMesh.from_legacy(
        o3d.geometry.TriangleMesh.create_box()))
    crossings = box.count_intersections(
        o3d.core.Tensor(np.array([[0.5, 0.5, 0.5, 1, 0, 0]], np.float32))).numpy()[0]
    if crossings != 1:
        print(f"  note: this Open3D counts {crossings} crossings for a ray leaving a closed box "
              "(expected 1), so its sign reports no point inside")
    p32 = o3d.core.Tensor(pts.astype(np.float32))
    scene.compute_signed_distance(p32[:1000])
    o3_t, eb_t = [], []
    for _ in range(o.rounds):
        t0 = time.perf_counter()
        d_o3 = scene.compute_signed_distance(p32).numpy()
        o3_t.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        d_eb = sdf(pts, threads=o.threads)
        eb_t.append(time.perf_counter() - t0)
    mo, me = statistics.median(o3_t), statistics.median(eb_t)
    print(f"  Open3D {o3d.__version__} compute_signed_distance {mo * 1e3:9.2f} ms "
          f"({o.points / mo / 1e6:.2f} M points/s): {mo / me:.2f}x ebgeom's time")
    ref = ebgeom.MeshSdf(mesh, sign="winding", precision="double")
    sample = slice(0, min(o.points, o.sign_points))  # the exact winding sign is O(n) per point
    exact = ref(pts[sample].astype(np.float64))
    far = np.abs(exact) > 1e-4 * float(np.linalg.norm(hi - lo))  # leave ties at the surface out
    o3_wrong = np.count_nonzero(((d_o3[sample] < 0) != (exact < 0)) & far)
    eb_wrong = np.count_nonzero(((d_eb[sample] < 0) != (exact < 0)) & far)
    mag = np.max(np.abs(np.abs(d_o3[sample]) - np.abs(exact)))
    n = int(np.count_nonzero(far))
    print(f"  signs vs the exact winding sign on {n} points (|S| > 1e-4 of the diagonal): "
          f"Open3D {o3_wrong} wrong ({100 * o3_wrong / n:.2f}%), ebgeom ({sdf.sign_mode}) "
          f"{eb_wrong} wrong ({100 * eb_wrong / n:.2f}%); Open3D |S| max deviation {mag:.3g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
"""The ebgeom Python package against independent references: closed-form shapes, NumPy brute
force over triangles, a NumPy winding number, and the ebgeom CLI's own outputs."""

import gc
import json
import os
import re
import subprocess
import sys
import tempfile
import threading

import numpy as np
import pytest

import ebgeom
from conftest import brute_unsigned, cube, icosphere, winding_number

RNG = np.random.default_rng(7)


def test_version_matches_header(source_dir):
    text = open(os.path.join(source_dir, "include/ebgeom/version.hpp")).read()
    m = re.search(r'EBGEOM_VERSION_STRING "([0-9.]+)"', text)
    assert ebgeom.__version__ == m.group(1)


# ---- meshes ------------------------------------------------------------------------------------


def test_mesh_from_arrays_and_info(cube_mesh):
    v, f = cube_mesh
    m = ebgeom.Mesh(v.astype(np.float32), f.astype(np.int32))
    assert (m.vertex_count, m.face_count, m.triangle_count) == (8, 12, 12)
    np.testing.assert_array_equal(m.vertices, v)
    np.testing.assert_array_equal(m.faces, f)
    info = m.info()
    assert info["watertight"] and info["consistently_oriented"] and info["outward"]
    assert info["volume"] == pytest.approx(8.0)
    assert info["area"] == pytest.approx(24.0)
    assert info["auto_sign"]["mode"] == "pseudonormal"
    assert m.validate() == info


def test_mesh_mixed_faces():
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 1]])
    m = ebgeom.Mesh(v, [[0, 3, 2, 1], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]])
    assert m.triangle_count == 6
    assert isinstance(m.faces, list) and len(m.faces) == 5
    assert m.info()["watertight"]


@pytest.mark.parametrize("vertices,faces,message", [
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 3]], "row 0 has index 3"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2], [0, -1, 2]], "row 1 has index -1"),
    ([[0, 0, 0], [1, np.nan, 0], [0, 1, 0]], [[0, 1, 2]], "vertices: row 1 is not finite"),
    ([[0, 0], [1, 0], [0, 1]], [[0, 1, 2]], "shape \\(V, 3\\)"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1]], "row 0 has 2 corners"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.zeros((0, 3), int), "no faces"),
])
def test_mesh_bad_arrays(vertices, faces, message):
    with pytest.raises(ValueError, match=message):
        ebgeom.Mesh(vertices, faces)


def test_mesh_bad_dtypes():
    with pytest.raises(TypeError):
        ebgeom.Mesh(np.array([["a", "b", "c"]]), [[0, 0, 0]])
    with pytest.raises(TypeError):
        ebgeom.Mesh(np.zeros((3, 3)), np.array([[0.0, 1.0, 2.0]]))


def test_read_write_roundtrip(tmp_path, sphere_mesh):
    v, f = sphere_mesh
    m = ebgeom.Mesh(v, f)
    for ext in ("stl", "ply", "obj", "vtk"):
        p = tmp_path / f"s.{ext}"
        m.write(p if ext != "obj" else str(p))
        r = ebgeom.read_mesh(p)
        assert r.path == str(p)
        assert r.triangle_count == len(f)
        assert r.info()["watertight"], ext
    a = ebgeom.read_mesh(tmp_path / "s.ply")
    np.testing.assert_array_equal(a.vertices, v)  # binary PLY keeps doubles
    np.testing.assert_array_equal(a.faces, f)


def test_read_errors(tmp_path):
    with pytest.raises(FileNotFoundError):
        ebgeom.read_mesh(tmp_path / "missing.obj")
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n")
    with pytest.raises(ebgeom.MeshFormatError) as e:
        ebgeom.read_mesh(bad)
    assert isinstance(e.value, ValueError)
    assert str(bad) in str(e.value) and "line 4" in str(e.value)
    assert e.value.line == 4 and e.value.path == str(bad)
    trunc = tmp_path / "t.stl"
    trunc.write_bytes(b"\0" * 80 + (5).to_bytes(4, "little") + b"\0" * 60)
    with pytest.raises(ebgeom.MeshFormatError, match="byte"):
        ebgeom.read_mesh(trunc)
    with pytest.raises((OSError, ValueError)):
        ebgeom.read_mesh(tmp_path)  # a directory
    with pytest.raises(OSError):
        ebgeom.Mesh(*cube()).write(tmp_path / "no" / "such" / "dir.stl")


# ---- distances ---------------------------------------------------------------------------------


@pytest.mark.parametrize("precision,dtype,tol", [("float", np.float32, 2e-6),
                                                   ("double", np.float64, 1e-12)])
def test_mesh_sdf_vs_brute_force(sphere_mesh, precision, dtype, tol):
    v, f = sphere_mesh
    sdf = ebgeom.MeshSdf(ebgeom.Mesh(v, f), precision=precision)
    assert sdf.sign_mode == "pseudonormal" and sdf.precision == precision
    p = RNG.uniform(-1.6, 1.6, size=(2000, 3))
    d = sdf(p)
    assert d.dtype == dtype and d.shape == (2000,)
    ref = brute_unsigned(p.astype(dtype).astype(float), v.astype(dtype).astype(float), f)
    inside = winding_number(p, v, f) > 0.5
    ref = np.where(inside, -ref, ref)
    np.testing.assert_allclose(d, ref, rtol=0, atol=tol * 4)


def test_cube_closed_form(cube_mesh):
    sdf = ebgeom.MeshSdf(ebgeom.Mesh(*cube_mesh), precision="double")
    p = RNG.uniform(-3, 3, size=(3000, 3))
    q = np.abs(p) - 1
    ref = np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0)
    np.testing.assert_allclose(sdf(p), ref, atol=1e-12)


def test_open_mesh_winding_sign(sphere_mesh):
    v, f = sphere_mesh
    keep = ~np.all(v[f][:, :, 2] > 0.8, axis=1)  # cut a hole at the top
    m = ebgeom.Mesh(v, f[keep])
    assert not m.info()["watertight"]
    sdf = ebgeom.MeshSdf(m, precision="double")
    assert sdf.sign_mode == "fast-winding" and "boundary edges" in sdf.sign_reason
    exact = ebgeom.MeshSdf(m, sign="winding", precision="double")
    p = RNG.uniform(-1.5, 1.5, size=(1500, 3))
    ref_u = brute_unsigned(p, v, f[keep])
    inside = winding_number(p, v, f[keep]) > 0.5
    np.testing.assert_allclose(np.abs(exact(p)), ref_u, atol=1e-12)
    assert np.array_equal(exact(p) < 0, inside & (ref_u > 0))
    assert np.all(ebgeom.MeshSdf(m, sign="unsigned")(p) >= 0)


def test_sign_modes():
    m = ebgeom.Mesh(*cube())
    for s in ebgeom.SIGN_MODES:
        sdf = ebgeom.MeshSdf(m, sign=s)
        assert sdf.sign_requested == s
        assert sdf.sign_mode in ("pseudonormal", "winding", "fast-winding", "unsigned")
    with pytest.raises(ValueError, match="unknown sign mode 'bogus'"):
        ebgeom.MeshSdf(m, sign="bogus")
    with pytest.raises(ValueError, match="precision"):
        ebgeom.MeshSdf(m, precision="half")


def test_query_closest_normals_faces(cube_mesh):
    v, f = cube_mesh
    sdf = ebgeom.MeshSdf(ebgeom.Mesh(v, f), precision="double")
    p = RNG.uniform(-3, 3, size=(2000, 3))
    q = sdf.query(p)
    np.testing.assert_array_equal(q.distance, sdf(p))
    # closest point: on the cube's surface, at distance |S|
    c = q.closest
    assert np.all(np.abs(c) <= 1 + 1e-12) and np.allclose(np.abs(c).max(axis=1), 1)
    np.testing.assert_allclose(np.linalg.norm(p - c, axis=1), np.abs(q.distance), atol=1e-12)
    # normal: unit, equal to the closed-form gradient where it is defined
    np.testing.assert_allclose(np.linalg.norm(q.normal, axis=1), 1, atol=1e-12)
    outside = np.any(np.abs(p) > 1, axis=1)
    g = (p - np.clip(p, -1, 1))[outside]
    g /= np.linalg.norm(g, axis=1)[:, None]
    np.testing.assert_allclose(q.normal[outside], g, atol=1e-9)
    # the triangle holds the closest point; the feature is a face, edge or vertex of it
    tri = sdf.vertices[sdf.triangles[q.triangle]]
    d = brute_unsigned(c, v, f)
    assert np.all(d < 1e-12)
    for i in range(0, 2000, 97):
        a, b, cc = tri[i]
        assert brute_unsigned(c[i:i + 1], np.array([a, b, cc]), np.array([[0, 1, 2]]))[0] < 1e-12
    assert set(np.unique(q.feature)) <= set(range(7))
    corner = np.all(np.abs(p) > 1, axis=1)
    assert np.all(q.feature[corner] >= 4)  # corner regions: vertex features
    only = sdf.query(p, closest=False, normals=False, faces=False)
    assert only.closest is None and only.normal is None and only.triangle is None


def test_cli_query_bit_for_bit(tmp_path, cli, sphere_mesh):
    v, f = sphere_mesh
    mp = tmp_path / "s.ply"
    ebgeom.Mesh(v, f).write(mp)
    p = RNG.uniform(-1.5, 1.5, size=(500, 3))
    np.save(tmp_path / "p.npy", p)
    subprocess.run([cli, "query", str(mp), "--points", str(tmp_path / "p.npy"), "-o",
                    str(tmp_path / "d.npy"), "--closest", str(tmp_path / "c.npy"), "--normals",
                    str(tmp_path / "n.npy"), "-q"], check=True)
    q = ebgeom.MeshSdf(ebgeom.read_mesh(mp), precision="double").query(p)
    np.testing.assert_array_equal(q.distance, np.load(tmp_path / "d.npy"))
    np.testing.assert_array_equal(q.closest, np.load(tmp_path / "c.npy"))
    np.testing.assert_array_equal(q.normal, np.load(tmp_path / "n.npy"))


# ---- arrays: dtypes, layouts, copies, threads, leaks -------------------------------------------


def test_array_layouts_and_dtypes(sphere_mesh):
    sdf = ebgeom.MeshSdf(ebgeom.Mesh(*sphere_mesh))
    p = RNG.uniform(-1.5, 1.5, size=(1000, 3))
    ref = sdf(p.astype(np.float32))
    big = RNG.uniform(-1.5, 1.5, size=(1000, 6))
    big[:, ::2] = p
    for arr in (p, np.asfortranarray(p), p.astype(np.float32, order="F"), big[:, ::2],
                p.tolist()):
        np.testing.assert_array_equal(sdf(arr), ref)
    np.testing.assert_array_equal(sdf(np.array([1, 0, 0])), sdf([[1.0, 0.0, 0.0]]))
    assert sdf(np.zeros((0, 3))).shape == (0,)
    for bad in (np.zeros((4, 2)), np.zeros((2, 3, 3)), np.zeros(5)):
        with pytest.raises(ValueError, match=r"shape \(N, 3\)"):
            sdf(bad)
    with pytest.raises(TypeError):
        sdf(np.array([["a", "b", "c"]]))
    with pytest.raises(ValueError, match="threads"):
        sdf(p, threads=-1)


def test_no_copy_and_out(sphere_mesh):
    sdf = ebgeom.MeshSdf(ebgeom.Mesh(*sphere_mesh))
    p = RNG.uniform(-1.5, 1.5, size=(1000, 3)).astype(np.float32)
    out = np.empty(1000, np.float32)
    r = sdf(p, out=out)
    assert r is out or np.shares_memory(r, out)
    np.testing.assert_array_equal(out, sdf(p))
    # the input is read in place: a view of the caller's buffer, checked through the buffer
    # address the extension sees (a read-only array cannot be copied into silently either)
    p.setflags(write=False)
    sdf(p)
    with pytest.raises(ValueError, match="out"):
        sdf(p, out=np.empty(1000, np.float64))
    with pytest.raises(ValueError, match="out"):
        sdf(p, out=np.empty(999, np.float32))
    # no allocation proportional to N for matching input: tracemalloc sees only the result
    import tracemalloc
    big = RNG.uniform(-1.5, 1.5, size=(200000, 3)).astype(np.float32)
    sdf(big)
    tracemalloc.start()
    sdf(big, out=np.empty(200000, np.float32))
    peak_same = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    tracemalloc.start()
    sdf(big.astype(np.float64), out=np.empty(200000, np.float32))
    peak_convert = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert peak_same < 200000 * 4 * 1.5  # the out array only
    assert peak_convert > 200000 * 12  # the converted copy


def test_thread_invariance_and_gil_release(sphere_mesh):
    sdf = ebgeom.MeshSdf(ebgeom.Mesh(*icosphere(3)), sign="fast-winding")
    p = RNG.uniform(-1.5, 1.5, size=(20000, 3))
    ref = sdf(p, threads=1)
    for t in (2, 3, 0):
        np.testing.assert_array_equal(sdf(p, threads=t), ref)
    # concurrent calls from Python threads (the GIL is released during queries)
    results = [None] * 4

    def work(i):
        results[i] = sdf(p, threads=1)

    ts = [threading.Thread(target=work, args=(i,)) for i in range(4)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    for r in results:
        np.testing.assert_array_equal(r, ref)


def test_no_leaks(sphere_mesh):
    sdf = ebgeom.MeshSdf(ebgeom.Mesh(*sphere_mesh))
    p = RNG.uniform(-1.5, 1.5, size=(100, 3))
    rc = sys.getrefcount(p)
    for _ in range(1000):
        sdf(p)
        sdf.query(p)
    assert sys.getrefcount(p) == rc
    gc.collect()
    import tracemalloc
    tracemalloc.start()
    for _ in range(200):
        sdf(p)
    a = tracemalloc.get_traced_memory()[0]
    for _ in range(1000):
        sdf(p)
        sdf.query(p)
        sdf.sign_reason
    b = tracemalloc.get_traced_memory()[0]
    tracemalloc.stop()
    assert b - a < 20000


# ---- shapes, CSG, scenes -----------------------------------------------------------------------


def test_shapes_closed_form():
    p = RNG.uniform(-3, 3, size=(2000, 3))
    r = np.linalg.norm(p - [0.5, 0, 0], axis=1)
    np.testing.assert_allclose(ebgeom.sphere(1.2, (0.5, 0, 0))(p), r - 1.2, atol=1e-12)
    q = np.abs(p) - [1, 0.5, 0.25]
    boxd = np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0)
    np.testing.assert_allclose(ebgeom.box(size=(2, 1, 0.5))(p), boxd, atol=1e-12)
    # torus around z
    t = np.sqrt((np.hypot(p[:, 0], p[:, 1]) - 1.5) ** 2 + p[:, 2] ** 2) - 0.3
    np.testing.assert_allclose(ebgeom.torus(1.5, 0.3)(p), t, atol=1e-12)
    np.testing.assert_allclose(ebgeom.plane((0, 0, 2), (0, 0, 1))(p), p[:, 2] - 1, atol=1e-12)
    # transforms: a translated, rotated, scaled sphere is still a sphere
    s = ebgeom.sphere(0.5).scale(2).rotate((1, 1, 0), 30).translate((1, 2, 3))
    np.testing.assert_allclose(s(p), np.linalg.norm(p - [1, 2, 3], axis=1) - 1, atol=1e-12)
    # CSG: sharp union/intersection/difference are min/max
    a, b = ebgeom.sphere(1), ebgeom.sphere(1, (1, 0, 0))
    da, db = a(p), b(p)
    np.testing.assert_allclose((a | b)(p), np.minimum(da, db), atol=1e-12)
    np.testing.assert_allclose((a & b)(p), np.maximum(da, db), atol=1e-12)
    np.testing.assert_allclose((a - b)(p), np.maximum(da, -db), atol=1e-12)
    k = 0.3
    h = np.maximum(k - np.abs(da - db), 0) / k
    smooth = np.minimum(da, db) - h * h * k * 0.25
    np.testing.assert_allclose(ebgeom.union(a, b, smooth=k)(p), smooth, atol=1e-12)
    np.testing.assert_allclose(a.offset(0.2)(p), da - 0.2, atol=1e-12)
    np.testing.assert_allclose(a.shell(0.1)(p), np.abs(da) - 0.1, atol=1e-12)


def test_mesh_in_csg(tmp_path, cube_mesh):
    mp = tmp_path / "cube.stl"
    ebgeom.Mesh(*cube_mesh).write(mp)
    s = ebgeom.mesh(mp) - ebgeom.sphere(1.2)
    p = RNG.uniform(-2, 2, size=(1000, 3))
    ref = np.maximum(ebgeom.MeshSdf(mp, precision="double")(p),
                     -(np.linalg.norm(p, axis=1) - 1.2))
    np.testing.assert_allclose(s(p), ref, atol=1e-12)


def test_scene_file_and_errors(tmp_path, source_dir):
    scene = ebgeom.load_scene(os.path.join(source_dir, "examples/scenes/csg.json"))
    assert scene(np.zeros((1, 3))).shape == (1,)
    bad = tmp_path / "bad.json"
    bad.write_text('{"root": {"type": "sphere", "radius": -1}}')
    with pytest.raises(ebgeom.SceneError, match=r"bad.json: /root/radius: expected a positive"):
        ebgeom.load_scene(bad)
    bad.write_text('{"root": {"type": "sphere",\n "radius": }}')
    with pytest.raises(ebgeom.SceneError, match=r"line 2"):
        ebgeom.load_scene(bad)
    with pytest.raises(FileNotFoundError):
        ebgeom.load_scene(tmp_path / "none.json")
    with pytest.raises(ebgeom.SceneError, match="unknown node type"):
        ebgeom.scene_from_json({"type": "blob"})
    with pytest.raises(ebgeom.SceneError, match="does not exist"):
        ebgeom.scene_from_json({"type": "mesh", "path": str(tmp_path / "x.stl")})
    with pytest.raises(ValueError, match="box: give exactly one"):
        ebgeom.box()


# ---- grids -------------------------------------------------------------------------------------


def test_grid_layout_matches_points():
    s = ebgeom.sphere(1.0).compile("double")
    g = ebgeom.sample_grid(s, res=(6, 7, 8))
    assert g.values.shape == (8, 7, 6) and g.dims == (6, 7, 8)
    assert g.centering == "cell"
    np.testing.assert_allclose(g.values, np.linalg.norm(g.points(), axis=-1) - 1, atol=1e-12)
    (lo, hi) = g.box
    np.testing.assert_allclose(lo, [-1.2] * 3)  # bounds grown by pad = 0.1 per side
    np.testing.assert_allclose(g.origin, np.asarray(lo) + np.asarray(g.spacing) / 2)
    n = ebgeom.sample_grid(s, box=(-1, -1, -1, 1, 1, 1), res=5, nodes=True)
    assert n.origin == (-1, -1, -1) and n.spacing == (0.5, 0.5, 0.5)
    d = ebgeom.sample_grid(s, box=((-1, -1, -1), (1, 1, 1.1)), dx=0.25)
    assert d.dims == (8, 8, 9) and d.box[1][2] == pytest.approx(1.25)


def test_grid_errors():
    s = ebgeom.sphere(1.0).compile()
    with pytest.raises(ValueError, match="res or dx"):
        ebgeom.sample_grid(s, res=8, dx=0.1)
    with pytest.raises(ValueError, match="lo >= hi|must be below"):
        ebgeom.sample_grid(s, box=(0, 0, 0, 1, -1, 1), res=4)
    with pytest.raises(ValueError, match="unbounded"):
        ebgeom.sample_grid(ebgeom.plane((0, 0, 1)), res=4)
    with pytest.raises(ValueError, match="res"):
        ebgeom.sample_grid(s, res=0)
    with pytest.raises(TypeError):
        ebgeom.sample_grid(object(), res=4)


@pytest.mark.parametrize("precision", ["float", "double"])
@pytest.mark.parametrize("args,kw", [
    (["--res", "12", "10", "9"], {"res": (12, 10, 9)}),
    (["--dx", "0.15", "--nodes"], {"dx": 0.15, "nodes": True}),
    (["--res", "16", "--band", "2"], {"res": 16, "band": 2}),
    (["--res", "8", "--box", "-2", "-1", "-1", "2", "1", "1.5"],
     {"res": 8, "box": (-2, -1, -1, 2, 1, 1.5)}),
    (["--res", "10", "--pad", "0.3"], {"res": 10, "pad": 0.3}),
])
def test_grid_bit_for_bit_with_cli(tmp_path, cli, source_dir, precision, args, kw):
    mp = tmp_path / "s.ply"
    v, f = icosphere(2)
    ebgeom.Mesh(v + [0.1, 0.2, 0.3], f).write(mp)
    for src in (str(mp), os.path.join(source_dir, "examples/scenes/csg.json")):
        out = tmp_path / "g.npy"
        r = subprocess.run([cli, "sdf", src, "-o", str(out), "--precision", precision, "--json"]
                           + args, check=True, capture_output=True, text=True)
        summary = json.loads(r.stdout)
        sdf = (ebgeom.load_scene(src, precision) if src.endswith(".json")
               else ebgeom.MeshSdf(src, precision=precision))
        g = ebgeom.sample_grid(sdf, **kw)
        ref = np.load(out)
        assert g.values.dtype == ref.dtype and g.values.shape == ref.shape
        np.testing.assert_array_equal(g.values, ref)
        assert list(g.origin) == summary["origin"] and list(g.spacing) == summary["spacing"]
        assert g.band == summary["band"]


def test_grid_save_formats(tmp_path):
    g = ebgeom.sample_grid(ebgeom.sphere(1.0), res=(5, 6, 7))
    g.save(tmp_path / "g.npy")
    np.testing.assert_array_equal(np.load(tmp_path / "g.npy"), g.values)
    g.save(tmp_path / "g.raw")
    side = json.loads((tmp_path / "g.json").read_text())
    raw = np.fromfile(tmp_path / "g.raw", dtype=np.float32).reshape(7, 6, 5)
    np.testing.assert_array_equal(raw, g.values)
    assert side["dims"] == [5, 6, 7]
    np.testing.assert_allclose(side["origin"], g.origin, rtol=1e-6)
    g.save(tmp_path / "g.vti")
    assert b"ImageData" in (tmp_path / "g.vti").read_bytes()[:400]
    with pytest.raises(ValueError, match="extension|format"):
        g.save(tmp_path / "g.xyz")
    with pytest.raises(OSError):
        g.save(tmp_path / "missing" / "g.npy")


# ---- training samples --------------------------------------------------------------------------


def test_sample_points(sphere_mesh):
    sdf = ebgeom.MeshSdf(ebgeom.Mesh(*icosphere(3)), precision="double")
    p, d = ebgeom.sample_points(sdf, 5000, near_surface=0.8, sigma=0.01, seed=3)
    assert p.shape == (5000, 3) and d.shape == (5000,) and p.dtype == np.float64
    np.testing.assert_array_equal(d, sdf(p))
    p2, d2 = ebgeom.sample_points(sdf, 5000, near_surface=0.8, sigma=0.01, seed=3)
    np.testing.assert_array_equal(p, p2)
    assert not np.array_equal(p, ebgeom.sample_points(sdf, 5000, seed=4)[0])
    near = np.abs(d[:4000])
    assert np.median(near) < 0.02 and near.max() < 0.1  # |S| <= |noise| (plus the facets' sag)
    lo, hi = np.asarray(sdf.bounds())
    ext = hi - lo
    assert np.all(p[4000:] >= lo - 0.1 * ext - 1e-12) and np.all(p[4000:] <= hi + 0.1 * ext)
    with pytest.raises(ValueError):
        ebgeom.sample_points(sdf, 10, near_surface=1.5)


def test_help_has_examples():
    assert "sign" in ebgeom.MeshSdf.__doc__ and ">>>" in ebgeom.MeshSdf.__doc__
    assert "info --json" in ebgeom.Mesh.info.__doc__


# ---- glTF --------------------------------------------------------------------------------------


def cube_gltf(buffer):
    """A glTF scene: the cube [-1, 1]^3 (float positions, uint16 indices) at node 0, moved by
    (10, 0, 0) and scaled by 2: the box [8, 12] x [-2, 2] x [-2, 2]."""
    return {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "translation": [10, 0, 0], "scale": [2, 2, 2]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
        "buffers": [buffer],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 72}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                       "min": [-1, -1, -1], "max": [1, 1, 1]},
                      {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}],
    }


def test_gltf_and_glb(tmp_path, cli):
    import base64
    import struct
    v, f = cube()
    data = v.astype("<f4").tobytes() + f.astype("<u2").tobytes()
    uri = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    (tmp_path / "cube.gltf").write_text(json.dumps(cube_gltf({"uri": uri,
                                                               "byteLength": len(data)})))
    js = json.dumps(cube_gltf({"byteLength": len(data)})).encode()
    js += b" " * (-len(js) % 4)
    glb = (b"glTF" + struct.pack("<II", 2, 12 + 8 + len(js) + 8 + len(data))
           + struct.pack("<I", len(js)) + b"JSON" + js + struct.pack("<I", len(data)) + b"BIN\0"
           + data)
    (tmp_path / "cube.glb").write_bytes(glb)
    p = RNG.uniform(5, 15, size=(500, 3)) - [0, 10, 10]
    q = np.abs(p - [10, 0, 0]) - 2
    ref = np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0)
    np.save(tmp_path / "p.npy", p)
    for name in ("cube.gltf", "cube.glb"):
        m = ebgeom.read_mesh(tmp_path / name)
        assert m.triangle_count == 12 and m.info()["watertight"]
        np.testing.assert_array_equal(m.vertices, 2 * v + [10, 0, 0])
        np.testing.assert_allclose(ebgeom.MeshSdf(m)(p), ref, atol=1e-5)
        sdf = ebgeom.MeshSdf(tmp_path / name, precision="double")
        np.testing.assert_allclose(sdf(p), ref, atol=1e-12)
        out = tmp_path / "d.npy"  # the CLI's query (double) on the same file
        subprocess.run([cli, "query", str(tmp_path / name), "--points", str(tmp_path / "p.npy"),
                        "-o", str(out), "-q"], check=True)
        np.testing.assert_array_equal(sdf(p), np.load(out))
    bad = cube_gltf({"uri": uri, "byteLength": len(data)})
    bad["accessors"][0]["componentType"] = 5121  # unsigned byte positions
    (tmp_path / "bad.gltf").write_text(json.dumps(bad))
    with pytest.raises(ebgeom.MeshFormatError, match="bad.gltf.*POSITION must be float VEC3") as e:
        ebgeom.read_mesh(tmp_path / "bad.gltf")
    assert e.value.path == str(tmp_path / "bad.gltf")


# ---- in-memory meshes inside CSG ---------------------------------------------------------------


@pytest.mark.parametrize("precision", ["float", "double"])
def test_in_memory_mesh_in_csg(precision):
    v, f = icosphere(2)
    m = ebgeom.Mesh(v * 0.8 + [0.3, 0, 0], f)  # built from arrays: no file
    ball = ebgeom.sphere(0.5, (-0.4, 0, 0))
    p = RNG.uniform(-1.5, 1.5, size=(2000, 3))
    dm = ebgeom.MeshSdf(m, precision=precision)(p)
    db = ball.compile(precision)(p)
    for shape, ref in ((ebgeom.union(m, ball), np.minimum(dm, db)),
                       (m | ball, np.minimum(dm, db)),
                       (m - ball, np.maximum(dm, -db)),
                       (ball - m, np.maximum(db, -dm)),
                       (ebgeom.intersection(ball, m), np.maximum(db, dm))):
        np.testing.assert_array_equal(shape.compile(precision)(p), ref)
    # a MeshSdf brings its sign mode; an open mesh under the exact winding sign
    keep = ~np.all(v[f][:, :, 2] > 0.8, axis=1)
    open_sdf = ebgeom.MeshSdf(ebgeom.Mesh(v, f[keep]), sign="winding", precision=precision)
    s = ebgeom.union(open_sdf, ebgeom.sphere(0.2, (0, 0, 2)))
    assert s.node["children"][0]["sign"] == "winding"
    np.testing.assert_array_equal(
        s.compile(precision)(p),
        np.minimum(open_sdf(p), ebgeom.sphere(0.2, (0, 0, 2)).compile(precision)(p)))
    # transforms of the composed shape apply to the mesh too (p + 1 - 1 rounds: not bit for bit)
    moved = (m | ball).translate((0, 0, 1))
    np.testing.assert_allclose(moved.compile(precision)(p + [0, 0, 1]),
                               (m | ball).compile(precision)(p),
                               atol=1e-6 if precision == "float" else 1e-14)


def test_in_memory_mesh_lives_with_its_shapes_without_a_file(tmp_path, monkeypatch):
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))  # a temporary file would show here
    m = ebgeom.Mesh(*cube())
    s = m | ebgeom.sphere(0.1, (3, 0, 0))
    node = s.node["children"][0]
    assert "path" not in node and node["ref"].startswith("mesh-")
    assert ebgeom.mesh(m).node["ref"] == node["ref"]  # one reference per mesh
    assert ebgeom.mesh(ebgeom.Mesh(*cube())).node["ref"] != node["ref"]
    t = s.translate((1, 0, 0))
    del s, m
    gc.collect()
    np.testing.assert_allclose(t([[1, 0, 0]]), [-1], atol=1e-12)  # t keeps the mesh alive
    assert os.listdir(tmp_path) == []  # nothing written
    # the scene file names the reference, which only the shapes that hold the mesh resolve
    with pytest.raises(ebgeom.SceneError, match='/root/children/0/ref: no in-memory mesh is '
                                                'registered as "mesh-'):
        ebgeom.scene_from_json(t.to_json())
    # a mesh read from a file is used through its file, as MeshSdf reads it
    mp = tmp_path / "cube.obj"
    ebgeom.Mesh(*cube()).write(mp)
    assert ebgeom.mesh(ebgeom.read_mesh(mp)).node["path"] == str(mp)
    with pytest.raises(TypeError, match="union: expected ebgeom shapes, meshes"):
        ebgeom.union(ebgeom.sphere(1), "cube.obj")


def test_info_equals_cli_info_json(tmp_path, cli, sphere_mesh):
    v, f = sphere_mesh
    keep = ~np.all(v[f][:, :, 2] > 0.8, axis=1)  # a hole: boundary edges, fast-winding sign
    for name, faces in (("closed.ply", f), ("open.obj", f[keep])):
        path = tmp_path / name
        ebgeom.Mesh(v, faces).write(path)
        r = subprocess.run([cli, "info", str(path), "--json"], check=True, capture_output=True,
                           text=True)
        assert ebgeom.read_mesh(path).info() == json.loads(r.stdout)

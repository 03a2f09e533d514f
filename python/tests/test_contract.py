# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
"""The package's promises about Python itself: the GIL is released during C++ work, results do not
depend on threads, inputs are not copied where no copy is promised, nothing leaks over 1,000 calls
(error paths included), errors carry their location, stubs match the extension, and every public
name has a docstring whose worked examples hold."""

import ast
import gc
import inspect
import os
import re
import sys
import threading
import time

import numpy as np
import pytest

import ebgeom
from conftest import icosphere

RNG = np.random.default_rng(11)


@pytest.fixture(scope="module")
def ball():
    return ebgeom.MeshSdf(ebgeom.Mesh(*icosphere(3)), precision="double")


# ---- the GIL -----------------------------------------------------------------------------------


def calibrated(make, seconds=0.4):
    """make(n) returns a call of size n; the first (doubling n) that takes `seconds`, so that the
    GIL test measures a call long enough to tell a released GIL from a held one when other jobs
    load the machine."""
    n = 1 << 10
    while True:
        fn = make(n)
        t0 = time.perf_counter()
        fn()
        if time.perf_counter() - t0 >= seconds or n >= 1 << 26:
            return fn
        n *= 2


def longest_stall(fn):
    """Runs fn() in a thread while this thread spins in Python; returns (seconds fn took, longest
    interval in which this thread could not run). A call that holds the GIL stalls this thread
    for the whole call; a call that releases it stalls it for a thread switch at most."""
    done = threading.Event()
    took = {}

    def work():
        t0 = time.perf_counter()
        fn()
        took["s"] = time.perf_counter() - t0
        done.set()

    last = time.perf_counter()
    stall = 0.0
    th = threading.Thread(target=work)
    th.start()
    while not done.is_set():
        now = time.perf_counter()
        stall = max(stall, now - last)
        last = now
    th.join()
    return took["s"], stall


def plane_mesh(n):
    """An n x n grid of vertices on the plane z = 0, two triangles per square."""
    x, y = np.meshgrid(np.arange(n, dtype=float), np.arange(n, dtype=float))
    v = np.stack([x.ravel(), y.ravel(), np.zeros(n * n)], axis=1)
    i = (np.arange(n - 1)[None, :] + n * np.arange(n - 1)[:, None]).ravel()
    f = np.concatenate([np.stack([i, i + 1, i + n], 1), np.stack([i + 1, i + n + 1, i + n], 1)])
    return ebgeom.Mesh(v, f)


@pytest.mark.parametrize("call", ["sdf", "query", "grid", "sparse", "read_mesh", "build"])
def test_gil_released(ball, tmp_path, call):
    def make(n):
        if call in ("sdf", "query"):
            pts = RNG.uniform(-1.5, 1.5, size=(n, 3))
            f = ball if call == "sdf" else ball.query
            return lambda: f(pts, threads=1)
        if call in ("grid", "sparse"):
            res = max(8, int(round(n ** (1 / 3))))
            return lambda: ebgeom.sample_grid(ball, res=res, band=2, sparse=call == "sparse",
                                              threads=1)
        m = plane_mesh(max(8, int(n ** 0.5)))
        if call == "build":
            return lambda: ebgeom.MeshSdf(m)
        path = tmp_path / f"plane{n}.obj"
        m.write(path, ascii=True)
        return lambda: ebgeom.read_mesh(path)

    took, stall = longest_stall(calibrated(make))
    assert took > 0.2
    assert stall < 0.5 * took, f"{call}: stalled {stall:.3f} s of a {took:.3f} s call"


# ---- threads -----------------------------------------------------------------------------------


def test_threads_invariance_everywhere(ball):
    p = RNG.uniform(-1.5, 1.5, size=(5000, 3))
    q1 = ball.query(p, threads=1)
    for t in (2, 5, 0):
        q = ball.query(p, threads=t)
        for name in ("distance", "closest", "normal", "triangle", "feature"):
            np.testing.assert_array_equal(getattr(q, name), getattr(q1, name))
    g1 = ebgeom.sample_grid(ball, res=(33, 17, 20), threads=1)
    for t in (2, 3, 0):
        np.testing.assert_array_equal(ebgeom.sample_grid(ball, res=(33, 17, 20), threads=t).values,
                                      g1.values)
    s1 = ebgeom.sample_points(ball, 3000, seed=5, threads=1)
    s0 = ebgeom.sample_points(ball, 3000, seed=5, threads=0)
    np.testing.assert_array_equal(s1[0], s0[0])
    np.testing.assert_array_equal(s1[1], s0[1])
    scene = (ebgeom.sphere(1) - ebgeom.box(size=(1, 1, 3))).compile("double")
    np.testing.assert_array_equal(scene(p, threads=1), scene(p, threads=3))


# ---- copies ------------------------------------------------------------------------------------


def test_points_read_in_place_when_layout_matches(ball):
    f32 = ebgeom.MeshSdf(ebgeom.Mesh(*icosphere(1)))
    for sdf, dt in ((ball, np.float64), (f32, np.float32)):
        p = np.ascontiguousarray(RNG.uniform(-1, 1, size=(100, 3)).astype(dt))
        assert ebgeom._ebgeom._points_address(sdf._impl, p) == p.ctypes.data
        row = p[10:20]  # a C-contiguous slice is read in place too
        assert ebgeom._ebgeom._points_address(sdf._impl, row) == row.ctypes.data
        p.setflags(write=False)  # read-only input: still no copy
        assert ebgeom._ebgeom._points_address(sdf._impl, p) == p.ctypes.data
        other = np.float32 if dt == np.float64 else np.float64
        for copied in (np.asfortranarray(p), p.astype(other), p[::2]):
            assert ebgeom._ebgeom._points_address(sdf._impl, copied) != copied.ctypes.data
    # results are new arrays the caller owns
    p = RNG.uniform(-1, 1, size=(100, 3))
    d = ball(p)
    assert d.flags.owndata and d.flags.writeable and not np.shares_memory(d, p)
    q = ball.query(p)
    assert not np.shares_memory(q.closest, p) and q.closest.flags.writeable
    g = ebgeom.sample_grid(ball, res=8)
    assert g.values.flags.owndata and g.values.flags.writeable


# ---- leaks -------------------------------------------------------------------------------------


def rss():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_no_leaks_over_1000_calls(ball, tmp_path):
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
    p = RNG.uniform(-1.5, 1.5, size=(200, 3))
    wrong = np.zeros((4, 2))
    shape = ebgeom.sphere(1.0).compile("double")  # grids of a cheap SDF: many calls, quickly

    def one_round():
        ball(p)
        ball.query(p)
        g = ebgeom.sample_grid(shape, res=12, band=1, sparse=True, threads=1)
        g.values, g.tiles, g.tile_code, g.to_dense()
        ebgeom.sample_grid(shape, res=12, threads=1)
        with pytest.raises(ValueError):
            ball(wrong)
        with pytest.raises(ebgeom.MeshFormatError):
            ebgeom.read_mesh(bad)
        with pytest.raises(ValueError):
            ebgeom.Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 5]])
        with pytest.raises(ebgeom.SceneError):
            ebgeom.scene_from_json({"type": "sphere", "radius": -1})

    refs = [sys.getrefcount(x) for x in (p, wrong, ball, ball._impl)]
    for _ in range(100):
        one_round()
    gc.collect()
    before = rss()
    for _ in range(1000):
        one_round()
    gc.collect()
    grown = rss() - before
    assert [sys.getrefcount(x) for x in (p, wrong, ball, ball._impl)] == refs
    # one leaked grid or message per call would be >= 1000 x 2 KiB
    assert grown < 2 << 20, f"resident memory grew by {grown} bytes over 1,000 rounds"


# ---- errors carry their location ---------------------------------------------------------------


def test_format_errors_carry_path_line_byte(tmp_path):
    trunc = tmp_path / "t.stl"
    trunc.write_bytes(b"\0" * 80 + (5).to_bytes(4, "little") + b"\0" * 60)
    with pytest.raises(ebgeom.MeshFormatError) as e:
        ebgeom.read_mesh(trunc)
    assert e.value.path == str(trunc) and e.value.code
    assert e.value.byte > 0 and f"byte {e.value.byte}" in str(e.value)
    bad = tmp_path / "bad.ply"
    bad.write_text("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                   "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                   "end_header\n0 0 0\n1 0 0\n0 1 nope\n3 0 1 2\n")
    with pytest.raises(ebgeom.MeshFormatError) as e:
        ebgeom.read_mesh(bad)
    assert e.value.line == 12 and "line 12" in str(e.value)


# ---- stubs and docstrings ----------------------------------------------------------------------


def test_stubs_match_the_extension():
    stub = os.path.join(os.path.dirname(ebgeom.__file__), "_ebgeom.pyi")
    tree = ast.parse(open(stub).read())
    declared = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            declared[node.name] = {m.target.id if isinstance(m, ast.AnnAssign) else m.name
                                   for m in node.body
                                   if isinstance(m, (ast.AnnAssign, ast.FunctionDef))}
        elif isinstance(node, ast.FunctionDef):
            declared[node.name] = None
    actual = {n for n in dir(ebgeom._ebgeom) if not n.startswith("__")}
    assert set(declared) == actual
    for name, members in declared.items():
        obj = getattr(ebgeom._ebgeom, name)
        if members and not issubclass(obj, BaseException):  # exceptions: instance attributes
            missing = {m for m in members if m != "__init__" and not hasattr(obj, m)}
            assert not missing, (name, missing)
            real = {m for m in dir(obj) if not m.startswith("_")}
            assert real <= members, (name, real - members)


def public_callables():
    for name in ebgeom.__all__:
        obj = getattr(ebgeom, name)
        if callable(obj):
            yield name, obj
            if inspect.isclass(obj):
                for m, v in vars(obj).items():
                    if not m.startswith("_") and (callable(v) or isinstance(v, property)):
                        yield f"{name}.{m}", v


def test_every_public_name_has_a_docstring_and_examples():
    missing = [n for n, o in public_callables() if len((o.__doc__ or "").strip()) < 20]
    assert not missing, missing
    functions = [n for n, o in public_callables()
                 if "." not in n and n not in ("QueryResult", "MeshFormatError", "SceneError")]
    no_example = [n for n in functions if ">>>" not in getattr(ebgeom, n).__doc__]
    assert not no_example, no_example


def test_docstring_results_hold():
    """Examples written as `>>> expr   # array([values])` state the result: check each."""
    checked = 0
    for name, obj in public_callables():
        for line in (obj.__doc__ or "").splitlines():
            m = re.match(r"\s*>>> (.*?)\s+# array\((\[[^\]]*\])", line)
            if m:
                got = np.asarray(eval(m.group(1), {"ebgeom": ebgeom, "np": np}))
                np.testing.assert_allclose(got, ast.literal_eval(m.group(2)), atol=1e-6,
                                           err_msg=f"{name}: {m.group(1)}")
                checked += 1
    assert checked >= 7

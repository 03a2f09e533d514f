# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
"""Sparse narrow-band grids (sample_grid(..., sparse=True)) against the CLI's sparse .npz byte for
byte, the dense banded grid, a NumPy reconstruction from the tiles, and memory bounds."""

import gc
import os
import subprocess

import numpy as np
import pytest

import ebgeom
from conftest import icosphere

CASES = [
    (["--res", "37", "20", "11", "--band", "2"], {"res": (37, 20, 11), "band": 2}),
    (["--dx", "0.06", "--band", "1.5", "--nodes"], {"dx": 0.06, "band": 1.5, "nodes": True}),
    (["--res", "24", "--band", "3", "--box", "-1", "-0.5", "-1", "1.5", "1", "0.2"],
     {"res": 24, "band": 3, "box": (-1, -0.5, -1, 1.5, 1, 0.2)}),
]


def npz_members(path):
    with np.load(path) as z:
        return {k: z[k] for k in z.files}


def dense_from_tiles(g):
    """The dense (NZ, NY, NX) array rebuilt in NumPy from tiles, values and tile_code."""
    nx, ny, nz = g.dims
    tz, ty, tx = g.tile_code.shape
    out = np.empty((tz * 8, ty * 8, tx * 8), dtype=g.dtype)
    fill = np.where(g.tile_code == -1, -g.band, g.band).astype(g.dtype)
    out[...] = np.repeat(np.repeat(np.repeat(fill, 8, 0), 8, 1), 8, 2)
    for b, (x, y, z) in enumerate(g.tiles):
        assert g.tile_code[z, y, x] == b
        out[8 * z:8 * z + 8, 8 * y:8 * y + 8, 8 * x:8 * x + 8] = g.values[b]
    return out[:nz, :ny, :nx]


@pytest.fixture
def shifted_sphere(tmp_path):
    mp = tmp_path / "s.ply"
    v, f = icosphere(3)
    ebgeom.Mesh(v + [0.1, 0.2, 0.3], f).write(mp)
    return str(mp)


@pytest.mark.parametrize("precision", ["float", "double"])
@pytest.mark.parametrize("args,kw", CASES)
def test_sparse_npz_byte_for_byte_with_cli(tmp_path, cli, source_dir, shifted_sphere, precision,
                                           args, kw):
    for src in (shifted_sphere, os.path.join(source_dir, "examples/scenes/csg.json")):
        ref = tmp_path / "cli.npz"
        subprocess.run([cli, "sdf", src, "-o", str(ref), "--precision", precision, "-q"] + args,
                       check=True)
        sdf = (ebgeom.load_scene(src, precision) if src.endswith(".json")
               else ebgeom.MeshSdf(src, precision=precision))
        g = ebgeom.sample_grid(sdf, sparse=True, **kw)
        assert isinstance(g, ebgeom.SparseGrid)
        mine = tmp_path / "py.npz"
        g.save(mine)
        assert mine.read_bytes() == ref.read_bytes(), src
        # every member against the object's own arrays and geometry
        z = npz_members(ref)
        assert "blocks" not in z  # the kept tiles' member is "tiles" ("blocks" in 0.1)
        np.testing.assert_array_equal(z["tiles"], g.tiles)
        np.testing.assert_array_equal(z["values"], g.values)
        np.testing.assert_array_equal(z["tile_code"], g.tile_code)
        assert z["values"].dtype == g.values.dtype == g.dtype
        assert list(z["dims"]) == list(g.dims) and int(z["tile"]) == g.tile
        assert tuple(z["origin"]) == g.origin and tuple(z["spacing"]) == g.spacing
        assert tuple(map(tuple, z["box"])) == g.box
        assert float(z["band"]) == g.band and str(z["centering"]) == g.centering


@pytest.mark.parametrize("precision", ["float", "double"])
@pytest.mark.parametrize("args,kw", CASES)
def test_sparse_equals_dense_band(shifted_sphere, precision, args, kw):
    sdf = ebgeom.MeshSdf(shifted_sphere, precision=precision)
    g = ebgeom.sample_grid(sdf, sparse=True, **kw)
    dense = ebgeom.sample_grid(sdf, **kw)
    assert isinstance(dense, ebgeom.Grid)
    d = g.to_dense()
    assert d.values.dtype == dense.values.dtype and d.values.shape == dense.values.shape
    np.testing.assert_array_equal(d.values, dense.values)
    np.testing.assert_array_equal(dense_from_tiles(g), dense.values)
    assert (d.origin, d.spacing, d.box, d.centering) == (
        dense.origin, dense.spacing, dense.box, dense.centering)
    assert d.band == g.band == float(np.asarray(dense.band, dtype=g.dtype))  # the fill value
    # every sample closer than the band lies in a kept tile
    k, j, i = np.nonzero(np.abs(dense.values) < g.band)
    assert np.all(g.tile_code[k // 8, j // 8, i // 8] >= 0)
    assert set(np.unique(g.tile_code[g.tile_code < 0])) <= {-1, -2}


def test_sparse_winding_sign_equals_the_dense_band(tmp_path):
    v, f = icosphere(2)
    keep = ~np.all(v[f][:, :, 2] > 0.8, axis=1)  # open: auto picks a winding sign
    sdf = ebgeom.MeshSdf(ebgeom.Mesh(v, f[keep]))
    assert sdf.kind == "implicit"
    g = ebgeom.sample_grid(sdf, res=20, band=1, sparse=True)
    dense = ebgeom.sample_grid(sdf, res=20, band=1)
    # far tiles may be skipped (their winding sign proven), never one the band needs
    k, j, i = np.nonzero(np.abs(dense.values) < g.band)
    assert np.all(g.tile_code[k // 8, j // 8, i // 8] >= 0)
    np.testing.assert_array_equal(g.to_dense().values, dense.values)


def test_sparse_memory_proportional_to_kept_tiles():
    s = ebgeom.sphere(1.0).compile("float")
    res = 512
    dense_bytes = res ** 3 * 4

    def rss():
        with open("/proc/self/statm") as f:
            return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")

    gc.collect()
    before = rss()
    g = ebgeom.sample_grid(s, res=res, band=2, sparse=True, threads=2)
    grown = rss() - before
    m, tiles = len(g.tiles), g.tile_code.size
    assert tiles == (res // 8) ** 3
    expected = 4 * tiles + m * (12 + 512 * 4)
    assert expected <= g.memory_bytes <= expected * 1.01 + 4096
    assert g.memory_bytes < dense_bytes / 10
    assert grown < dense_bytes / 4, (grown, g.memory_bytes)
    # the arrays are views of the grid's own memory: no copy per access, read-only
    a, b = g.values, g.values
    assert np.shares_memory(a, b) and a.ctypes.data == b.ctypes.data
    assert not a.flags.writeable and not g.tiles.flags.writeable
    assert not g.tile_code.flags.writeable
    with pytest.raises(ValueError):
        a[0, 0, 0, 0] = 1
    # a view keeps the grid alive after the SparseGrid is gone
    ref = np.array(a[:2])
    del g, b
    gc.collect()
    np.testing.assert_array_equal(a[:2], ref)


def test_sparse_threads_invariance():
    sdf = ebgeom.MeshSdf(ebgeom.Mesh(*icosphere(3)), precision="double")
    ref = ebgeom.sample_grid(sdf, res=64, band=2, sparse=True, threads=1)
    for t in (2, 3, 0):
        g = ebgeom.sample_grid(sdf, res=64, band=2, sparse=True, threads=t)
        np.testing.assert_array_equal(g.tiles, ref.tiles)
        np.testing.assert_array_equal(g.values, ref.values)
        np.testing.assert_array_equal(g.tile_code, ref.tile_code)


def test_sparse_auto(monkeypatch):
    s = ebgeom.sphere(1.0).compile("float")
    dense_bytes = 40 * 40 * 40 * 4
    monkeypatch.setattr(ebgeom._ebgeom, "available_memory", lambda: 4 * dense_bytes)
    assert isinstance(ebgeom.sample_grid(s, res=40, band=2, sparse="auto"), ebgeom.Grid)
    monkeypatch.setattr(ebgeom._ebgeom, "available_memory", lambda: dense_bytes)
    g = ebgeom.sample_grid(s, res=40, band=2, sparse="auto")
    assert isinstance(g, ebgeom.SparseGrid)
    np.testing.assert_array_equal(g.to_dense().values,
                                  ebgeom.sample_grid(s, res=40, band=2).values)
    # without a band there is nothing sparse to keep
    assert isinstance(ebgeom.sample_grid(s, res=40, sparse="auto"), ebgeom.Grid)


def test_sparse_errors(tmp_path):
    s = ebgeom.sphere(1.0).compile("float")
    with pytest.raises(ValueError, match="band=W"):
        ebgeom.sample_grid(s, res=16, sparse=True)
    with pytest.raises(ValueError, match="sparse"):
        ebgeom.sample_grid(s, res=16, band=2, sparse="yes")
    g = ebgeom.sample_grid(s, res=16, band=2, sparse=True)
    with pytest.raises(ValueError, match="to_dense"):
        g.save(tmp_path / "g.vti")
    with pytest.raises(OSError):
        g.save(tmp_path / "missing" / "g.npz")
    assert not os.path.exists(tmp_path / "missing")
    # a tile table far beyond any memory is refused before anything is allocated
    with pytest.raises(MemoryError, match="tile table"):
        ebgeom.sample_grid(s, res=(1 << 21, 1 << 21, 1 << 20), band=1, sparse=True)
    with pytest.raises(MemoryError, match="sparse=True"):
        ebgeom.sample_grid(s, res=(1 << 21, 1 << 21, 1 << 20), band=1)


@pytest.mark.parametrize("precision", ["float", "double"])
def test_sparse_vdb_as_the_cli(tmp_path, cli, shifted_sphere, precision):
    g = ebgeom.sample_grid(ebgeom.MeshSdf(shifted_sphere, precision=precision), res=40, band=2,
                           sparse=True)
    if not ebgeom._ebgeom.vdb_available():
        with pytest.raises(ValueError, match=r"without OpenVDB.*-o OUT.vdb --band W"):
            g.save(tmp_path / "g.vdb")
        assert not (tmp_path / "g.vdb").exists()
        return
    subprocess.run([cli, "sdf", shifted_sphere, "-o", str(tmp_path / "cli.vdb"), "--res", "40",
                    "--band", "2", "--precision", precision, "-q"], check=True)
    g.save(tmp_path / "py.vdb")
    mine, ref = (tmp_path / "py.vdb").read_bytes(), (tmp_path / "cli.vdb").read_bytes()
    assert mine[:4] == b" BDV" and len(mine) == len(ref)
    # equal but for the file's UUID (36 characters after the 21-byte header)
    assert mine[:21] == ref[:21] and mine[57:] == ref[57:]


def test_dense_npz_byte_for_byte_with_cli(tmp_path, cli, shifted_sphere):
    for precision in ("float", "double"):
        ref = tmp_path / "cli.npz"
        subprocess.run([cli, "sdf", shifted_sphere, "-o", str(ref), "--res", "19", "--nodes",
                        "--precision", precision, "-q"], check=True)
        g = ebgeom.sample_grid(ebgeom.MeshSdf(shifted_sphere, precision=precision), res=19,
                               nodes=True)
        g.save(tmp_path / "py.npz")
        assert (tmp_path / "py.npz").read_bytes() == ref.read_bytes()
        z = npz_members(ref)
        np.testing.assert_array_equal(z["sdf"], g.values)
        assert tuple(z["origin"]) == g.origin and str(z["centering"]) == "node"


def test_sparse_blocks_is_a_deprecated_alias_of_tiles():
    g = ebgeom.sample_grid(ebgeom.sphere(1.0).compile("float"), res=24, band=2, sparse=True)
    assert g.tiles.shape == (len(g.tiles), 3) and len(g.tiles) > 0
    with pytest.warns(DeprecationWarning, match="SparseGrid.tiles"):
        old = g.blocks
    np.testing.assert_array_equal(old, g.tiles)

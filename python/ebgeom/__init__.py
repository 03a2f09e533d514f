# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
"""ebgeom: fast, exact signed distance fields (SDFs) of meshes and analytic shapes.

Sign convention: S < 0 inside, S > 0 outside, |S| is the Euclidean distance to the surface.

Quick start::

    >>> import numpy as np, ebgeom
    >>> mesh = ebgeom.read_mesh("bunny.obj")            # STL, PLY, OBJ, OFF, VTK, glTF
    >>> sdf = ebgeom.MeshSdf(mesh)                       # sign="auto", precision="float"
    >>> sdf([[0.0, 0.0, 0.0]])                           # (N, 3) points -> (N,) distances
    >>> grid = ebgeom.sample_grid(sdf, res=128)          # the CLI's `ebgeom sdf --res 128`
    >>> grid.values.shape, grid.origin, grid.spacing     # (NZ, NY, NX), sample (0,0,0), steps
    >>> grid.save("bunny.vti")                           # ParaView; also .npy and .raw

Queries release the GIL and run on all cores (``threads=0``); results never depend on the thread
count. See docs/python.md for the full guide.
"""

from __future__ import annotations

import itertools as _itertools
import json as _json
import math as _math
import os as _os
import warnings as _warnings
import weakref as _weakref
from dataclasses import dataclass as _dataclass
from typing import Any, Dict, Optional, Sequence, Tuple, Union

import numpy as np

from . import _ebgeom
from ._ebgeom import MeshFormatError, SceneError

__version__: str = _ebgeom.__version__

__all__ = [
    "__version__", "Mesh", "MeshFormatError", "SceneError", "read_mesh", "MeshSdf", "Scene",
    "Shape", "sphere", "box", "capsule", "cylinder", "cone", "torus", "plane", "mesh",
    "union", "intersection", "difference", "load_scene", "scene_from_json", "Grid",
    "SparseGrid", "sample_grid", "sample_points", "QueryResult", "SIGN_MODES",
]

#: The sign modes, spelled as the CLI's ``--sign``.
SIGN_MODES = ("auto", "pseudonormal", "winding", "fast-winding", "unsigned")

PathLike = Union[str, "_os.PathLike[str]"]

# ---- meshes ------------------------------------------------------------------------------------

Mesh = _ebgeom.Mesh
Mesh.__doc__ = """A polygon mesh (vertices in double precision).

    Mesh(vertices, faces)

``vertices``: array-like of shape (V, 3), any float or integer dtype (converted to float64).
``faces``: integer array of shape (F, K) (K >= 3 corners per face) or a sequence of index
sequences (faces of mixed sizes). Raises ValueError naming the offending row for NaN/inf
vertices, indices out of 0..V-1, faces with fewer than 3 corners, and wrong shapes; TypeError for
non-numeric dtypes.

Example::

    >>> m = ebgeom.Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
    ...                 [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    >>> m.info()["watertight"]
    True
"""


def _faces(self: Any) -> Union[np.ndarray, list]:
    """The faces: an (F, K) int64 array when every face has K corners, else a list of arrays."""
    idx, off = self.indices, self.offsets
    sizes = np.diff(off)
    if len(sizes) and np.all(sizes == sizes[0]):
        return idx.reshape(-1, int(sizes[0]))
    return [idx[off[i]:off[i + 1]] for i in range(len(sizes))]


Mesh.faces = property(_faces)
Mesh.validate = Mesh.info
Mesh.__repr__ = lambda self: (f"<ebgeom.Mesh {self.vertex_count} vertices, {self.face_count} "
                              f"faces{' from ' + self.path if self.path else ''}>")


def read_mesh(path: PathLike) -> Mesh:
    """Reads a mesh file: STL (ASCII/binary), PLY (ASCII/binary), OBJ, OFF (ASCII/binary) or
    legacy VTK POLYDATA, the format detected from the content; or glTF 2.0 (.gltf, .glb: every
    mesh instance of the scene with its node transforms applied, as the CLI reads it).

    Raises FileNotFoundError when the file does not exist, OSError when it cannot be read, and
    ``ebgeom.MeshFormatError`` (a ValueError) for a malformed file; its message names the file
    and the line (text) or byte offset (binary), and it carries ``path``, ``line``, ``byte`` and
    ``code`` attributes (a glTF error names the element at fault; line and byte are 0).

    >>> m = ebgeom.read_mesh("bunny.obj")
    """
    return _ebgeom.read_mesh(_os.fspath(path))


# ---- SDF objects -------------------------------------------------------------------------------


@_dataclass
class QueryResult:
    """What ``MeshSdf.query`` returns. Arrays have the SDF's precision except ``triangle``
    (int64, an index into ``MeshSdf.triangles``) and ``feature`` (uint8: 0 the face's interior,
    1-3 edges (v0v1, v1v2, v2v0), 4-6 vertices v0, v1, v2 of that triangle). ``normal`` is the
    unit gradient of S (pointing away from the surface outside, into it inside; the triangle's
    normal on the surface). Fields not asked for are None."""
    distance: np.ndarray
    closest: Optional[np.ndarray] = None
    normal: Optional[np.ndarray] = None
    triangle: Optional[np.ndarray] = None
    feature: Optional[np.ndarray] = None


class _SdfBase:
    """Shared behaviour of ``MeshSdf`` and ``Scene``: evaluation, bounds, grids."""

    _impl: Any

    def __call__(self, points: Any, *, threads: int = 0, out: Optional[np.ndarray] = None
                 ) -> np.ndarray:
        """Signed distances at ``points`` (array-like (N, 3), or one point (3,)).

        Points in the SDF's dtype (float32 for precision="float", float64 for "double") and C
        order are read in place (no copy); any other float/int dtype, Fortran order or
        non-contiguous view is converted once. Returns a new (N,) array of the SDF's dtype, or
        fills ``out`` (C-contiguous, that dtype, N values) and returns it. The GIL is released;
        ``threads=0`` uses every core."""
        return self._impl.eval(points, threads, out)

    @property
    def precision(self) -> str:
        """"float" or "double": the precision of the computation and of the results."""
        return self._impl.precision

    @property
    def dtype(self) -> np.dtype:
        """numpy.float32 or numpy.float64 (see ``precision``)."""
        return np.dtype(np.float64 if self._impl.precision == "double" else np.float32)

    @property
    def kind(self) -> str:
        """"exact", "bound" or "implicit" (docs/shapes.md#concepts)."""
        return self._impl.kind

    def bounds(self) -> Tuple[Tuple[float, float, float], Tuple[float, float, float]]:
        """((x0, y0, z0), (x1, y1, z1)): the bounding box of the surface (infinite for planes)."""
        return self._impl.bounds()


class MeshSdf(_SdfBase):
    """The exact signed distance to a triangle mesh (polygons are fan-triangulated).

    MeshSdf(mesh, sign="auto", precision="float")

    ``mesh``: an ``ebgeom.Mesh`` or a path to a mesh file. ``sign`` (as the CLI's ``--sign``):
    "pseudonormal" (exact on watertight oriented meshes), "winding" (exact generalized winding
    number; robust to holes), "fast-winding" (its fast approximation), "unsigned" or "auto"
    (pseudonormal on closed, manifold, consistently oriented meshes, fast-winding otherwise;
    ``sign_mode``/``sign_reason`` say what it chose and why). ``precision``: "float" or
    "double" (the computation and the result dtype).

    >>> sdf = ebgeom.MeshSdf(ebgeom.read_mesh("bunny.obj"))
    >>> d = sdf(np.random.rand(1000, 3))                       # (1000,) float32
    >>> q = sdf.query(points)                                  # + closest points, normals
    >>> sdf.sign_mode, sdf.sign_reason
    ('pseudonormal', 'closed, manifold and consistently oriented')
    """

    def __init__(self, mesh: Union[Mesh, PathLike], sign: str = "auto", precision: str = "float"):
        if not isinstance(mesh, Mesh):
            mesh = read_mesh(mesh)
        self.mesh = mesh
        self._impl = _ebgeom.mesh_sdf(mesh, sign, precision)

    @property
    def sign_mode(self) -> str:
        """The sign mode in use (never "auto")."""
        return self._impl.sign_info["mode"]

    @property
    def sign_requested(self) -> str:
        """The sign mode asked for."""
        return self._impl.sign_info["requested"]

    @property
    def sign_reason(self) -> str:
        """Why ``sign_mode`` was chosen ("requested" unless sign="auto")."""
        return self._impl.sign_info["reason"]

    @property
    def triangles(self) -> np.ndarray:
        """(T, 3) int64 vertex indices of the triangles the SDF uses (``query``'s ids)."""
        return self._impl.triangle_mesh()[1]

    @property
    def vertices(self) -> np.ndarray:
        """(V, 3) vertices of those triangles, in the SDF's precision."""
        return self._impl.triangle_mesh()[0]

    def query(self, points: Any, closest: bool = True, normals: bool = True, faces: bool = True,
              *, threads: int = 0) -> QueryResult:
        """Distances plus closest surface points, normals (unit gradient of S), the id of the
        closest triangle and its feature, as ``ebgeom query`` computes them. See QueryResult."""
        r = self._impl.query(points, threads)
        return QueryResult(r["distance"], r["closest"] if closest else None,
                           r["normal"] if normals else None, r["triangle"] if faces else None,
                           r["feature"] if faces else None)

    def __repr__(self) -> str:
        return (f"<ebgeom.MeshSdf {self._impl.triangle_count} triangles, sign {self.sign_mode}, "
                f"{self.precision}>")


class Scene(_SdfBase):
    """A compiled scene: analytic shapes, meshes, transforms and CSG evaluated in C++ (no Python
    call per point). Made by ``load_scene``, ``scene_from_json`` or ``Shape.compile``; the scene
    format is docs/scene-format.md (the CLI's).

    >>> scene = (ebgeom.sphere(1.0) - ebgeom.box(size=(1, 1, 3))).compile("double")
    >>> scene([[0, 0, 0], [2, 0, 0]]), scene.kind, scene.bounds()
    """

    def __init__(self, impl: Any, source: Any = None):
        self._impl = impl
        self.source = source

    @property
    def triangle_count(self) -> int:
        """Triangles of the meshes in the scene (0 for analytic shapes only)."""
        return self._impl.triangle_count

    def __repr__(self) -> str:
        return f"<ebgeom.Scene {self.kind}, {self.precision}>"


def load_scene(path: PathLike, precision: str = "float") -> Scene:
    """Reads and compiles a JSON scene file (docs/scene-format.md), with the same meaning as
    ``ebgeom sdf scene.json``; relative mesh paths are relative to the file. Raises
    ``ebgeom.SceneError`` (a ValueError) naming the file, line/column or the JSON pointer of the
    bad value; FileNotFoundError when the file does not exist.

    >>> scene = ebgeom.load_scene("examples/scenes/csg.json", precision="double")
    >>> scene([[0, 0, 0]]), ebgeom.sample_grid(scene, res=64).values.shape
    """
    p = _os.fspath(path)
    if not _os.path.exists(p):
        raise FileNotFoundError(2, "No such file or directory", p)
    return Scene(_ebgeom.compile_scene("", p, precision, True), p)


def scene_from_json(scene: Union[str, Dict[str, Any]], precision: str = "float",
                    base_dir: Optional[PathLike] = None) -> Scene:
    """Compiles a scene given as a dict or a JSON string; relative mesh paths are relative to
    ``base_dir`` (default: the current directory).

    >>> ebgeom.scene_from_json({"type": "sphere", "radius": 1.0})([[2, 0, 0]])   # array([1.])
    """
    text = scene if isinstance(scene, str) else _json.dumps(scene)
    label = _os.path.join(_os.fspath(base_dir), "<scene>") if base_dir is not None else "<scene>"
    return Scene(_ebgeom.compile_scene(text, label, precision, False), scene)


# ---- shapes and CSG ----------------------------------------------------------------------------


def _vec(v: Any, name: str) -> list:
    a = np.asarray(v, dtype=float).reshape(-1)
    if a.shape != (3,) or not np.all(np.isfinite(a)):
        raise ValueError(f"{name}: expected 3 finite numbers, got {v!r}")
    return [float(x) for x in a]


class Shape:
    """An analytic shape or a CSG tree of shapes (a scene node, docs/scene-format.md).

    Compose with ``a | b`` (union), ``a & b`` (intersection), ``a - b`` (difference), or
    ``ebgeom.union(a, b, smooth=0.1)``; transform with ``translate``, ``rotate``, ``scale``;
    ``offset(r)`` grows (r > 0) or shrinks, ``shell(t)`` hollows. Shapes are immutable. Calling a
    shape evaluates it (compiled once per precision, in C++)::

        >>> s = ebgeom.sphere(1.0) - ebgeom.box(size=(1, 1, 3)).rotate((0, 0, 1), 45)
        >>> s([[0, 0, 0], [2, 0, 0]])
        >>> grid = ebgeom.sample_grid(s, res=64)
    """

    def __init__(self, node: Dict[str, Any], keep: Tuple[Any, ...] = ()):
        self.node = node
        self._keep = keep  # (ref, Mesh) of the in-memory meshes the node names (see ``mesh``)
        self._compiled: Dict[str, Scene] = {}

    def to_json(self) -> Dict[str, Any]:
        """The scene file content (``{"version": 1, "root": node}``)."""
        return {"version": 1, "root": self.node}

    def compile(self, precision: str = "float") -> Scene:
        """The compiled scene (cached)."""
        if precision not in self._compiled:
            doc = self.to_json()
            self._compiled[precision] = Scene(
                _ebgeom.compile_scene(_json.dumps(doc), "<scene>", precision, False,
                                      dict(self._keep)), doc)
        return self._compiled[precision]

    def __call__(self, points: Any, *, threads: int = 0, precision: str = "double",
                 out: Optional[np.ndarray] = None) -> np.ndarray:
        """S at ``points`` (N, 3), computed in ``precision`` (default double) by the compiled
        scene; see ``MeshSdf.__call__`` for arrays, ``threads`` and ``out``."""
        return self.compile(precision)(points, threads=threads, out=out)

    def bounds(self) -> Tuple[Tuple[float, float, float], Tuple[float, float, float]]:
        """((x0, y0, z0), (x1, y1, z1)): a box holding the surface (infinite for planes)."""
        return self.compile("double").bounds()

    def _with(self, **keys: Any) -> "Shape":
        if any(k in self.node for k in ("translate", "rotate", "scale", "offset", "shell")):
            node: Dict[str, Any] = {"type": "transform", "child": self.node}
        else:
            node = dict(self.node)
        node.update(keys)
        return Shape(node, self._keep)

    def translate(self, v: Sequence[float]) -> "Shape":
        """The shape moved by ``v``: ``ebgeom.sphere(1).translate((0, 0, 2))``."""
        return self._with(translate=_vec(v, "translate"))

    def rotate(self, axis: Sequence[float], degrees: float) -> "Shape":
        """Rotation by ``degrees`` about ``axis`` (through the origin, right-handed)."""
        return self._with(rotate={"axis": _vec(axis, "axis"), "degrees": float(degrees)})

    def scale(self, s: float) -> "Shape":
        """Uniform scaling (s > 0; distances scale with it, so the SDF stays exact)."""
        return self._with(scale=float(s))

    def offset(self, r: float) -> "Shape":
        """S - r: the surface moved outwards by ``r`` (inwards for r < 0), rounding edges."""
        return self._with(offset=float(r))

    def shell(self, t: float) -> "Shape":
        """|S| - t: a hollow shell of thickness 2 t around the surface."""
        return self._with(shell=float(t))

    def __or__(self, other: Any) -> "Shape":
        return union(self, other)

    def __and__(self, other: Any) -> "Shape":
        return intersection(self, other)

    def __sub__(self, other: Any) -> "Shape":
        return difference(self, other)

    # mesh | shape, mesh & shape, mesh - shape with an ebgeom.Mesh or MeshSdf on the left
    def __ror__(self, other: Any) -> "Shape":
        return union(other, self)

    def __rand__(self, other: Any) -> "Shape":
        return intersection(other, self)

    def __rsub__(self, other: Any) -> "Shape":
        return difference(other, self)

    def __repr__(self) -> str:
        return f"ebgeom.Shape({_json.dumps(self.node)})"


def sphere(radius: float, center: Sequence[float] = (0, 0, 0)) -> Shape:
    """A sphere of ``radius`` around ``center`` (exact SDF).

    >>> ebgeom.sphere(1.0, center=(0, 0, 1))([[0, 0, 0]])   # array([0.])
    """
    return Shape({"type": "sphere", "center": _vec(center, "center"), "radius": float(radius)})


def box(size: Optional[Sequence[float]] = None, center: Sequence[float] = (0, 0, 0), *,
        half_size: Optional[Sequence[float]] = None, rounding: float = 0.0) -> Shape:
    """An axis-aligned box of full edge lengths ``size`` (or ``half_size``) around ``center``,
    its edges rounded by ``rounding`` (exact SDF).

    >>> ebgeom.box(size=(2, 1, 1), rounding=0.1)([[0, 0, 0]])
    """
    n: Dict[str, Any] = {"type": "box", "center": _vec(center, "center")}
    if (size is None) == (half_size is None):
        raise ValueError("box: give exactly one of size or half_size")
    if size is not None:
        n["size"] = _vec(size, "size")
    else:
        n["half_size"] = _vec(half_size, "half_size")
    if rounding:
        n["rounding"] = float(rounding)
    return Shape(n)


def capsule(a: Sequence[float], b: Sequence[float], radius: float) -> Shape:
    """The points within ``radius`` of the segment from ``a`` to ``b`` (exact SDF).

    >>> ebgeom.capsule((0, 0, 0), (0, 0, 1), 0.2)([[1, 0, 0.5]])   # array([0.8])
    """
    return Shape({"type": "capsule", "a": _vec(a, "a"), "b": _vec(b, "b"),
                  "radius": float(radius)})


def cylinder(a: Sequence[float], b: Sequence[float], radius: float) -> Shape:
    """A capped cylinder of ``radius`` whose axis runs from ``a`` to ``b`` (exact SDF).

    >>> ebgeom.cylinder((0, 0, -1), (0, 0, 1), 0.5)([[0, 0, 0]])   # array([-0.5])
    """
    return Shape({"type": "cylinder", "a": _vec(a, "a"), "b": _vec(b, "b"),
                  "radius": float(radius)})


def cone(a: Sequence[float], b: Sequence[float], radius_a: float, radius_b: float) -> Shape:
    """A capped cone from ``a`` (radius ``radius_a``) to ``b`` (``radius_b``); exact SDF.

    >>> ebgeom.cone((0, 0, 0), (0, 0, 1), 0.5, 0.0)([[0, 0, -1]])   # array([1.])
    """
    return Shape({"type": "cone", "a": _vec(a, "a"), "b": _vec(b, "b"),
                  "radius_a": float(radius_a), "radius_b": float(radius_b)})


def torus(major_radius: float, minor_radius: float, center: Sequence[float] = (0, 0, 0)) -> Shape:
    """A torus around the z axis through ``center``: the points within ``minor_radius`` of the
    circle of ``major_radius`` (exact SDF).

    >>> ebgeom.torus(1.0, 0.25)([[1, 0, 0]])                       # array([-0.25])
    """
    return Shape({"type": "torus", "center": _vec(center, "center"),
                  "major_radius": float(major_radius), "minor_radius": float(minor_radius)})


def plane(normal: Sequence[float], point: Sequence[float] = (0, 0, 0)) -> Shape:
    """The half-space behind the plane through ``point`` (inside where (x - point)·normal < 0;
    an unbounded shape: intersect it with a bounded one before sampling a grid).

    >>> (ebgeom.sphere(1.0) & ebgeom.plane((0, 0, 1)))([[0, 0, 0.5]])   # array([0.5])
    """
    return Shape({"type": "plane", "normal": _vec(normal, "normal"), "point": _vec(point, "point")})


# The reference ("ref" in a mesh node) of each in-memory mesh used in a shape: one per mesh.
_mesh_refs: "_weakref.WeakKeyDictionary[Any, str]" = _weakref.WeakKeyDictionary()
_mesh_ref_count = _itertools.count(1)


def mesh(source: Union[PathLike, Mesh, "MeshSdf"], sign: Optional[str] = None) -> Shape:
    """A mesh as a scene node (its exact SDF with ``sign`` mode, default "auto"), for CSG with
    other shapes: a mesh file (its path resolved now, relative to the current directory), an
    ``ebgeom.Mesh`` (from a file or from arrays) or a ``MeshSdf`` (its mesh, and its sign mode
    unless ``sign`` is given). ``union``, ``intersection``, ``difference`` and the operators
    accept a ``Mesh`` or ``MeshSdf`` directly. The SDF of the node is ``MeshSdf(mesh, sign)``'s,
    value for value.

    A mesh built from arrays reaches the scene compiler in memory (no file is written): its node
    names it by reference (``{"type": "mesh", "ref": "mesh-1"}``), which the shapes that contain
    it resolve when they compile. A scene file from ``to_json()`` therefore holds only the
    reference; write the mesh (``mesh.write``) and use ``ebgeom.mesh(path)`` for a scene file that
    the command-line tool reads.

    >>> part = ebgeom.mesh("part.stl") - ebgeom.cylinder((0, 0, -1), (0, 0, 1), 0.1)
    >>> blob = ebgeom.Mesh(vertices, faces) | ebgeom.sphere(0.5)
    """
    keep: Tuple[Any, ...] = ()
    if isinstance(source, MeshSdf):
        sign = source.sign_requested if sign is None else sign
        source = source.mesh
    if isinstance(source, Mesh):
        if source.path:
            path = _os.path.abspath(source.path)  # read as the file's own numbers, as MeshSdf
        else:
            ref = _mesh_refs.get(source)
            if ref is None:
                ref = _mesh_refs[source] = f"mesh-{next(_mesh_ref_count)}"
            return Shape({"type": "mesh", "ref": ref, "sign": "auto" if sign is None else sign},
                         ((ref, source),))
    else:
        path = _os.path.abspath(_os.fspath(source))
    return Shape({"type": "mesh", "path": path, "sign": "auto" if sign is None else sign}, keep)


def _as_shape(s: Any, kind: str) -> Shape:
    if isinstance(s, Shape):
        return s
    if isinstance(s, (Mesh, MeshSdf)):
        return mesh(s)
    raise TypeError(f"{kind}: expected ebgeom shapes, meshes or mesh SDFs, got {type(s).__name__}")


def _csg(kind: str, shapes: Sequence[Any], smooth: float) -> Shape:
    if len(shapes) == 1 and not isinstance(shapes[0], (Shape, Mesh, MeshSdf)):
        shapes = tuple(shapes[0])
    if not shapes:
        raise ValueError(f"{kind}: needs at least one shape")
    parts = [_as_shape(s, kind) for s in shapes]
    n: Dict[str, Any] = {"type": kind, "children": [s.node for s in parts]}
    if smooth:
        n["smooth"] = float(smooth)
    return Shape(n, tuple(k for s in parts for k in s._keep))


def union(*shapes: Union[Shape, Mesh, MeshSdf], smooth: float = 0.0) -> Shape:
    """The union of shapes (``a | b``); ``smooth`` > 0 blends them over that distance
    (polynomial smooth minimum). Meshes (``Mesh``, ``MeshSdf``) take part as ``mesh(m)``.

    >>> blob = ebgeom.union(ebgeom.sphere(1), ebgeom.sphere(1, (1.5, 0, 0)), smooth=0.3)
    """
    return _csg("union", shapes, smooth)


def intersection(*shapes: Union[Shape, Mesh, MeshSdf], smooth: float = 0.0) -> Shape:
    """The intersection of shapes (``a & b``); ``smooth`` > 0 blends the edges.

    >>> lens = ebgeom.intersection(ebgeom.sphere(1, (0, 0, -0.5)), ebgeom.sphere(1, (0, 0, 0.5)))
    """
    return _csg("intersection", shapes, smooth)


def difference(*shapes: Union[Shape, Mesh, MeshSdf], smooth: float = 0.0) -> Shape:
    """The first shape minus the others (``a - b``); ``smooth`` > 0 blends the edges.

    >>> hole = ebgeom.cylinder((0, 0, -1), (0, 0, 1), 0.4)
    >>> nut = ebgeom.difference(ebgeom.box(size=(2, 2, 0.5)), hole)
    """
    return _csg("difference", shapes, smooth)


# ---- grids -------------------------------------------------------------------------------------


@_dataclass
class Grid:
    """A dense SDF grid. ``values[k, j, i]`` is S at ``origin + (i, j, k) * spacing`` (shape
    (NZ, NY, NX), x fastest: the CLI's .npy layout). ``box`` is ((x0, y0, z0), (x1, y1, z1)),
    ``centering`` "cell" (samples at cell centres) or "node" (samples on the box faces too),
    ``band`` the narrow band half-width in length units (0: exact everywhere).

    >>> g = ebgeom.sample_grid(ebgeom.sphere(1.0), res=(32, 32, 16))
    >>> g.values.shape, g.dims, g.origin, g.spacing       # (16, 32, 32), (32, 32, 16), ...
    >>> g.save("sphere.vti")
    """
    values: np.ndarray
    origin: Tuple[float, float, float]
    spacing: Tuple[float, float, float]
    box: Tuple[Tuple[float, float, float], Tuple[float, float, float]]
    centering: str
    band: float = 0.0

    @property
    def dims(self) -> Tuple[int, int, int]:
        """(NX, NY, NZ): samples along x, y, z (``values.shape`` reversed)."""
        nz, ny, nx = self.values.shape
        return (nx, ny, nz)

    def points(self) -> np.ndarray:
        """The sample positions, shape (NZ, NY, NX, 3) (computed as origin + index * spacing)."""
        nz, ny, nx = self.values.shape
        dt = self.values.dtype
        o = np.asarray(self.origin, dtype=dt)
        h = np.asarray(self.spacing, dtype=dt)
        x = o[0] + np.arange(nx, dtype=dt) * h[0]
        y = o[1] + np.arange(ny, dtype=dt) * h[1]
        z = o[2] + np.arange(nz, dtype=dt) * h[2]
        zz, yy, xx = np.meshgrid(z, y, x, indexing="ij")
        return np.stack([xx, yy, zz], axis=-1)

    def save(self, path: PathLike) -> None:
        """Writes the grid with the CLI's writers, by extension: .vti (ParaView ImageData), .npy
        (shape (NZ, NY, NX)), .raw (+ a .json sidecar with dims, origin, spacing) or .npz (the
        dense .npz of ``ebgeom sdf -o OUT.npz``: arrays sdf, origin, spacing, box, centering).

        >>> ebgeom.sample_grid(ebgeom.sphere(1.0), res=32).save("sphere.vti")
        """
        lo, hi = self.box
        _ebgeom.save_grid(_os.fspath(path), self.values, [*lo, *hi], self.centering)


class SparseGrid:
    """A narrow band stored by 8^3 tiles, for grids whose dense array would not fit: what
    ``sample_grid(..., band=W, sparse=True)`` returns, and the content of the CLI's sparse
    ``.npz`` (``ebgeom sdf -o OUT.npz --band W``) as arrays of the same names. Memory: the kept
    tiles (512 values and 12 bytes each) plus 4 bytes per tile of the whole grid
    (``memory_bytes``).

    - ``tiles`` (M, 3) uint32: tile coordinates (tx, ty, tz) of kept tile b, whose samples are
      (8 tx + x, 8 ty + y, 8 tz + z); ``blocks``, its name in 0.1, is a deprecated alias;
    - ``values`` (M, 8, 8, 8): ``values[b, z, y, x]`` is S at that sample, exactly the dense
      grid's value; local samples past the grid's last sample hold +band;
    - ``tile_code`` (TZ, TY, TX) int32: the index b of each kept tile, or -1 (a skipped tile
      inside the surface: -band everywhere) or -2 (skipped, outside: +band);
    - ``origin``, ``spacing``, ``box``, ``centering``, ``band``, ``dims``: as in ``Grid``.

    The arrays are read-only views of the C++ grid (no copy; copy them to modify).
    ``to_dense()`` gives the ``Grid`` that ``sample_grid(..., band=W)`` gives; ``save(path)``
    writes .npz (the CLI's file, byte for byte) or .vdb (the CLI's OpenVDB level set).

    >>> band = ebgeom.sample_grid(sdf, res=2048, band=3, sparse=True)
    >>> band.tiles.shape, band.memory_bytes           # kept tiles, bytes held
    >>> band.save("bunny_band.npz")                   # = ebgeom sdf bunny.obj --res 2048 --band 3
    """

    #: Samples per tile edge.
    tile: int = 8

    def __init__(self, impl: Any, origin: Tuple[float, float, float],
                 spacing: Tuple[float, float, float],
                 box: Tuple[Tuple[float, float, float], Tuple[float, float, float]],
                 dims: Tuple[int, int, int], centering: str, band: float):
        self._impl = impl
        self.origin, self.spacing, self.box = origin, spacing, box
        self.dims, self.centering, self.band = dims, centering, band

    @property
    def tiles(self) -> np.ndarray:
        """(M, 3) uint32 tile coordinates (tx, ty, tz) of the kept tiles, in Morton order."""
        return self._impl.tiles

    @property
    def blocks(self) -> np.ndarray:
        """Deprecated name of ``tiles`` (the .npz member is ``tiles`` too)."""
        _warnings.warn("SparseGrid.blocks is deprecated; use SparseGrid.tiles",
                       DeprecationWarning, stacklevel=2)
        return self._impl.tiles

    @property
    def values(self) -> np.ndarray:
        """(M, 8, 8, 8) values of the kept tiles: ``values[b, z, y, x]``."""
        return self._impl.values

    @property
    def tile_code(self) -> np.ndarray:
        """(TZ, TY, TX) int32: kept tile index, -1 (skipped, inside) or -2 (skipped, outside)."""
        return self._impl.tile_code

    @property
    def dtype(self) -> np.dtype:
        """numpy.float32 or numpy.float64: the dtype of ``values``."""
        return np.dtype(np.float64 if self._impl.precision == "double" else np.float32)

    @property
    def memory_bytes(self) -> int:
        """Bytes the grid holds (tile table, kept tiles' coordinates and values)."""
        return self._impl.memory_bytes

    def to_dense(self) -> Grid:
        """The dense ``Grid``: kept tiles' values, -band/+band in skipped tiles inside/outside
        (equal to ``sample_grid`` with the same options and ``sparse=False``, except on an open
        mesh with sign="pseudonormal", where a skipped tile takes the sign at its centre). Raises
        MemoryError when the dense array does not fit."""
        return Grid(self._impl.to_dense(), self.origin, self.spacing, self.box, self.centering,
                    self.band)

    def save(self, path: PathLike) -> None:
        """Writes the band by extension as ``ebgeom sdf -o OUT --band W`` does: .npz (the CLI's
        sparse .npz, byte for byte; read it with ``numpy.load``) or .vdb (an OpenVDB level set,
        when the package was built with OpenVDB: ``ebgeom._ebgeom.vdb_available()``). For .vti,
        .npy or .raw, ``to_dense().save(path)``."""
        self._impl.save(_os.fspath(path))

    def __repr__(self) -> str:
        nx, ny, nz = self.dims
        return (f"<ebgeom.SparseGrid {nx} x {ny} x {nz}, {len(self.tiles)} of "
                f"{self.tile_code.size} tiles kept, band {self.band:g}>")


def _as_sdf(sdf: Any) -> Any:
    if isinstance(sdf, Shape):
        sdf = sdf.compile("float")
    if not isinstance(sdf, _SdfBase):
        raise TypeError(f"expected an ebgeom MeshSdf, Scene or Shape, got {type(sdf).__name__}")
    return sdf._impl


def sample_grid(sdf: Union[MeshSdf, Scene, Shape], box: Optional[Sequence[float]] = None,
                res: Union[None, int, Sequence[int]] = None, dx: Optional[float] = None,
                pad: float = 0.1, band: Optional[float] = None, nodes: bool = False,
                threads: int = 0, sparse: Union[bool, str] = False
                ) -> Union[Grid, SparseGrid]:
    """Samples ``sdf`` on a regular grid, exactly as ``ebgeom sdf`` does with the same options
    (same sample positions, same values bit for bit).

    ``box``: (x0, y0, z0, x1, y1, z1) or ((x0, y0, z0), (x1, y1, z1)); default the bounds grown
    by ``pad`` (a fraction of the extent per side). ``res``: N or (NX, NY, NZ) samples (default
    64); or ``dx``: cubic cells of that size (the box grows to a whole number of cells).
    ``band``: narrow band of that many times the largest spacing: exact inside, ±band outside.
    ``nodes``: node-centred samples (on the box faces) instead of cell centres. A Shape is
    sampled in float (compile it with ``precision="double"`` for double).

    ``sparse``: False (default) returns a dense ``Grid``; True returns a ``SparseGrid`` holding
    only the 8^3 tiles the narrow band needs (needs ``band``; ``ebgeom sdf -o OUT.npz --band W``),
    for resolutions whose dense array would not fit; "auto" returns a ``SparseGrid`` when a band
    is given and the dense array would take more than half of the available memory, else a
    ``Grid``. A dense grid that does not fit raises MemoryError.

    >>> g = ebgeom.sample_grid(sdf, res=128)                          # Grid, values (128,)*3
    >>> b = ebgeom.sample_grid(sdf, res=2048, band=3, sparse=True)    # SparseGrid
    """
    impl = _as_sdf(sdf)
    b: list = []
    if box is not None:
        b = [float(x) for x in np.asarray(box, dtype=float).reshape(-1)]
    r: list = [] if res is None else ([int(res)] if np.ndim(res) == 0 else [int(x) for x in res])
    h = 0.0 if dx is None else float(dx)
    w = 0.0 if band is None else float(band)
    if sparse == "auto":
        _, dense_bytes = _ebgeom.grid_size(impl, b, r, h, float(pad), bool(nodes))
        avail = _ebgeom.available_memory()
        sparse = w > 0 and avail > 0 and dense_bytes > avail // 2
    elif not isinstance(sparse, (bool, np.bool_)):
        raise ValueError(f"sparse: expected True, False or 'auto', got {sparse!r}")
    if sparse:
        d = _ebgeom.sample_sparse(impl, b, r, h, float(pad), w, bool(nodes), int(threads))
        return SparseGrid(d["grid"], d["origin"], d["spacing"], d["box"], d["dims"],
                          d["centering"], d["band"])
    d = _ebgeom.sample_grid(impl, b, r, h, float(pad), w, bool(nodes), int(threads))
    return Grid(d["values"], d["origin"], d["spacing"], d["box"], d["centering"], d["band"])


# ---- training samples --------------------------------------------------------------------------


def sample_points(sdf: MeshSdf, n: int, near_surface: float = 0.9, sigma: Optional[float] = None,
                  seed: Optional[int] = None, pad: float = 0.1, threads: int = 0
                  ) -> Tuple[np.ndarray, np.ndarray]:
    """Points and their exact signed distances, for training (DeepSDF style).

    ``round(n * near_surface)`` points are area-uniform on the mesh's triangles, displaced by
    Gaussian noise of standard deviation ``sigma`` (default 1% of the bounding-box diagonal);
    the others are uniform in the bounding box grown by ``pad`` per side. The same ``seed`` gives
    the same points (NumPy's default generator). Returns (points (n, 3), distances (n,)) in the
    SDF's precision; the distances are ``sdf(points)``.

    >>> sdf = ebgeom.MeshSdf("scan.ply", sign="winding", precision="double")
    >>> pts, d = ebgeom.sample_points(sdf, 100_000, near_surface=0.95, sigma=0.005, seed=0)
    """
    if not isinstance(sdf, MeshSdf):
        raise TypeError("sample_points: expected an ebgeom.MeshSdf")
    n = int(n)
    if n < 0:
        raise ValueError("n: expected a count >= 0")
    if not 0.0 <= near_surface <= 1.0:
        raise ValueError("near_surface: expected a fraction in [0, 1]")
    rng = np.random.default_rng(seed)
    v = np.asarray(sdf.vertices, dtype=np.float64)
    t = sdf.triangles
    lo, hi = (np.asarray(x, dtype=np.float64) for x in sdf.bounds())
    diag = float(np.linalg.norm(hi - lo))
    if sigma is None:
        sigma = 0.01 * diag
    if not (sigma >= 0 and _math.isfinite(sigma)):
        raise ValueError("sigma: expected a number >= 0")
    n_near = int(round(n * near_surface))
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    if n_near and not area.sum() > 0:
        raise ValueError("sample_points: the mesh has no area to sample near")
    pts = np.empty((n, 3), dtype=np.float64)
    if n_near:
        tri = rng.choice(len(t), size=n_near, p=area / area.sum())
        u, w = rng.random(n_near), rng.random(n_near)
        flip = u + w > 1
        u[flip], w[flip] = 1 - u[flip], 1 - w[flip]
        pts[:n_near] = (a[tri] + (b[tri] - a[tri]) * u[:, None] + (c[tri] - a[tri]) * w[:, None]
                        + rng.normal(0.0, sigma, size=(n_near, 3)))
    ext = hi - lo
    glo, ghi = lo - pad * ext, hi + pad * ext
    pts[n_near:] = glo + (ghi - glo) * rng.random((n - n_near, 3))
    pts = pts.astype(sdf.dtype, copy=False)
    return pts, sdf(pts, threads=threads)

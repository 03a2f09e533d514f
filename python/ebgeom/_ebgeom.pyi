# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
# Type stubs of the C++ extension (the public API is the `ebgeom` package, python/ebgeom).
import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

__version__: str

class MeshFormatError(ValueError):
    path: str
    line: int
    byte: int
    code: str

class SceneError(ValueError): ...

class Mesh:
    def __init__(self, vertices: Any, faces: Any) -> None: ...
    path: str
    vertex_count: int
    face_count: int
    triangle_count: int
    vertices: np.ndarray
    indices: np.ndarray
    offsets: np.ndarray
    faces: Union[np.ndarray, List[np.ndarray]]
    def info(self) -> Dict[str, Any]: ...
    def validate(self) -> Dict[str, Any]: ...
    def write(self, path: Union[str, os.PathLike], ascii: bool = ...) -> None: ...

class Sdf:
    precision: str
    is_mesh: bool
    sign_info: Dict[str, Optional[str]]
    kind: str
    triangle_count: int
    def bounds(self) -> Tuple[Tuple[float, float, float], Tuple[float, float, float]]: ...
    def triangle_mesh(self) -> Tuple[np.ndarray, np.ndarray]: ...
    def eval(self, points: Any, threads: int = ..., out: Optional[np.ndarray] = ...) -> np.ndarray: ...
    def query(self, points: Any, threads: int = ...) -> Dict[str, np.ndarray]: ...

def read_mesh(path: str) -> Mesh: ...
def mesh_sdf(mesh: Mesh, sign: str = ..., precision: str = ...) -> Sdf: ...
def compile_scene(json: str, file: str, precision: str = ..., from_file: bool = ...) -> Sdf: ...
def sample_grid(sdf: Sdf, box: Sequence[float], res: Sequence[int], dx: float, pad: float,
                band: float, nodes: bool, threads: int) -> Dict[str, Any]: ...
def save_grid(path: str, values: np.ndarray, box: Sequence[float], centering: str) -> None: ...

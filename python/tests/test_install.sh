#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
# `pip install` of the source tree into a fresh venv, offline, with Debian's packages only
# (python3-venv python3-pip python3-setuptools python3-numpy pybind11-dev), then an import and a
# query from outside the source tree. Usage: test_install.sh PYTHON SOURCE_DIR WORK_DIR
set -eu
py=$1 src=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
# A copy of the tracked files, so that the install never writes into the source tree.
git -C "$src" ls-files -z --cached --others --exclude-standard |
  (cd "$src" && xargs -0 tar cf -) | (cd "$work" && mkdir src && cd src && tar xf -)
"$py" -m venv --system-site-packages "$work/venv"
EBGEOM_NATIVE=0 "$work/venv/bin/python" -m pip install --no-build-isolation --no-index -q \
  "$work/src"
cd "$work"
"$work/venv/bin/python" - <<'PY'
import numpy as np
import ebgeom
print("ebgeom", ebgeom.__version__, "from", ebgeom.__file__)
assert "/venv/" in ebgeom.__file__, ebgeom.__file__
v = np.array([[-1, -1, -1], [1, -1, -1], [-1, 1, -1], [1, 1, -1], [-1, -1, 1], [1, -1, 1],
              [-1, 1, 1], [1, 1, 1]], float)
f = [[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4], [2, 6, 3], [3, 6, 7],
     [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]]
ebgeom.Mesh(v, f).write("cube.obj")
d = ebgeom.MeshSdf(ebgeom.read_mesh("cube.obj"))([[0, 0, 0], [3, 0, 0]])
assert list(d) == [-1.0, 2.0], d
print("distances", d)
PY

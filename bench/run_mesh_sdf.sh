#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
# Mesh signed-distance benchmark against the peers (issue #4): installs the peers (Debian), builds
# the `bench` preset's target and runs it on the shared meshes (absent ones are skipped) in float
# and double. Output (text and JSON) goes to $OUT_DIR (default build/bench/mesh_sdf_results/).
# Usage: bash bench/run_mesh_sdf.sh [extra benchmark options, e.g. --points 200000 --reps 3]
#        (GENERATE="N1 N2 ..." adds generated meshes of about N triangles; see below)
set -euo pipefail
cd "$(dirname "$0")/.."
MESHES_DIR=${MESHES_DIR:-../shared/meshes}
OUT_DIR=${OUT_DIR:-build/bench/mesh_sdf_results}
sh bench/install-peers.sh
cmake --preset bench >/dev/null
cmake --build --preset bench --target ebgeom_bench_mesh_sdf_bench
bin=build/bench/bench/ebgeom_bench_mesh_sdf_bench
mkdir -p "$OUT_DIR"
for mesh in stanford-bunny.obj ogre.obj nefertiti.obj; do
  path="$MESHES_DIR/$mesh"
  if [ ! -f "$path" ]; then
    echo "skipping $mesh: $path not found" >&2
    continue
  fi
  name=${mesh%.obj}
  echo "== $mesh" >&2
  "$bin" "$path" --precision both --json-file "$OUT_DIR/$name.json" "$@" | tee "$OUT_DIR/$name.txt"
done
# Optional size sweep on generated meshes: GENERATE="100000 1000000 4000000" bash bench/run_mesh_sdf.sh
for n in ${GENERATE:-}; do
  echo "== generated, $n triangles" >&2
  "$bin" --generate "$n" --precision both --json-file "$OUT_DIR/generated-$n.json" "$@" |
    tee "$OUT_DIR/generated-$n.txt"
done
echo "results in $OUT_DIR" >&2

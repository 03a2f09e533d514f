#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
# Strong scaling of ebgeom-mpi (issue #8): the same grid on 1 and then 2 ranks (1 thread each),
# dense and narrow band, REPS runs each (the median is reported), plus a projection of the time
# of a 4096^3 grid from the measured cost per sample (dense) and per band brick (narrow band).
#
# Usage: bash bench/mpi_scaling.sh [MESH] (default ../shared/meshes/nefertiti.obj: closed, so the
# narrow band skips far bricks; open meshes get fast-winding signs, an implicit SDF sampled densely)
#   BUILD=build/mpi  RES=160  BAND=3  REPS=3  RANKS="1 2"  bash bench/mpi_scaling.sh
# The binaries come from $BUILD (configure it as in docs/distributed.md). On a shared machine the
# timings are noisy: compare medians, and read efficiency only to about +-10%.
set -euo pipefail
cd "$(dirname "$0")/.."
MESH=${1:-../shared/meshes/nefertiti.obj}
BUILD=${BUILD:-build/mpi}
RES=${RES:-160}
BAND=${BAND:-3}
REPS=${REPS:-3}
RANKS=${RANKS:-"1 2"}
bin=$BUILD/ebgeom-mpi
[ -x "$bin" ] || { echo "no $bin: build the ebgeom_mpi target first" >&2; exit 1; }
[ -f "$MESH" ] || { echo "no mesh $MESH" >&2; exit 1; }
cores=$(nproc --all)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "mesh $MESH, ${RES}^3, $cores cores, load average $(cut -d" " -f1 /proc/loadavg), $REPS runs per point (median), 1 thread per rank"
# run RANKS MODE -> prints "eval_s total_s imbalance_est imbalance_meas bricks band_bricks"
run() {
  local ranks=$1 mode=$2 band=()
  [ "$mode" = band ] && band=(--band "$BAND")
  for r in $(seq "$REPS"); do
    mpirun --oversubscribe -n "$ranks" "$bin" sdf "$MESH" -o "$tmp/g.npy" --res "$RES" \
      "${band[@]}" --threads 1 --json >"$tmp/j.json"
    python3 - "$tmp/j.json" <<'EOF'
import json, sys
j = json.load(open(sys.argv[1]))
m = j["mpi"]
print(j["timings"]["eval_s"], j["timings"]["total_s"], m["imbalance_estimated"],
      m["imbalance_measured"], m["bricks"], m["band_bricks"], m["brick"])
EOF
  done | sort -n | awk -v n="$REPS" 'NR == int((n + 1) / 2)'
}
printf '%-6s %5s %9s %9s %8s %8s %7s\n' mode ranks eval_s total_s imb_est imb_meas effic
for mode in dense band; do
  t1=
  for p in $RANKS; do
    read -r e t ie im bricks band_bricks side < <(run "$p" "$mode")
    [ -z "$t1" ] && t1=$e && e1=$e && b1=$band_bricks && s1=$side
    eff=$(python3 -c "print(f'{$t1 / ($p * $e):.2f}')")
    printf '%-6s %5d %9.3f %9.3f %8.3f %8.3f %7s\n' "$mode" "$p" "$e" "$t" "$ie" "$im" "$eff"
  done
  # Projection to 4096^3 on 1 core from the 1-rank run: dense work goes with the volume, narrow
  # band work with the surface (band bricks at the same brick side grow as (4096 / RES)^2).
  python3 - "$mode" "$e1" "$RES" "$b1" "$s1" <<'EOF'
import sys
mode, e1, res, bb, side = sys.argv[1], float(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
n = 4096
if mode == "dense":
    per = e1 / res**3
    core_s = per * n**3
    print(f"  dense: {per * 1e9:.1f} ns/sample -> 4096^3 = {core_s / 3600:.1f} core-hours "
          f"({core_s / 1024 / 60:.1f} min on 1024 cores)")
else:
    per = e1 / max(bb, 1)
    bricks = bb * (n / res) ** 2
    core_s = per * bricks
    print(f"  band: {bb} band bricks of {side}^3, {per * 1e3:.2f} ms/brick -> 4096^3 ~ "
          f"{bricks:.3g} band bricks = {core_s / 3600:.2f} core-hours "
          f"({core_s / 1024:.1f} s on 1024 cores); dense fill of the rest not included")
EOF
done

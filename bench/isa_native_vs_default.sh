#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
# A default build (no -march: run-time instruction-set dispatch) against a -march=native build of
# bench/isa_dispatch_bench.cpp, interleaved: R rounds, each running both binaries on every mesh;
# prints the median ns per query and per tile sample of each build's own choice ("auto") and the
# median over rounds of the paired ratio default / native (1.00: as fast; 1.10: 10% slower).
#
#   sh bench/isa_native_vs_default.sh DEFAULT_BIN NATIVE_BIN ROUNDS MESH... [-- --points N]
set -eu
default=$1 native=$2 rounds=$3
shift 3
meshes=""
while [ $# -gt 0 ] && [ "$1" != "--" ]; do meshes="$meshes $1"; shift; done
[ $# -gt 0 ] && shift
out=$(mktemp)
trap 'rm -f "$out"' EXIT
r=1
while [ "$r" -le "$rounds" ]; do
  for m in $meshes; do
    "$default" "$m" --reps 1 --only-auto "$@" | sed -n 's/ (auto)//p' | grep -v native_isa | sed 's/^/default /' >> "$out"
    "$native" "$m" --reps 1 --only-auto "$@" | sed -n 's/ (auto)//p' | grep -v native_isa | sed 's/^/native /' >> "$out"
  done
  r=$((r + 1))
done
# lines: BUILD MESH PRECISION ISA query_ns Q tile_ns L, in run order: the i-th default line of a
# (mesh, precision) pairs with its i-th native line (same round, run one after the other).
awk '
  { k = $2 " " $3; n = ++cnt[$1 "|" k]; q[$1 "|" k "|" n] = $6; l[$1 "|" k "|" n] = $8; keys[k] = 1 }
  function med(s,   a, n, i, j, t) {
    n = split(s, a, " ")
    for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (a[j] + 0 < a[i] + 0) { t = a[i]; a[i] = a[j]; a[j] = t }
    return a[int((n + 1) / 2)]
  }
  END {
    printf "%-44s %9s %9s %7s %9s %9s %7s\n", "mesh precision", "q default", "q native", "paired", "t default", "t native", "paired"
    for (k in keys) {
      qd = qn = ld = ln = rq = rl = ""
      for (i = 1; i <= cnt["default|" k]; i++) {
        qd = qd " " q["default|" k "|" i]; qn = qn " " q["native|" k "|" i]
        ld = ld " " l["default|" k "|" i]; ln = ln " " l["native|" k "|" i]
        rq = rq " " q["default|" k "|" i] / q["native|" k "|" i]
        rl = rl " " l["default|" k "|" i] / l["native|" k "|" i]
      }
      printf "%-44s %9.1f %9.1f %7.2f %9.1f %9.1f %7.2f\n", k, med(qd), med(qn), med(rq), med(ld), med(ln), med(rl)
    }
  }' "$out" | sort -r

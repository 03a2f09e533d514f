#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
# The library on 64-bit Arm: cross-compiles the unit tests of the geometry kernels, the BVH, the
# mesh SDF and the signs with Debian's GCC for AArch64 (NEON; no x86 run-time dispatch there, and
# fused multiply-adds in the base instruction set) and runs them under qemu-user. Checks results,
# not speed (an emulator says nothing about speed).
# Usage: sh scripts/check-aarch64.sh [--quick] [build-dir]   (as root, or with sudo available)
# Exit status: 0 all passed, 1 a build or a test failed, 3 the packages could not be installed.
#   --quick: without the tests that take minutes under the emulator (the band-against-dense-grid
#            comparisons, a million copies of one triangle, thread-count invariance); every kernel
#            is still compared with brute force or the per-point values. Without it, every test of
#            those four executables (over half an hour: the slowest take minutes each).
set -e
cd "$(dirname "$0")/.."
quick=0
if [ "${1:-}" = "--quick" ]; then
  quick=1
  shift
fi
b=${1:-build/aarch64}

# The packages; exit status 3 (not 1) when they cannot be installed, so that callers can tell a
# machine without them from a failing test.
SUDO=""
[ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null 2>&1 && SUDO=sudo
if ! dpkg --print-foreign-architectures | grep -qx arm64; then
  $SUDO dpkg --add-architecture arm64 && $SUDO apt-get update -qq || {
    echo "check-aarch64: cannot add Debian's arm64 architecture" >&2
    exit 3
  }
fi
sh scripts/install-deps.sh g++-aarch64-linux-gnu qemu-user libgtest-dev:arm64 || {
  echo "check-aarch64: cannot install g++-aarch64-linux-gnu, qemu-user and libgtest-dev:arm64" >&2
  exit 3
}

cmake -S . -B "$b" -G Ninja -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/aarch64-linux-gnu.cmake \
  -DCMAKE_BUILD_TYPE=Release -DEBGEOM_ASSERTS=ON -DEBGEOM_WERROR=ON -DEBGEOM_BUILD_CLI=OFF \
  -DEBGEOM_BUILD_EXAMPLES=OFF >/dev/null
tests="geom bvh sdf sign"
targets=""
for t in $tests; do targets="$targets ebgeom_test_unit_$t"; done
cmake --build "$b" --target $targets

# The tests left out by --quick, per executable (gtest negative filters).
slow_geom=''
slow_bvh=''
slow_sdf='*DegenerateMeshes*:*ThreadCount*:BvhUnionTest*.MixedTypeErased*'
slow_sign='BandConsistency.*:OpenBandTest*.Ranges*:OpenBandTest*.BandIs*:OpenBandTest*.FarTiles*:DirtyMesh.PointsOn*'
# Two executables at a time (the emulator runs one thread each); each one's summary and failures.
run() {
  t=$1
  filter='*'
  if [ $quick -eq 1 ]; then
    eval "slow=\$slow_$t"
    [ -n "$slow" ] && filter="*:-$slow"
  fi
  if qemu-aarch64 -L /usr/aarch64-linux-gnu "$b/tests/ebgeom_test_unit_$t" --gtest_brief=1 \
    --gtest_filter="$filter" >"$b/qemu_$t.log" 2>&1; then
    echo "--- $t (AArch64, qemu, $filter): $(grep -E '^\[ +PASSED' "$b/qemu_$t.log")"
  else
    echo "--- $t (AArch64, qemu, $filter): FAILED"
    cat "$b/qemu_$t.log"
    return 1
  fi
}
fail=0
run sign >"$b/run_sign.out" 2>&1 &
pid=$!
for t in sdf geom bvh; do run $t || fail=1; done
wait $pid || fail=1
cat "$b/run_sign.out"
exit $fail

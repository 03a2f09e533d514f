#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
#
# Checks the AMReX and Chombo couplings against the real codes, built from the source snapshots
# in ../shared/peers (AMReX 24.10, Chombo 3.2):
#  1. builds a minimal AMReX (EB on; no MPI, OpenMP, Fortran, particles, linear solvers or
#     AmrLevel) in 3D and 2D, and Chombo 3.2's EB libraries (3D, serial, optimised, HDF5), into a
#     cache directory outside the repository, reused when present;
#  2. compiles integrations/amrex/mesh_sdf (3D and 2D) and integrations/chombo/mesh_sdf (3D);
#  3. runs the sphere at 32^3, R = 0.3 in the unit cube through ebgeom and through each code's own
#     SphereIF: cut cells and fluid volume must be equal, and 1,760 cut cells in 3D; then a closed
#     mesh from ../shared/meshes (the dodecahedron) with the `dodecahedron` preset. Each ebgeom
#     case runs twice, with ebgeom's whole-box evaluation (AMReX: ebgeom::make_amrex_shop;
#     Chombo: the adapter's InsideOutside hook) and without it (every node per point): the
#     results must be equal.
#
# Usage: scripts/check-couplings.sh [--quick] [--cache DIR] [--jobs N] [--amrex-only|--chombo-only]
#   --quick   only compile the two adapters' examples against the real headers (AMReX is
#             configured, not built, for its generated config header; Chombo's headers are used
#             from the source tree). Minutes, not tens of minutes.
# Environment: EBGEOM_COUPLINGS_CACHE (default /var/cache/ebgeom-couplings), EBGEOM_PEERS
# (default ../shared/peers), EBGEOM_MESHES (default ../shared/meshes), CXX (default g++), FC
# (default gfortran).
# Debian packages: cmake g++ make tar gzip csh perl gfortran libhdf5-dev (the last four for
# Chombo).
# Exit status: 0 all checks passed, 1 a check failed, 2 a tool or input is missing.

set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
CACHE=${EBGEOM_COUPLINGS_CACHE:-/var/cache/ebgeom-couplings}
PEERS=${EBGEOM_PEERS:-$ROOT/../shared/peers}
MESHES=${EBGEOM_MESHES:-$ROOT/../shared/meshes}
JOBS=$(nproc 2>/dev/null || echo 2)
QUICK=0
DO_AMREX=1
DO_CHOMBO=1
CXX=${CXX:-g++}
FC=${FC:-gfortran}

while [ $# -gt 0 ]; do
  case "$1" in
  --quick) QUICK=1 ;;
  --cache) CACHE=$2; shift ;;
  --jobs) JOBS=$2; shift ;;
  --amrex-only) DO_CHOMBO=0 ;;
  --chombo-only) DO_AMREX=0 ;;
  -h | --help) sed -n '4,26p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
  *) echo "check-couplings: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done

say() { printf 'check-couplings: %s\n' "$*"; }
die() { printf 'check-couplings: error: %s\n' "$*" >&2; exit 2; }
fail() { printf 'check-couplings: FAILED: %s\n' "$*" >&2; FAILURES=$((FAILURES + 1)); }
FAILURES=0
T0=$(date +%s)
elapsed() { echo "$(($(date +%s) - T0)) s"; }

need() { command -v "$1" >/dev/null 2>&1 || die "'$1' not found (Debian package: $2)"; }
need cmake cmake
need make make
need tar tar
need "$CXX" g++
if [ $DO_CHOMBO = 1 ] && [ $QUICK = 0 ]; then # the quick mode only reads Chombo's headers
  need csh csh
  need perl perl
  need "$FC" gfortran
fi

AMREX_TGZ=$(ls "$PEERS"/amrex-*.tar.gz 2>/dev/null | head -n 1 || true)
CHOMBO_TGZ=$(ls "$PEERS"/Chombo_*.tar.gz 2>/dev/null | head -n 1 || true)
[ $DO_AMREX = 0 ] || [ -n "$AMREX_TGZ" ] || die "no amrex-*.tar.gz in $PEERS"
[ $DO_CHOMBO = 0 ] || [ -n "$CHOMBO_TGZ" ] || die "no Chombo_*.tar.gz in $PEERS"

mkdir -p "$CACHE" 2>/dev/null || die "cannot create the cache $CACHE (use --cache DIR)"
[ -w "$CACHE" ] || die "the cache $CACHE is not writable (use --cache DIR)"
say "cache $CACHE, $JOBS jobs$([ $QUICK = 1 ] && echo ', quick: compile only')"

# unpack <tarball> -> prints the source directory (unpacked once, marked by a stamp)
unpack() {
  local tgz=$1 name
  name=$(basename "$tgz" .tar.gz)
  if [ ! -f "$CACHE/src/$name/.unpacked" ]; then
    say "unpacking $name" >&2
    rm -rf "$CACHE/src/$name"
    mkdir -p "$CACHE/src"
    tar -xzf "$tgz" -C "$CACHE/src"
    [ -d "$CACHE/src/$name" ] || die "$tgz did not unpack into $name/"
    touch "$CACHE/src/$name/.unpacked"
  fi
  echo "$CACHE/src/$name"
}

# cut cells and fluid volume from an example's output line "mesh_sdf: N cut cells, fluid volume V"
result_of() { grep -E '^mesh_sdf: [0-9]+ cut cells, fluid volume' "$1" | tail -n 1 | awk '{print $2, $7}'; }

# compare <label> <ebgeom log> <reference log> [expected cut cells]
compare() {
  local label=$1 mine ref cut vol rcut rvol
  mine=$(result_of "$2") || true
  ref=$(result_of "$3") || true
  if [ -z "$mine" ] || [ -z "$ref" ]; then fail "$label: no result line (see $2, $3)"; return; fi
  read -r cut vol <<<"$mine"
  read -r rcut rvol <<<"$ref"
  say "$label: $cut cut cells, volume $vol; reference $rcut, $rvol"
  [ "$cut" = "$rcut" ] || fail "$label: cut cells differ ($cut vs $rcut)"
  awk -v a="$vol" -v b="$rvol" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= 1e-12 * (b < 0 ? -b : b) + 1e-15) }' ||
    fail "$label: fluid volumes differ ($vol vs $rvol)"
  if [ $# -ge 4 ] && [ "$cut" != "$4" ]; then fail "$label: $cut cut cells, expected $4"; fi
}

WORK="$CACHE/work"
mkdir -p "$WORK"
DODECA="$MESHES/formats/dodecahedron.ply"

# ---- AMReX ---------------------------------------------------------------------------------
amrex_configure() { # <dim> <build dir> <install dir>
  cmake -S "$AMREX_SRC" -B "$2" -G "Unix Makefiles" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CXX_COMPILER="$CXX" -DCMAKE_INSTALL_PREFIX="$3" -DAMReX_SPACEDIM="$1" \
    -DAMReX_EB=ON -DAMReX_MPI=OFF -DAMReX_OMP=OFF -DAMReX_FORTRAN=OFF \
    -DAMReX_FORTRAN_INTERFACES=OFF -DAMReX_PARTICLES=OFF -DAMReX_LINEAR_SOLVERS=OFF \
    -DAMReX_AMRLEVEL=OFF -DAMReX_AMRDATA=OFF -DAMReX_TINY_PROFILE=OFF -DAMReX_PROBINIT=OFF \
    -DAMReX_HDF5=OFF -DAMReX_GPU_BACKEND=NONE -DAMReX_BUILD_TUTORIALS=OFF \
    -DAMReX_ENABLE_TESTS=OFF >"$2.configure.log" 2>&1 ||
    { tail -n 30 "$2.configure.log" >&2; die "AMReX ${1}D configure failed ($2.configure.log)"; }
}

amrex_quick() { # <dim>: compile the example against the source headers + the configured header
  local dim=$1
  local bdir="$CACHE/amrex-quick-${dim}d" cfg incs=() d
  [ -f "$bdir/.configured" ] || { amrex_configure "$dim" "$bdir" "$CACHE/unused"; touch "$bdir/.configured"; }
  cfg=$(find "$bdir" -name AMReX_Config.H | head -n 1)
  [ -n "$cfg" ] || die "AMReX ${dim}D: no AMReX_Config.H under $bdir"
  while IFS= read -r d; do incs+=("-I$d"); done < <(find "$AMREX_SRC/Src/Base" "$AMREX_SRC/Src/Boundary" \
    "$AMREX_SRC/Src/AmrCore" "$AMREX_SRC/Src/EB" -type d)
  say "AMReX ${dim}D: compiling integrations/amrex/mesh_sdf against the real headers"
  if "$CXX" -std=c++17 -fsyntax-only -Wall -Wextra -I"$(dirname "$cfg")" "${incs[@]}" \
    -I"$ROOT/include" -I"$ROOT/integrations/amrex" "$ROOT/integrations/amrex/mesh_sdf/main.cpp" \
    >"$WORK/amrex-quick-${dim}d.log" 2>&1; then
    say "AMReX ${dim}D: compiles ($(grep -c 'warning:' "$WORK/amrex-quick-${dim}d.log" || true) warnings, $(grep 'warning:' "$WORK/amrex-quick-${dim}d.log" | grep -vc "^$CACHE/src/" || true) of them outside AMReX's headers)"
  else
    tail -n 40 "$WORK/amrex-quick-${dim}d.log" >&2
    fail "AMReX ${dim}D: the example does not compile ($WORK/amrex-quick-${dim}d.log)"
  fi
}

amrex_full() { # <dim>
  local dim=$1
  local bdir="$CACHE/amrex-build-${dim}d" idir="$CACHE/amrex-${dim}d"
  local ebuild="$WORK/amrex-mesh_sdf-${dim}d" exe run
  if [ ! -f "$idir/.complete" ]; then
    say "AMReX ${dim}D: building (once; reused from $idir afterwards) [$(elapsed)]"
    amrex_configure "$dim" "$bdir" "$idir"
    nice cmake --build "$bdir" -j "$JOBS" >"$bdir.build.log" 2>&1 ||
      { tail -n 30 "$bdir.build.log" >&2; die "AMReX ${dim}D build failed ($bdir.build.log)"; }
    cmake --install "$bdir" >"$bdir.install.log" 2>&1 || die "AMReX ${dim}D install failed"
    touch "$idir/.complete"
  fi
  say "AMReX ${dim}D: compiling integrations/amrex/mesh_sdf [$(elapsed)]"
  # a fresh build folder: one configured from another checkout would be refused by CMake
  rm -rf "$ebuild"
  cmake -S "$ROOT/integrations/amrex/mesh_sdf" -B "$ebuild" -DAMReX_ROOT="$idir" \
    -DCMAKE_CXX_COMPILER="$CXX" >"$ebuild.configure.log" 2>&1 ||
    { tail -n 30 "$ebuild.configure.log" >&2; fail "AMReX ${dim}D: example configure failed"; return; }
  nice cmake --build "$ebuild" -j "$JOBS" >"$ebuild.build.log" 2>&1 ||
    { tail -n 40 "$ebuild.build.log" >&2; fail "AMReX ${dim}D: the example does not compile"; return; }
  exe="$ebuild/ebgeom_amrex_mesh_sdf"
  [ -x "$exe" ] || { fail "AMReX ${dim}D: no executable (is AMReX found with EB?)"; return; }
  run="$WORK/amrex-run-${dim}d"
  mkdir -p "$run"
  for g in sphere amrex_sphere; do
    (cd "$run" && "$exe" "$ROOT/integrations/amrex/mesh_sdf/inputs" mesh_sdf.which_geom=$g \
      mesh_sdf.n_cell=32 mesh_sdf.sphere_radius=0.3 mesh_sdf.plotfile="plt-$g") >"$run/$g.log" 2>&1 ||
      fail "AMReX ${dim}D: $g run failed ($run/$g.log)"
  done
  # ebgeom's sphere through AMReX's own GeometryShop too (every node per point): the same EB
  (cd "$run" && "$exe" "$ROOT/integrations/amrex/mesh_sdf/inputs" mesh_sdf.which_geom=sphere \
    mesh_sdf.eb_shop=amrex mesh_sdf.n_cell=32 mesh_sdf.sphere_radius=0.3 mesh_sdf.plotfile=plt-s2) \
    >"$run/sphere-amrex-shop.log" 2>&1 || fail "AMReX ${dim}D: sphere run with AMReX's shop failed"
  if [ "$dim" = 3 ]; then
    compare "AMReX 3D sphere 32^3" "$run/sphere.log" "$run/amrex_sphere.log" 1760
    compare "AMReX 3D sphere 32^3, AMReX's shop" "$run/sphere-amrex-shop.log" "$run/amrex_sphere.log" 1760
    if [ -f "$DODECA" ]; then
      for shop in ebgeom amrex; do
        (cd "$run" && "$exe" "$ROOT/integrations/amrex/mesh_sdf/inputs" mesh_sdf.which_geom=dodecahedron \
          mesh_sdf.file="$DODECA" mesh_sdf.n_cell=32 mesh_sdf.eb_shop=$shop \
          mesh_sdf.plotfile=plt-dodeca-$shop) >"$run/dodeca-$shop.log" 2>&1 &&
          grep -qE '^mesh_sdf: [1-9][0-9]* cut cells' "$run/dodeca-$shop.log" ||
          fail "AMReX 3D: the dodecahedron run failed ($run/dodeca-$shop.log)"
      done
      compare "AMReX 3D dodecahedron 32^3, ebgeom's shop against AMReX's" "$run/dodeca-ebgeom.log" \
        "$run/dodeca-amrex.log"
    else
      say "AMReX 3D: $DODECA not found, mesh run skipped"
    fi
  else
    compare "AMReX 2D circle 32^2 (slice z = 0.5)" "$run/sphere.log" "$run/amrex_sphere.log"
    compare "AMReX 2D circle 32^2, AMReX's shop" "$run/sphere-amrex-shop.log" "$run/amrex_sphere.log"
  fi
}

# ---- Chombo --------------------------------------------------------------------------------
chombo_hdf5_flags() {
  local inc lib
  for inc in /usr/include/hdf5/serial /usr/include; do [ -f "$inc/hdf5.h" ] && break; done
  for lib in /usr/lib/x86_64-linux-gnu/hdf5/serial /usr/lib/$(uname -m)-linux-gnu/hdf5/serial /usr/lib/x86_64-linux-gnu /usr/lib; do
    [ -e "$lib/libhdf5.so" ] && break
  done
  [ -f "$inc/hdf5.h" ] || die "hdf5.h not found (Debian package: libhdf5-dev)"
  HDFINC="-I$inc"
  HDFLIB="-L$lib -lhdf5 -lz"
}

chombo_config() { # writes Make.defs.local for 3D, serial, optimised, EB, HDF5
  chombo_hdf5_flags
  cat >"$CHOMBO_SRC/lib/mk/Make.defs.local" <<EOF
# written by ebgeom's scripts/check-couplings.sh
DIM           = 3
DEBUG         = FALSE
OPT           = TRUE
PRECISION     = DOUBLE
MPI           = FALSE
CXX           = $CXX
FC            = $FC
USE_EB        = TRUE
USE_HDF       = TRUE
USE_MT        = FALSE
HDFINCFLAGS   = $HDFINC -DH5_USE_16_API
HDFLIBFLAGS   = $HDFLIB
cxxoptflags   = -O2
foptflags     = -O2
syslibflags   = -lgfortran
EOF
}

chombo_quick() {
  local incs=() d
  for d in BaseTools BoxTools AMRTools AMRTimeDependent AMRElliptic EBTools EBAMRTools Workshop; do
    incs+=("-I$CHOMBO_SRC/lib/src/$d")
  done
  # the HDF5 output path too when HDF5's headers are installed (libhdf5-dev)
  local h
  for h in /usr/include/hdf5/serial /usr/include; do
    if [ -f "$h/hdf5.h" ]; then incs+=("-DCH_USE_HDF5" "-DH5_USE_16_API" "-I$h"); break; fi
  done
  say "Chombo 3D: compiling integrations/chombo/mesh_sdf against the real headers$(
    printf '%s\n' "${incs[@]}" | grep -q CH_USE_HDF5 && echo ', with HDF5' || echo ', without HDF5 (no hdf5.h)')"
  if "$CXX" -std=c++17 -fsyntax-only -Wall -Wextra -DCH_SPACEDIM=3 -DCH_LANG_CC -DCH_USE_DOUBLE \
    -DCH_USE_64 -DCH_USE_COMPLEX -DCH_FORT_UNDERSCORE -DCH_Linux "${incs[@]}" -I"$ROOT/include" \
    -I"$ROOT/integrations/chombo" "$ROOT/integrations/chombo/mesh_sdf/main.cpp" \
    >"$WORK/chombo-quick-3d.log" 2>&1; then
    say "Chombo 3D: compiles ($(grep -c 'warning:' "$WORK/chombo-quick-3d.log" || true) warnings, $(grep 'warning:' "$WORK/chombo-quick-3d.log" | grep -vc "^$CACHE/src/" || true) of them outside Chombo's headers)"
  else
    tail -n 40 "$WORK/chombo-quick-3d.log" >&2
    fail "Chombo 3D: the example does not compile ($WORK/chombo-quick-3d.log; headers generated by Chombo's build, e.g. *_F.H, need the full mode)"
  fi
}

CHOMBO_LIBS="BaseTools BoxTools AMRTools EBTools Workshop EBAMRTools"

chombo_full() {
  local ex="$WORK/chombo-mesh_sdf" exe run
  if [ ! -f "$CHOMBO_SRC/.complete" ]; then
    say "Chombo: building the EB libraries (once; reused afterwards) [$(elapsed)]"
    chombo_config
    # USE_EB=TRUE on the top-level make too, or the EB libraries are not built. Only the
    # libraries the example links (and their dependencies): `make lib` would also build the
    # elliptic, time-dependent, mapped-geometry and particle libraries, tripling the time.
    nice make -C "$CHOMBO_SRC/lib" -j "$JOBS" $CHOMBO_LIBS USE_EB=TRUE DIM=3 \
      >"$CACHE/chombo-build.log" 2>&1 ||
      { tail -n 40 "$CACHE/chombo-build.log" >&2; die "Chombo build failed ($CACHE/chombo-build.log)"; }
    touch "$CHOMBO_SRC/.complete"
  fi
  # Chombo's make builds in the example's folder: use a copy in the cache, not the repository
  say "Chombo 3D: compiling integrations/chombo/mesh_sdf [$(elapsed)]"
  rm -rf "$ex"
  cp -r "$ROOT/integrations/chombo/mesh_sdf" "$ex"
  nice make -C "$ex" -j "$JOBS" all CHOMBO_HOME="$CHOMBO_SRC/lib" EBGEOM_HOME="$ROOT" DIM=3 \
    OPT=TRUE DEBUG=FALSE MPI=FALSE USE_EB=TRUE >"$ex.build.log" 2>&1 ||
    { tail -n 40 "$ex.build.log" >&2; fail "Chombo 3D: the example does not compile ($ex.build.log)"; return; }
  exe=$(ls "$ex"/main3d*.ex 2>/dev/null | head -n 1)
  [ -n "$exe" ] || { fail "Chombo 3D: no executable in $ex"; return; }
  run="$WORK/chombo-run-3d"
  mkdir -p "$run"
  for g in sphere chombo_sphere; do
    (cd "$run" && "$exe" "$ex/mesh_sdf.inputs" mesh_sdf.which_geom=$g mesh_sdf.n_cells=32 \
      mesh_sdf.sphere_radius=0.3 mesh_sdf.output="$g.hdf5") >"$run/$g.log" 2>&1 ||
      fail "Chombo 3D: $g run failed ($run/$g.log)"
  done
  # ebgeom's sphere without the adapter's box hook (GeometryShop evaluates every node): the same
  (cd "$run" && "$exe" "$ex/mesh_sdf.inputs" mesh_sdf.which_geom=sphere mesh_sdf.box_hook=0 \
    mesh_sdf.n_cells=32 mesh_sdf.sphere_radius=0.3 mesh_sdf.output=sphere-nohook.hdf5) \
    >"$run/sphere-nohook.log" 2>&1 || fail "Chombo 3D: sphere run without the box hook failed"
  compare "Chombo 3D sphere 32^3" "$run/sphere.log" "$run/chombo_sphere.log" 1760
  compare "Chombo 3D sphere 32^3, no box hook" "$run/sphere-nohook.log" "$run/chombo_sphere.log" 1760
  if [ -f "$DODECA" ]; then
    for hook in 1 0; do
      (cd "$run" && "$exe" "$ex/mesh_sdf.inputs" mesh_sdf.which_geom=dodecahedron mesh_sdf.file="$DODECA" \
        mesh_sdf.n_cells=32 mesh_sdf.box_hook=$hook mesh_sdf.output=dodeca-$hook.hdf5) \
        >"$run/dodeca-$hook.log" 2>&1 &&
        grep -qE '^mesh_sdf: [1-9][0-9]* cut cells' "$run/dodeca-$hook.log" ||
        fail "Chombo 3D: the dodecahedron run failed ($run/dodeca-$hook.log)"
    done
    compare "Chombo 3D dodecahedron 32^3, box hook against none" "$run/dodeca-1.log" "$run/dodeca-0.log"
  fi
}

if [ $DO_AMREX = 1 ]; then
  AMREX_SRC=$(unpack "$AMREX_TGZ")
  for dim in 3 2; do
    if [ $QUICK = 1 ]; then amrex_quick $dim; else amrex_full $dim; fi
  done
fi
if [ $DO_CHOMBO = 1 ]; then
  CHOMBO_SRC=$(unpack "$CHOMBO_TGZ")
  if [ $QUICK = 1 ]; then chombo_quick; else chombo_full; fi
fi

if [ $FAILURES -gt 0 ]; then
  say "$FAILURES check(s) failed [$(elapsed)]"
  exit 1
fi
say "all checks passed [$(elapsed)]"

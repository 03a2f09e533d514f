# SPDX-License-Identifier: BSD-3-Clause
# SPDX-FileCopyrightText: 2026 The ebgeom authors
# Optional OpenVDB peer of bench/grid_bench.cpp (meshToVolume), compiled in only when found
# (Debian: bench/install-openvdb.sh installs libopenvdb-dev). Included from bench/CMakeLists.txt.
# Found by header and library rather than FindOpenVDB.cmake, which hard-fails on Debian 12 unless
# libboost-iostreams-dev is installed too (only the shared library needs it).
if(TARGET ebgeom_bench_grid_bench)
  find_path(EBGEOM_OPENVDB_INCLUDE openvdb/openvdb.h)
  find_library(EBGEOM_OPENVDB_LIB openvdb)
  find_package(TBB CONFIG QUIET)
  if(EBGEOM_OPENVDB_INCLUDE AND EBGEOM_OPENVDB_LIB AND TBB_FOUND)
    target_include_directories(ebgeom_bench_grid_bench SYSTEM PRIVATE ${EBGEOM_OPENVDB_INCLUDE})
    target_link_libraries(ebgeom_bench_grid_bench PRIVATE ${EBGEOM_OPENVDB_LIB} TBB::tbb)
    target_compile_definitions(ebgeom_bench_grid_bench PRIVATE EBGEOM_BENCH_HAVE_OPENVDB)
    message(STATUS "grid_bench: OpenVDB peer enabled (${EBGEOM_OPENVDB_LIB})")
  else()
    message(STATUS "grid_bench: OpenVDB not found, peer skipped (sh bench/install-openvdb.sh)")
  endif()
endif()

# Embree 3 peer of the dense grid (per-point closest-triangle queries, bench/peers/embree_peer.hpp),
# as in mesh_sdf_bench (bench/install-peers.sh installs libembree-dev).
if(TARGET ebgeom_bench_grid_bench)
  target_include_directories(ebgeom_bench_grid_bench PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  find_package(embree 3 QUIET)
  if(embree_FOUND)
    target_link_libraries(ebgeom_bench_grid_bench PRIVATE embree)
    target_compile_definitions(ebgeom_bench_grid_bench PRIVATE EBGEOM_BENCH_HAVE_EMBREE)
    message(STATUS "grid_bench: Embree ${embree_VERSION} peer enabled")
  else()
    message(STATUS "grid_bench: Embree 3 not found, peer skipped (sh bench/install-peers.sh)")
  endif()
endif()

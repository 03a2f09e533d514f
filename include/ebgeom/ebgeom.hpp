// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Umbrella header: includes every public module. Users may include finer headers instead.

#include "ebgeom/bvh.hpp"
#include "ebgeom/core.hpp"
#include "ebgeom/eval.hpp"
#include "ebgeom/geom.hpp"
#include "ebgeom/io.hpp"
#include "ebgeom/mesh.hpp"
#include "ebgeom/octree.hpp"
#include "ebgeom/sdf.hpp"
#include "ebgeom/sdf/brute_force_dcel_sdf.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"
#include "ebgeom/version.hpp"

// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Bounding volume hierarchies: builders, the compact wide form, traversals, point clouds, the
/// BVH mesh SDF and the BVH-accelerated union.

#include "ebgeom/bvh/build.hpp"
#include "ebgeom/bvh/point_cloud.hpp"
#include "ebgeom/bvh/traverse.hpp"
#include "ebgeom/bvh/wide_bvh.hpp"
#include "ebgeom/sdf/bvh_union.hpp"
#include "ebgeom/sdf/cached_union.hpp"
#include "ebgeom/sdf/dcel_sdf.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"

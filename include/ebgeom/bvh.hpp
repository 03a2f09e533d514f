// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Bounding volume hierarchies: builders, the compact wide form, traversals and point clouds.
/// The SDFs built on them (`MeshSdf`, `DcelSdf`, `BvhUnion`, `CachedUnion`) are in
/// `ebgeom/sdf.hpp`.

#include "ebgeom/bvh/build.hpp"
#include "ebgeom/bvh/point_cloud.hpp"
#include "ebgeom/bvh/traverse.hpp"
#include "ebgeom/bvh/wide_bvh.hpp"

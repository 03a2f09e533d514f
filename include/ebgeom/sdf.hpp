// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Module umbrella: analytic shapes, transforms, CSG, type erasure and normals (see
/// docs/shapes.md), the mesh SDFs (`MeshSdf`, `DcelSdf`, `SignedMeshSdf`) and the unions of many
/// SDFs (`BvhUnion`, `CachedUnion`; see docs/bvh.md). Users may include the finer headers instead.

#include "ebgeom/core/bounding_sphere.hpp"
#include "ebgeom/core/rotation.hpp"
#include "ebgeom/sdf/any_sdf.hpp"
#include "ebgeom/sdf/bvh_union.hpp"
#include "ebgeom/sdf/cached_union.hpp"
#include "ebgeom/sdf/concepts.hpp"
#include "ebgeom/sdf/csg.hpp"
#include "ebgeom/sdf/dcel_distance.hpp"
#include "ebgeom/sdf/dcel_sdf.hpp"
#include "ebgeom/sdf/mesh_closest_point.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "ebgeom/sdf/normal.hpp"
#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"
#include "ebgeom/sdf/transforms.hpp"
#include "ebgeom/sdf/winding.hpp"

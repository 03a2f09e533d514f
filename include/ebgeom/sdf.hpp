// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Module umbrella: analytic shapes, transforms, CSG, type erasure and normals (see
/// docs/shapes.md). Users may include the finer headers instead.

#include "ebgeom/core/rotation.hpp"
#include "ebgeom/core/sphere.hpp"
#include "ebgeom/sdf/any_sdf.hpp"
#include "ebgeom/sdf/concepts.hpp"
#include "ebgeom/sdf/csg.hpp"
#include "ebgeom/sdf/normal.hpp"
#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"
#include "ebgeom/sdf/transforms.hpp"
#include "ebgeom/sdf/winding.hpp"

// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Module umbrella: vectors, boxes, bounding spheres, rotations, Morton codes, errors, results,
/// spans and threading. Includes nothing above `core/` (the SDF contract is in `ebgeom/sdf.hpp`).

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/axis.hpp"
#include "ebgeom/core/bounding_sphere.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/error.hpp"
#include "ebgeom/core/morton.hpp"
#include "ebgeom/core/parallel.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/rotation.hpp"
#include "ebgeom/core/simd.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"

// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Module umbrella: per-primitive geometric kernels (closest point on a triangle, solid angles).

#include "ebgeom/geom/closest_point_triangle.hpp"
#include "ebgeom/geom/point_in_polygon.hpp"
#include "ebgeom/geom/polygon_geometry.hpp"
#include "ebgeom/geom/solid_angle.hpp"
#include "ebgeom/geom/tri_block.hpp"

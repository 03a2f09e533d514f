// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Deprecated path, kept for one release: the geometry of one planar polygon (a geometry kernel)
/// moved to `ebgeom/geom/polygon_geometry.hpp`. Include that instead.
#include "ebgeom/geom/polygon_geometry.hpp"

// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Deprecated path, kept for one release: the point-in-polygon tests (a geometry kernel) moved to
/// `ebgeom/geom/point_in_polygon.hpp`. Include that instead.
#include "ebgeom/geom/point_in_polygon.hpp"

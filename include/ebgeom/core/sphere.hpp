// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Deprecated: `BoundingSphere<T>` now lives in `ebgeom/core/bounding_sphere.hpp` (the sphere
/// *shape* is `Sphere<T>` in `ebgeom/sdf/shapes.hpp`). This forwarding header will be removed in a
/// later release; include `ebgeom/core/bounding_sphere.hpp` instead.

#include "ebgeom/core/bounding_sphere.hpp"

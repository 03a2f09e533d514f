// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Module umbrella: polygon soups, half-edge and triangle meshes, pseudonormals, procedural meshes,
/// validation.

#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/mesh/half_edge_mesh.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/mesh/pseudonormals.hpp"
#include "ebgeom/mesh/soup_check.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"
#include "ebgeom/mesh/validate.hpp"
#include "ebgeom/mesh/weld.hpp"

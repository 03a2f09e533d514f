// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Deprecated path, kept for one release: the grid samplers' tile engine (8^3 tiles) is
/// `ebgeom/eval/grid_tiles.hpp`. Include that instead.
#include "ebgeom/eval/grid_tiles.hpp"

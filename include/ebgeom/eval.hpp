// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Umbrella header of the evaluation module: batch evaluation, dense, sub-box and sparse grids,
/// grid writers.

#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/eval/grid.hpp"
#include "ebgeom/eval/grid_spec.hpp"
#include "ebgeom/eval/grid_tiles.hpp"
#include "ebgeom/eval/sparse_grid.hpp"
#include "ebgeom/eval/write_grid.hpp"

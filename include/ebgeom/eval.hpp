#pragma once
/// \file
/// Umbrella header of the evaluation module: batch evaluation, dense grids and grid writers.

#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/eval/grid.hpp"
#include "ebgeom/eval/write_grid.hpp"

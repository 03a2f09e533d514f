// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Module umbrella: the generic octree.

#include "ebgeom/octree/octree.hpp"

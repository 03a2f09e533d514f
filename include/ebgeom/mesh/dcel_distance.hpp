// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Deprecated path, kept for one release: the DCEL face, edge and vertex distances (the kernel of
/// `DcelSdf`) moved to `ebgeom/sdf/dcel_distance.hpp`. Include that instead.
#include "ebgeom/sdf/dcel_distance.hpp"

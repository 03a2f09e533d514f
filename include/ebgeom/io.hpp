// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Module umbrella: mesh readers (STL, PLY, OBJ, OFF, legacy VTK) with format detection, and
/// writers.

#include "ebgeom/io/byte_reader.hpp"
#include "ebgeom/io/obj.hpp"
#include "ebgeom/io/off.hpp"
#include "ebgeom/io/parse_error.hpp"
#include "ebgeom/io/ply.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/io/read_options.hpp"
#include "ebgeom/io/scalar_type.hpp"
#include "ebgeom/io/stl.hpp"
#include "ebgeom/io/text_reader.hpp"
#include "ebgeom/io/vtk.hpp"
#include "ebgeom/io/write_mesh.hpp"

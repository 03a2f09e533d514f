// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Shared pieces of the ebgeom command-line tools: the scene component's exit codes and error type
// under their command-line names, and the system utilities (memory, files, clock) they share.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "ebgeom/core/error.hpp"
#include "ebgeom/scene/error.hpp"
#include "ebgeom/scene/system.hpp"

namespace ebgeom::cli {

// The exit statuses, the error every subcommand throws (`CliError`) and `fail` are the scene
// component's (ebgeom/scene/error.hpp), as are the scene compiler and mesh input the subcommands
// use.
using namespace ebgeom::scene;
using CliError = scene::ToolError;

} // namespace ebgeom::cli

// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Shared pieces of the ebgeom command-line tool: the scene component's exit codes and error type
// under their command-line names, the system utilities (memory, files, clock), and the jobs
// component's grid-job rules and outputs, all visible in namespace ebgeom::cli.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "ebgeom/core/error.hpp"
#include "ebgeom/scene/error.hpp"
#include "ebgeom/scene/system.hpp"

namespace ebgeom::jobs {} // namespace ebgeom::jobs

namespace ebgeom::cli {

// The exit statuses, the error every subcommand throws (`CliError`) and `fail` are the scene
// component's (ebgeom/scene/error.hpp), as are the scene compiler and mesh input the subcommands
// use; the grid-job rules, the .npz and .vdb outputs and the mesh report are the jobs component's
// (ebgeom/jobs/).
using namespace ebgeom::scene;
using namespace ebgeom::jobs;
using CliError = scene::ToolError;

} // namespace ebgeom::cli

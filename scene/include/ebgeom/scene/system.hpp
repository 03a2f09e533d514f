// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// What the tools ask of the system before and around a job: the memory left, whether an input is
// a regular file and an output can be written, sizes in words, a clock.

#include <cstdint>
#include <string>

#include "ebgeom/scene/error.hpp"

namespace ebgeom::scene {

/// Bytes of memory the machine can still give (MemAvailable in /proc/meminfo); 0 if unknown.
std::uint64_t available_memory_bytes();

/// Throws `exit_resource` when `bytes` exceed the available memory, naming the size needed and
/// ending with `hint` (what the user can do instead).
void require_memory(std::uint64_t bytes, const std::string& what,
                    const std::string& hint = "lower the resolution (--res/--dx) or shrink --box");

/// Throws ToolError (input) unless `path` names an existing regular file (following links):
/// `FILE: no such file`, `FILE: is a directory, not a file`, `FILE: is a FIFO (named pipe), not
/// a regular file; ...` (FIFOs, devices and sockets would block or never end).
void require_input_file(const std::string& path);

/// Throws ToolError (output) unless `path` is something an output may be written to
/// (`ebgeom::check_output_target`): checked before the work, so a refused target costs nothing.
void require_output_target(const std::string& path);

/// "1.5 GiB" style size.
std::string human_bytes(std::uint64_t bytes);

/// True when stderr is a terminal.
bool stderr_is_terminal();

/// Seconds since `t0` (steady clock, in seconds since an arbitrary epoch from `now_s()`).
double now_s();

} // namespace ebgeom::scene

// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// The library's version: the one place it is written. CMake's `project(VERSION)`, the
/// package's version file, `ebgeom --version` and the Python package all read it from here.

#define EBGEOM_VERSION_MAJOR 0
#define EBGEOM_VERSION_MINOR 1
#define EBGEOM_VERSION_PATCH 0

/// "MAJOR.MINOR.PATCH" as a string literal.
#define EBGEOM_VERSION_STRING "0.1.0"

namespace ebgeom {

/// The version this header belongs to, for run-time checks and messages.
struct Version {
  int major, minor, patch;
};
inline constexpr Version version{EBGEOM_VERSION_MAJOR, EBGEOM_VERSION_MINOR, EBGEOM_VERSION_PATCH};
inline constexpr const char* version_string = EBGEOM_VERSION_STRING;

} // namespace ebgeom

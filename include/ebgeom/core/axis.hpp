// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `Axis`: a coordinate axis as a strong type (`Axis::x`, `Axis::y`, `Axis::z`). Functions that
/// take a coordinate axis (`rotate(shape, Axis::z, 90)`, `mirror(shape, Axis::x)`,
/// `Mat3::coordinate_axis`) take an `Axis`, never an `int`: a plain number does not convert to
/// it, so an argument-order slip such as EBGeometry's `rotate(angle, axis)` written as
/// `rotate(shape, 90, 0)` does not compile instead of silently doing nothing. Axes read at run
/// time (an input file, a command line) go through the checked `axis_from_index` or
/// `axis_from_name`.

#include <string>

#include "ebgeom/core/error.hpp"
#include "ebgeom/core/result.hpp"

namespace ebgeom {

/// A coordinate axis. The underlying values are the component indices (x = 0, y = 1, z = 2);
/// there is no implicit conversion from or to `int`.
enum class Axis : int { x = 0, y = 1, z = 2 };

/// The component index of `a` (0, 1 or 2).
constexpr int index(Axis a) noexcept { return static_cast<int>(a); }

/// True for `Axis::x`, `Axis::y` and `Axis::z`; false for a value forced out of range with a
/// cast (`static_cast<Axis>(7)`), which the functions taking an `Axis` turn into NaN results
/// rather than a silent identity.
constexpr bool is_valid(Axis a) noexcept { return index(a) >= 0 && index(a) <= 2; }

/// The letter of `a` ('x', 'y', 'z'; '?' for an invalid value).
constexpr char name(Axis a) noexcept { return is_valid(a) ? "xyz"[index(a)] : '?'; }

/// Checked conversion from a run-time index (0 = x, 1 = y, 2 = z). Errors: `invalid_argument`.
inline Result<Axis> axis_from_index(int i) {
  if (i < 0 || i > 2)
    return make_error(ErrorCode::invalid_argument, "axis index ", i,
                      " is out of range (expected 0 = x, 1 = y or 2 = z)");
  return static_cast<Axis>(i);
}

/// Checked conversion from a name: "x", "y", "z" (or "X", "Y", "Z"). Errors: `invalid_argument`.
inline Result<Axis> axis_from_name(const std::string& s) {
  if (s.size() == 1) {
    const char c = s[0];
    if (c == 'x' || c == 'X') return Axis::x;
    if (c == 'y' || c == 'Y') return Axis::y;
    if (c == 'z' || c == 'Z') return Axis::z;
  }
  return make_error(ErrorCode::invalid_argument, "axis name '", s, "' is not one of x, y, z");
}

} // namespace ebgeom

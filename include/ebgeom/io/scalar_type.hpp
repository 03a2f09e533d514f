// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `ScalarType`: the scalar types of PLY properties and VTK arrays, with their sizes.

#include <cstddef>
#include <cstdint>

#include "ebgeom/io/byte_reader.hpp"

namespace ebgeom::io {

/// A stored scalar type (`none` marks "no type", e.g. a scalar PLY property's list count type).
enum class ScalarType : std::uint8_t { none, i8, u8, i16, u16, i32, u32, i64, u64, f32, f64 };

/// Size in bytes of a binary `t` (0 for `none`).
inline std::size_t scalar_size(ScalarType t) noexcept {
  switch (t) {
  case ScalarType::i8:
  case ScalarType::u8:
    return 1;
  case ScalarType::i16:
  case ScalarType::u16:
    return 2;
  case ScalarType::i32:
  case ScalarType::u32:
  case ScalarType::f32:
    return 4;
  case ScalarType::i64:
  case ScalarType::u64:
  case ScalarType::f64:
    return 8;
  case ScalarType::none:
    break;
  }
  return 0;
}

inline bool is_integer(ScalarType t) noexcept {
  return t != ScalarType::none && t != ScalarType::f32 && t != ScalarType::f64;
}

namespace detail {

/// Loads a binary scalar of type `t` stored with byte order `e` at `p`, converted to `V`.
template <class V> EBGEOM_FORCE_INLINE V load_as(const char* p, ScalarType t, Endian e) noexcept {
  switch (t) {
  case ScalarType::i8:
    return V(load<std::int8_t>(p, e));
  case ScalarType::u8:
    return V(load<std::uint8_t>(p, e));
  case ScalarType::i16:
    return V(load<std::int16_t>(p, e));
  case ScalarType::u16:
    return V(load<std::uint16_t>(p, e));
  case ScalarType::i32:
    return V(load<std::int32_t>(p, e));
  case ScalarType::u32:
    return V(load<std::uint32_t>(p, e));
  case ScalarType::i64:
    return V(load<std::int64_t>(p, e));
  case ScalarType::u64:
    return V(load<std::uint64_t>(p, e));
  case ScalarType::f32:
    return V(load<float>(p, e));
  case ScalarType::f64:
    return V(load<double>(p, e));
  case ScalarType::none:
    break;
  }
  return V(0);
}

} // namespace detail
} // namespace ebgeom::io

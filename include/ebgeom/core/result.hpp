// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `Result<V, E>`: a value or an error (a small C++17 `expected`).

#include <type_traits>
#include <utility>
#include <variant>

#include "ebgeom/core/config.hpp"
#include "ebgeom/core/error.hpp"

namespace ebgeom {

/// Holds either a `V` or an `E` (`Error` by default; `ParseError` for readers).
/// `value()` on an error throws `ebgeom::Exception`, so tools may use exceptions while HPC callers
/// test `has_value()` first. `E` must have `code` and `what()`.
template <class V, class E = Error> class [[nodiscard]] Result {
 public:
  using value_type = V;
  using error_type = E;

  Result(V v) : data_(std::in_place_index<0>, std::move(v)) {}
  Result(E e) : data_(std::in_place_index<1>, std::move(e)) {}
  /// Converts from a compatible error type (e.g. ParseError into Error).
  template <class E2,
            class = std::enable_if_t<!std::is_same_v<E2, E> && std::is_convertible_v<E2, E> &&
                                     !std::is_convertible_v<E2, V>>>
  Result(E2 e) : data_(std::in_place_index<1>, E(std::move(e))) {}

  bool has_value() const noexcept { return data_.index() == 0; }
  explicit operator bool() const noexcept { return has_value(); }

  V& value() & {
    throw_if_error();
    return std::get<0>(data_);
  }
  const V& value() const& {
    throw_if_error();
    return std::get<0>(data_);
  }
  V&& value() && {
    throw_if_error();
    return std::get<0>(std::move(data_));
  }
  V& operator*() & noexcept { return *std::get_if<0>(&data_); }
  const V& operator*() const& noexcept { return *std::get_if<0>(&data_); }
  V* operator->() noexcept { return std::get_if<0>(&data_); }
  const V* operator->() const noexcept { return std::get_if<0>(&data_); }

  /// Precondition: `!has_value()`.
  const E& error() const& noexcept {
    EBGEOM_ASSERT(!has_value());
    return *std::get_if<1>(&data_);
  }
  E&& error() && noexcept {
    EBGEOM_ASSERT(!has_value());
    return std::move(*std::get_if<1>(&data_));
  }

  template <class U> V value_or(U&& fallback) const& {
    return has_value() ? std::get<0>(data_) : static_cast<V>(std::forward<U>(fallback));
  }

 private:
  void throw_if_error() const {
    if (!has_value()) {
      const E& e = *std::get_if<1>(&data_);
      throw Exception(e.code, e.what());
    }
  }
  std::variant<V, E> data_;
};

/// Result of an operation that produces nothing but may fail.
struct Ok {};

} // namespace ebgeom

// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `Span<T>`: a non-owning view of contiguous elements (a C++17 stand-in for `std::span`).

#include <array>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "ebgeom/core/config.hpp"

namespace ebgeom {

/// Pointer + size. Trivially copyable; never owns. `Span<const T>` converts from vectors, arrays
/// and `Span<T>`.
template <class T> class Span {
 public:
  using element_type = T;
  using value_type = std::remove_cv_t<T>;
  using size_type = std::size_t;
  using iterator = T*;

  constexpr Span() noexcept = default;
  constexpr Span(T* data, std::size_t size) noexcept : data_(data), size_(size) {}
  template <class U, class = std::enable_if_t<std::is_convertible_v<U (*)[], T (*)[]>>>
  constexpr Span(const Span<U>& other) noexcept : data_(other.data()), size_(other.size()) {}
  template <class A, class U = T, class = std::enable_if_t<std::is_const_v<U>>>
  Span(const std::vector<std::remove_const_t<U>, A>& v) noexcept
      : data_(v.data()), size_(v.size()) {}
  template <class A>
  Span(std::vector<std::remove_const_t<T>, A>& v) noexcept : data_(v.data()), size_(v.size()) {}
  template <std::size_t N> constexpr Span(T (&a)[N]) noexcept : data_(a), size_(N) {}
  template <class U, std::size_t N,
            class = std::enable_if_t<std::is_convertible_v<U (*)[], T (*)[]>>>
  constexpr Span(std::array<U, N>& a) noexcept : data_(a.data()), size_(N) {}
  template <class U, std::size_t N,
            class = std::enable_if_t<std::is_convertible_v<const U (*)[], T (*)[]>>>
  constexpr Span(const std::array<U, N>& a) noexcept : data_(a.data()), size_(N) {}

  constexpr T* data() const noexcept { return data_; }
  constexpr std::size_t size() const noexcept { return size_; }
  constexpr bool empty() const noexcept { return size_ == 0; }
  constexpr T& operator[](std::size_t i) const noexcept {
    EBGEOM_ASSERT(i < size_);
    return data_[i];
  }
  constexpr T* begin() const noexcept { return data_; }
  constexpr T* end() const noexcept { return data_ + size_; }
  constexpr T& front() const noexcept { return data_[0]; }
  constexpr T& back() const noexcept { return data_[size_ - 1]; }
  /// Elements [offset, offset + count).
  constexpr Span subspan(std::size_t offset, std::size_t count) const noexcept {
    EBGEOM_ASSERT(offset + count <= size_);
    return {data_ + offset, count};
  }
  constexpr Span first(std::size_t count) const noexcept { return subspan(0, count); }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
};

template <class T, class A> Span(std::vector<T, A>&) -> Span<T>;
template <class T, class A> Span(const std::vector<T, A>&) -> Span<const T>;

} // namespace ebgeom

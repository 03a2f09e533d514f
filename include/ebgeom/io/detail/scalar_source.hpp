// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Internal: value sources over an ASCII or a binary body, shared by the PLY and VTK readers.
/// Every read returns false on failure; `error(what...)` then explains it with the location.

#include <cmath>
#include <cstdint>

#include "ebgeom/io/byte_reader.hpp"
#include "ebgeom/io/scalar_type.hpp"
#include "ebgeom/io/text_reader.hpp"

namespace ebgeom::io::detail {

/// Whitespace-separated values (line breaks are ordinary whitespace). Errors carry the line.
class AsciiSource {
 public:
  explicit AsciiSource(TextReader& in) : in_(&in) {}
  template <class T> bool real(ScalarType, T& v) noexcept {
    st_ = in_->real(v);
    return st_ == NumberStatus::ok;
  }
  /// An integer; for a floating-point `t`, an integral value such as `3.0`.
  bool integer(ScalarType t, std::int64_t& v) noexcept {
    if (is_integer(t)) {
      st_ = in_->integer(v);
      return st_ == NumberStatus::ok;
    }
    double d;
    st_ = in_->real(d);
    if (st_ != NumberStatus::ok) return false;
    if (!(d >= -9.0e18 && d <= 9.0e18) || d != std::floor(d)) {
      st_ = NumberStatus::malformed;
      return false;
    }
    v = std::int64_t(d);
    return true;
  }
  bool skip(ScalarType) noexcept {
    if (in_->token().empty()) {
      st_ = NumberStatus::missing;
      return false;
    }
    return true;
  }
  std::uint64_t remaining() const noexcept { return std::uint64_t(in_->end() - in_->cur()); }
  template <class... A> ParseError error(const A&... what) const {
    return in_->number_error(st_, what...);
  }
  template <class... A> ParseError fail(ErrorCode code, const A&... parts) const {
    return in_->fail(code, parts...);
  }

 private:
  TextReader* in_;
  NumberStatus st_ = NumberStatus::ok;
};

/// Packed binary values with byte order `e`. Errors carry the byte offset of the value.
class BinarySource {
 public:
  BinarySource(ByteReader& in, Endian e) : in_(&in), e_(e) {}
  template <class T> bool real(ScalarType t, T& v) noexcept {
    mark_ = in_->offset();
    const std::size_t n = scalar_size(t);
    if (n > in_->remaining()) return false;
    v = load_as<T>(in_->data(), t, e_);
    in_->skip(n);
    return true;
  }
  bool integer(ScalarType t, std::int64_t& v) noexcept {
    mark_ = in_->offset();
    const std::size_t n = scalar_size(t);
    if (n > in_->remaining()) return false;
    if (t == ScalarType::u64) {
      const std::uint64_t u = load<std::uint64_t>(in_->data(), e_);
      if (u > std::uint64_t(INT64_MAX)) return bad_ = true, false;
      v = std::int64_t(u);
    } else if (is_integer(t)) {
      v = load_as<std::int64_t>(in_->data(), t, e_);
    } else {
      const double d = load_as<double>(in_->data(), t, e_);
      if (!(d >= -9.0e18 && d <= 9.0e18) || d != std::floor(d)) return bad_ = true, false;
      v = std::int64_t(d);
    }
    in_->skip(n);
    return true;
  }
  bool skip(ScalarType t) noexcept {
    mark_ = in_->offset();
    return in_->skip(scalar_size(t));
  }
  std::uint64_t remaining() const noexcept { return in_->remaining(); }
  ByteReader& reader() noexcept { return *in_; }
  Endian endian() const noexcept { return e_; }
  template <class... A> ParseError error(const A&... what) const {
    if (bad_) return in_->fail_at(mark_, ErrorCode::bad_number, what..., " is not a valid integer");
    return in_->fail_at(mark_, ErrorCode::truncated, "input ends where ", what..., " was expected");
  }
  template <class... A> ParseError fail(ErrorCode code, const A&... parts) const {
    return in_->fail_at(mark_, code, parts...);
  }

 private:
  ByteReader* in_;
  Endian e_;
  std::size_t mark_ = 0;
  bool bad_ = false;
};

} // namespace ebgeom::io::detail

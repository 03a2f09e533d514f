// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `ByteReader`: a bounds-checked cursor over binary data. Every read returns `bool` (false at the
/// end of the data, leaving the cursor where it was); nothing reads past the end.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

#include "ebgeom/core/config.hpp"
#include "ebgeom/io/parse_error.hpp"
#include "ebgeom/io/read_options.hpp"

namespace ebgeom::io {

/// Byte order of binary data.
enum class Endian : std::uint8_t { little, big };

namespace detail {

#if defined(__BYTE_ORDER__) && defined(__ORDER_BIG_ENDIAN__) &&                                    \
    __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
inline constexpr Endian host_endian = Endian::big;
#else
inline constexpr Endian host_endian = Endian::little;
#endif

/// Reverses the bytes of `n` consecutive scalars of `size` bytes each, in place.
inline void byte_swap(unsigned char* p, std::size_t size, std::size_t n) noexcept {
  for (std::size_t k = 0; k < n; ++k, p += size)
    for (std::size_t i = 0; i < size / 2; ++i) {
      const unsigned char t = p[i];
      p[i] = p[size - 1 - i];
      p[size - 1 - i] = t;
    }
}

/// Loads a scalar `V` stored with byte order `e` at `p` (no alignment needed).
template <class V> EBGEOM_FORCE_INLINE V load(const char* p, Endian e) noexcept {
  static_assert(std::is_arithmetic_v<V>, "load<V> needs an arithmetic V");
  V v;
  std::memcpy(&v, p, sizeof(V));
  if (sizeof(V) > 1 && e != host_endian)
    byte_swap(reinterpret_cast<unsigned char*>(&v), sizeof(V), 1);
  return v;
}

/// Appends scalar `v` with byte order `e` to `out` (a std::string used as a byte buffer).
template <class V> inline void store(std::string& out, V v, Endian e) {
  static_assert(std::is_arithmetic_v<V>, "store<V> needs an arithmetic V");
  char b[sizeof(V)];
  std::memcpy(b, &v, sizeof(V));
  if (sizeof(V) > 1 && e != host_endian)
    byte_swap(reinterpret_cast<unsigned char*>(b), sizeof(V), 1);
  out.append(b, sizeof(V));
}

} // namespace detail

/// Cursor over `bytes` that knows the input's name for error messages. Errors made with `fail`
/// carry the current byte offset (plus `base` when the view starts inside a larger file).
class ByteReader {
 public:
  ByteReader(ByteView bytes, const std::string& path, std::size_t base = 0) noexcept
      : data_(bytes.data()), size_(bytes.size()), path_(&path), base_(base) {}

  std::size_t offset() const noexcept { return pos_; }
  std::size_t size() const noexcept { return size_; }
  std::size_t remaining() const noexcept { return size_ - pos_; }
  bool at_end() const noexcept { return pos_ == size_; }
  /// Pointer to the current byte; valid for `remaining()` bytes.
  const char* data() const noexcept { return data_ + pos_; }
  const std::string& path() const noexcept { return *path_; }

  /// Moves to absolute offset `off`; false (and no move) when `off > size()`.
  bool seek(std::size_t off) noexcept {
    if (off > size_) return false;
    pos_ = off;
    return true;
  }
  bool skip(std::size_t n) noexcept {
    if (n > remaining()) return false;
    pos_ += n;
    return true;
  }
  /// Reads a scalar or a C array of scalars stored with byte order `e`.
  template <class V> bool read(V& v, Endian e) noexcept {
    static_assert(std::is_trivially_copyable_v<V>, "read needs a trivially copyable V");
    if (sizeof(V) > remaining()) return false;
    std::memcpy(&v, data_ + pos_, sizeof(V));
    if constexpr (std::is_array_v<V>) {
      using S = std::remove_all_extents_t<V>;
      if (sizeof(S) > 1 && e != detail::host_endian)
        detail::byte_swap(reinterpret_cast<unsigned char*>(&v), sizeof(S), sizeof(V) / sizeof(S));
    } else {
      if (sizeof(V) > 1 && e != detail::host_endian)
        detail::byte_swap(reinterpret_cast<unsigned char*>(&v), sizeof(V), 1);
    }
    pos_ += sizeof(V);
    return true;
  }
  template <class V> bool read_le(V& v) noexcept { return read(v, Endian::little); }
  template <class V> bool read_be(V& v) noexcept { return read(v, Endian::big); }

  /// An error at the current offset.
  template <class... A> ParseError fail(ErrorCode code, const A&... parts) const {
    return make_parse_error(code, *path_, base_ + pos_, 0, parts...);
  }
  /// An error at offset `off` of this view.
  template <class... A>
  ParseError fail_at(std::size_t off, ErrorCode code, const A&... parts) const {
    return make_parse_error(code, *path_, base_ + off, 0, parts...);
  }

 private:
  const char* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  const std::string* path_;
  std::size_t base_;
};

} // namespace ebgeom::io

// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Internal: welding of bit-identical vertices while a reader appends them (STL stores three
/// vertices per triangle). An open-addressing hash table of vertex indices; no stability promise.

#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "ebgeom/core/vec.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"

namespace ebgeom::io::detail {

/// Maps coordinates to vertex indices: `insert(p)` returns the index of a vertex equal to `p`
/// (bitwise, after turning -0 into +0) or appends `p` to `vertices` and returns its new index.
/// Amortised O(1); the table has at most 50% load.
template <class T> class ExactWelder {
 public:
  explicit ExactWelder(std::vector<Vec3<T>>& vertices, std::size_t expected = 0)
      : vertices_(&vertices) {
    std::size_t cap = 64;
    while (cap < 2 * expected) cap *= 2;
    slots_.assign(cap, empty);
    mask_ = cap - 1;
    for (std::size_t i = 0; i < vertices.size(); ++i) place(Index(i));
  }

  /// `p` with -0 turned into +0, the form in which vertices are stored and compared.
  static Vec3<T> canonical(Vec3<T> p) noexcept {
    p.x += T(0); // -0 + 0 == +0: equal values weld whatever their sign bit
    p.y += T(0);
    p.z += T(0);
    return p;
  }
  /// Hash of a canonical point (see `insert_canonical`).
  static std::size_t hash(const Vec3<T>& p) noexcept {
    std::uint64_t h = std::uint64_t(bits(p.x)) * 0x9E3779B97F4A7C15ull;
    h ^= std::uint64_t(bits(p.y)) * 0xC2B2AE3D27D4EB4Full;
    h ^= std::uint64_t(bits(p.z)) * 0x165667B19E3779F9ull;
    h ^= h >> 29;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 32;
    return std::size_t(h);
  }
  /// Hints the cache about the slot of hash `h` (and the vertex it holds): batch callers call
  /// this for a few points ahead of `insert_canonical`, hiding the table's cache misses.
  void prefetch(std::size_t h) const noexcept {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(slots_.data() + (h & mask_));
#else
    (void)h;
#endif
  }
  void prefetch_vertex(std::size_t h) const noexcept {
#if defined(__GNUC__) || defined(__clang__)
    const Index s = slots_[h & mask_];
    if (s != empty) __builtin_prefetch(vertices_->data() + s);
#else
    (void)h;
#endif
  }

  Index insert(const Vec3<T>& p) {
    const Vec3<T> c = canonical(p);
    return insert_canonical(c, hash(c));
  }
  /// `insert` for a point already in canonical form whose hash is `h`.
  Index insert_canonical(const Vec3<T>& p, std::size_t hp) {
    std::size_t h = hp & mask_;
    const Vec3<T>* v = vertices_->data();
    for (;;) {
      const Index s = slots_[h];
      if (s == empty) break;
      if (same_bits(v[s], p)) return s;
      h = (h + 1) & mask_;
    }
    const Index idx = Index(vertices_->size());
    vertices_->push_back(p);
    slots_[h] = idx;
    if (2 * vertices_->size() > slots_.size()) grow();
    return idx;
  }

 private:
  static constexpr Index empty = std::numeric_limits<Index>::max();
  using Bits = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;

  static Bits bits(T x) noexcept {
    Bits b;
    std::memcpy(&b, &x, sizeof(T));
    return b;
  }
  static bool same_bits(const Vec3<T>& a, const Vec3<T>& b) noexcept {
    return bits(a.x) == bits(b.x) && bits(a.y) == bits(b.y) && bits(a.z) == bits(b.z);
  }
  void place(Index i) {
    std::size_t h = hash((*vertices_)[i]) & mask_;
    while (slots_[h] != empty) h = (h + 1) & mask_;
    slots_[h] = i;
  }
  void grow() {
    slots_.assign(slots_.size() * 2, empty);
    mask_ = slots_.size() - 1;
    for (std::size_t i = 0; i < vertices_->size(); ++i) place(Index(i));
  }

  std::vector<Vec3<T>>* vertices_;
  std::vector<Index> slots_;
  std::size_t mask_ = 0;
};

} // namespace ebgeom::io::detail

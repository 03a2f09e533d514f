// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/bvh/build.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <set>
#include <vector>

#include "ebgeom/bvh/wide_bvh.hpp"
#include "test_support.hpp"

using namespace ebgeom;
using namespace ebgeom::bvh;

namespace {
/// Random small boxes (some degenerate) in [-1, 1]^3.
template <class T> std::vector<Aabb<T>> random_boxes(std::size_t n, std::uint64_t seed = 7) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), s(0, 0.05);
  std::vector<Aabb<T>> b(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3<T> c{T(u(rng)), T(u(rng)), T(u(rng))};
    const Vec3<T> h = i % 7 == 0 ? Vec3<T>::zero() : Vec3<T>{T(s(rng)), T(s(rng)), T(s(rng))};
    b[i] = {c - h, c + h};
  }
  return b;
}
template <class T> std::vector<Vec3<T>> centers(const std::vector<Aabb<T>>& b) {
  std::vector<Vec3<T>> c;
  for (const auto& x : b) c.push_back(x.center());
  return c;
}

/// Checks a builder tree: permutation, leaf coverage, boxes contain their contents, arity.
template <class T>
void check_tree(const BuildTree<T>& t, const std::vector<Aabb<T>>& boxes, std::uint32_t max_leaf,
                bool exact_leaf_size) {
  const std::size_t n = boxes.size();
  ASSERT_EQ(t.prim.size(), n);
  std::vector<std::uint32_t> sorted = t.prim;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(sorted[i], i);
  std::vector<int> covered(n, 0);
  for (const auto& node : t.nodes) {
    if (node.is_leaf()) {
      ASSERT_GE(node.count, 1u);
      if (exact_leaf_size) {
        EXPECT_LE(node.count, max_leaf);
      }
      for (std::uint32_t s = node.first; s < node.first + node.count; ++s) {
        ++covered[s];
        EXPECT_TRUE(node.box.contains(boxes[t.prim[s]]));
      }
    } else {
      ASSERT_GE(node.children, 2u);
      ASSERT_LE(node.children, std::uint32_t(max_build_children));
      for (std::uint32_t c = node.first; c < node.first + node.children; ++c)
        EXPECT_TRUE(node.box.contains(t.nodes[c].box));
    }
  }
  for (std::size_t s = 0; s < n; ++s) EXPECT_EQ(covered[s], 1) << "slot " << s;
  EXPECT_LE(t.depth, max_build_depth + 1);
}

/// Checks a flattened tree: every slot in exactly one leaf, child boxes contain the primitives,
/// pre-order layout, depth within the proven stack bound.
template <class T, int K>
void check_wide(const WideBvh<T, K>& w, const std::vector<Aabb<T>>& boxes) {
  const std::size_t n = boxes.size();
  std::vector<int> covered(n, 0);
  auto leaf = [&](const ChildRef& r, const Aabb<T>& box) {
    for (std::uint32_t s = r.index; s < r.index + r.count; ++s) {
      ++covered[s];
      EXPECT_TRUE(box.contains(boxes[w.prim[s]]));
    }
  };
  if (w.root.is_leaf()) leaf(w.root, w.box);
  for (std::size_t i = 0; i < w.nodes.size(); ++i) {
    const auto& node = w.nodes[i];
    for (int k = 0; k < K; ++k) {
      const ChildRef r = node.child[k];
      if (r.is_leaf()) leaf(r, node.child_box(k));
      if (r.is_inner()) {
        EXPECT_GT(r.index, i); // pre-order
        EXPECT_TRUE(node.child_box(k).contains(w.nodes[r.index].bounds()));
      }
      if (r.is_empty()) {
        EXPECT_TRUE(node.child_box(k).is_empty());
      }
    }
  }
  for (std::size_t s = 0; s < n; ++s) EXPECT_EQ(covered[s], 1) << "slot " << s;
  EXPECT_LE(w.depth, (WideBvh<T, K>::max_depth));
}
} // namespace

template <class T> class BuildTest : public ::testing::Test {};
TYPED_TEST_SUITE(BuildTest, test::FloatTypes);

TYPED_TEST(BuildTest, EveryBuilderMakesAValidTree) {
  using T = TypeParam;
  for (std::size_t n : {1u, 2u, 5u, 100u, 3000u}) {
    const auto boxes = random_boxes<T>(n);
    const auto cent = centers(boxes);
    const Span<const Aabb<T>> B(boxes);
    const Span<const Vec3<T>> C(cent);
    for (BuildMethod m : {BuildMethod::sah_binned, BuildMethod::median, BuildMethod::morton}) {
      BuildOptions o;
      o.method = m;
      o.max_leaf_size = 3;
      const auto t = build(B, C, o);
      check_tree(t, boxes, 3, true);
      check_wide(flatten<2>(t), boxes);
      check_wide(flatten<4>(t), boxes);
      check_wide(flatten<8>(t), boxes);
    }
    const auto chunk = build_top_down<T>(B, C, ChunkPartition<8>{}, LeafSizeStop{4});
    check_tree(chunk, boxes, 4, true);
    check_wide(flatten<2>(chunk), boxes); // 8-ary tree regrouped into binary nodes
    check_wide(flatten<4>(chunk), boxes);
    check_wide(flatten<8>(chunk), boxes);
  }
}

TYPED_TEST(BuildTest, FastSahBuildEqualsTheGenericSahBuild) {
  using T = TypeParam;
  // build_sah must make build_top_down(SahPartition, LeafSizeStop)'s tree: same nodes in the same
  // order, same boxes, same primitives in every leaf (their order inside a leaf may differ).
  auto expect_same = [](const BuildTree<T>& a, const BuildTree<T>& b) {
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    EXPECT_EQ(a.depth, b.depth);
    for (std::size_t i = 0; i < a.nodes.size(); ++i) {
      const auto &x = a.nodes[i], &y = b.nodes[i];
      ASSERT_EQ(x.first, y.first) << "node " << i;
      ASSERT_EQ(x.count, y.count) << "node " << i;
      ASSERT_EQ(x.children, y.children) << "node " << i;
      EXPECT_EQ(x.box, y.box) << "node " << i;
      if (!x.is_leaf()) continue;
      std::vector<std::uint32_t> p(a.prim.begin() + x.first, a.prim.begin() + x.first + x.count);
      std::vector<std::uint32_t> q(b.prim.begin() + y.first, b.prim.begin() + y.first + y.count);
      std::sort(p.begin(), p.end());
      std::sort(q.begin(), q.end());
      ASSERT_EQ(p, q) << "leaf " << i;
    }
  };
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> cell(0, 9);
  for (int input = 0; input < 4; ++input) {
    std::vector<Aabb<T>> boxes = random_boxes<T>(input == 0 ? 3000 : 2000, 5 + input);
    std::vector<Vec3<T>> cent = centers(boxes);
    if (input == 1) // centroids that are not the box centres (the builder must use the given ones)
      for (std::size_t i = 0; i < cent.size(); i += 3) cent[i] = boxes[i].lo;
    if (input == 2) // many coincident centroids on a coarse lattice, and a run of identical boxes
      for (std::size_t i = 0; i < cent.size(); ++i) {
        const Vec3<T> c{T(cell(rng)), T(cell(rng) / 5), T(0)};
        boxes[i] =
            i < 500 ? Aabb<T>::of({0, 0, 0}, {1, 1, 1}) : Aabb<T>::of(c, c + Vec3<T>{1, 1, 1});
        cent[i] = boxes[i].center();
      }
    if (input == 3) // subnormal extents: bins per unit length would overflow
      for (std::size_t i = 0; i < cent.size(); ++i) {
        const T tiny = std::numeric_limits<T>::denorm_min();
        boxes[i] = Aabb<T>::of(Vec3<T>{T(i % 3), T(i % 5), T(i % 7)} * tiny);
        cent[i] = boxes[i].center();
      }
    const Span<const Aabb<T>> B(boxes);
    const Span<const Vec3<T>> C(cent);
    struct Case {
      int bins;
      std::uint32_t block, leaf, above;
    };
    for (const Case c :
         {Case{16, 1, 1, 1024}, Case{16, 1, 4, 0}, Case{16, 8, 8, 1024}, Case{16, 8, 8, ~0u},
          Case{4, 4, 4, 64}, Case{32, 8, 4, 100}, Case{2, 1, 2, 1024}, Case{64, 4, 16, 0}}) {
      const SahPartition sah{c.bins, c.block, c.above};
      const auto fast = build_sah<T>(B, C, sah, c.leaf);
      SCOPED_TRACE(testing::Message()
                   << "input " << input << " bins " << c.bins << " block " << c.block << " leaf "
                   << c.leaf << " longest axis above " << c.above);
      expect_same(fast, build_top_down<T>(B, C, sah, LeafSizeStop{c.leaf}));
      check_tree(fast, boxes, c.leaf, true);
    }
  }
}

TYPED_TEST(BuildTest, ChunkPartitionMakesKEqualChunksAlongTheLongestAxis) {
  using T = TypeParam;
  std::vector<Aabb<T>> boxes;
  for (int i = 0; i < 64; ++i) boxes.push_back(Aabb<T>::of({T(63 - i), T(0.5), T(0)})); // x axis
  const auto cent = centers(boxes);
  const auto t = build_top_down<T>(Span<const Aabb<T>>(boxes), Span<const Vec3<T>>(cent),
                                   ChunkPartition<4>{}, LeafSizeStop{4});
  ASSERT_EQ(t.nodes[0].children, 4u);
  for (std::uint32_t c = 0; c < 4; ++c) {
    const auto& ch = t.nodes[t.nodes[0].first + c];
    // chunk c holds x in [16c, 16c + 15]
    EXPECT_EQ(ch.box.lo.x, T(16 * c));
    EXPECT_EQ(ch.box.hi.x, T(16 * c + 15));
  }
  check_tree(t, boxes, 4, true);
}

TYPED_TEST(BuildTest, UserPartitionAndStopFunctionsDriveTheBuild) {
  using T = TypeParam;
  const auto boxes = random_boxes<T>(500);
  const auto cent = centers(boxes);
  int calls = 0;
  // A ternary partition by slot order (not geometric at all) and a depth-based stop.
  auto part = [&](const PartitionInput<T>&, std::uint32_t*, std::uint32_t n) {
    ++calls;
    Parts p;
    p.count = 3;
    p.ends[0] = n / 3;
    p.ends[1] = 2 * n / 3;
    p.ends[2] = n;
    return p;
  };
  auto stop = [](const PartitionInput<T>& in, std::uint32_t n) { return in.depth >= 3 || n < 2; };
  const auto t =
      build_top_down<T>(Span<const Aabb<T>>(boxes), Span<const Vec3<T>>(cent), part, stop);
  EXPECT_GT(calls, 0);
  EXPECT_EQ(t.depth, 4);
  EXPECT_EQ(t.nodes[0].children, 3u);
  check_tree(t, boxes, 0, false);
  check_wide(flatten<4>(t), boxes);
}

TYPED_TEST(BuildTest, BadPartitionsFallBackToAMedianSplit) {
  using T = TypeParam;
  const auto boxes = random_boxes<T>(300);
  const auto cent = centers(boxes);
  // Returns everything in one part, or nonsense ends: the builder must still terminate.
  auto lazy = [](const PartitionInput<T>&, std::uint32_t*, std::uint32_t n) {
    Parts p;
    p.count = 1;
    p.ends[0] = n;
    return p;
  };
  auto liar = [](const PartitionInput<T>&, std::uint32_t*, std::uint32_t n) {
    Parts p;
    p.count = 2;
    p.ends[0] = n + 5;
    p.ends[1] = n;
    return p;
  };
  check_tree(build_top_down<T>(Span<const Aabb<T>>(boxes), Span<const Vec3<T>>(cent), lazy,
                               LeafSizeStop{2}),
             boxes, 2, true);
  check_tree(build_top_down<T>(Span<const Aabb<T>>(boxes), Span<const Vec3<T>>(cent), liar,
                               LeafSizeStop{2}),
             boxes, 2, true);
}

TYPED_TEST(BuildTest, DegenerateInputs) {
  using T = TypeParam;
  // Empty.
  const std::vector<Aabb<T>> none;
  const std::vector<Vec3<T>> nc;
  const auto e = flatten<4>(build(Span<const Aabb<T>>(none), Span<const Vec3<T>>(nc)));
  EXPECT_TRUE(e.root.is_empty());
  EXPECT_TRUE(e.nodes.empty());
  // All centroids equal (200,000 identical boxes): median fallback keeps the depth logarithmic.
  const std::vector<Aabb<T>> same(200000, Aabb<T>::of({0, 0, 0}, {1, 1, 1}));
  const auto sc = centers(same);
  for (BuildMethod m : {BuildMethod::sah_binned, BuildMethod::median, BuildMethod::morton}) {
    BuildOptions o;
    o.method = m;
    const auto t = build(Span<const Aabb<T>>(same), Span<const Vec3<T>>(sc), o);
    EXPECT_LE(t.depth, 20);
    const auto w = flatten<4>(t);
    EXPECT_LE(w.depth, 20);
    std::size_t leaves = 0, prims = 0;
    for (const auto& n : w.nodes)
      for (const auto& c : n.child)
        if (c.is_leaf()) ++leaves, prims += c.count;
    EXPECT_EQ(prims, same.size());
    EXPECT_GT(leaves, same.size() / 4 - 1);
  }
}

TEST(Morton, CodesInterleaveBitsAndOrderAlongTheCurve) {
  const Aabb<double> box = Aabb<double>::of({0, 0, 0}, {1, 1, 1});
  EXPECT_EQ(morton_code(Vec3<double>{0, 0, 0}, box), 0u);
  const double cell = 1.0 / 2097152.0;
  EXPECT_EQ(morton_code(Vec3<double>{cell * 1.5, 0, 0}, box), 1u);
  EXPECT_EQ(morton_code(Vec3<double>{0, cell * 1.5, 0}, box), 2u);
  EXPECT_EQ(morton_code(Vec3<double>{0, 0, cell * 1.5}, box), 4u);
  EXPECT_EQ(morton_code(Vec3<double>{1, 1, 1}, box), (std::uint64_t(1) << 63) - 1);
}

// build_morton (radix sort, topology top down, boxes bottom up) against a reference built the
// straightforward way: (code, index) pairs sorted with std::sort, then build_top_down with a
// partition that cuts each sorted range at its highest differing bit (the middle for equal codes).
template <class T>
BuildTree<T> morton_reference(const std::vector<Aabb<T>>& boxes, const std::vector<Vec3<T>>& cent,
                              std::uint32_t leaf) {
  Aabb<T> cbox;
  for (const auto& c : cent) cbox.extend(c);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(boxes.size());
  for (std::uint32_t i = 0; i < keys.size(); ++i) keys[i] = {morton_code(cent[i], cbox), i};
  std::sort(keys.begin(), keys.end());
  std::vector<Aabb<T>> sb;
  std::vector<Vec3<T>> sc;
  std::vector<std::uint64_t> codes;
  for (const auto& k : keys)
    sb.push_back(boxes[k.second]), sc.push_back(cent[k.second]), codes.push_back(k.first);
  auto split = [&](const PartitionInput<T>&, std::uint32_t* idx, std::uint32_t cnt) {
    Parts p;
    p.count = 2;
    p.ends[1] = cnt;
    const std::uint64_t a = codes[idx[0]], b = codes[idx[cnt - 1]];
    if (a == b) {
      p.ends[0] = cnt / 2;
      return p;
    }
    int bit = 63;
    while (!(((a ^ b) >> bit) & 1)) --bit;
    std::uint32_t i = 0;
    while (((codes[idx[i]] >> bit) & 1) == 0) ++i;
    p.ends[0] = i;
    return p;
  };
  BuildTree<T> t = build_top_down<T>(Span<const Aabb<T>>(sb), Span<const Vec3<T>>(sc), split,
                                     LeafSizeStop{leaf});
  for (auto& p : t.prim) p = keys[p].second;
  return t;
}

TYPED_TEST(BuildTest, MortonEqualsTopDownReference) {
  using T = TypeParam;
  // Random boxes (radix path above 4,096), a coarse lattice with many equal codes, few boxes.
  std::vector<std::vector<Aabb<T>>> inputs = {random_boxes<T>(20000), random_boxes<T>(300)};
  std::vector<Aabb<T>> lattice;
  for (int i = 0; i < 9000; ++i) {
    const T x = T(i % 7), y = T(i / 7 % 5), z = T(i % 3);
    lattice.push_back(Aabb<T>::of({x, y, z}, {x + T(1), y + T(1), z + T(1)}));
  }
  inputs.push_back(lattice);
  for (const auto& boxes : inputs)
    for (std::uint32_t leaf : {1u, 4u, 8u}) {
      const auto cent = centers(boxes);
      const BuildTree<T> got =
          build_morton(Span<const Aabb<T>>(boxes), Span<const Vec3<T>>(cent), leaf);
      const BuildTree<T> ref = morton_reference(boxes, cent, leaf);
      ASSERT_EQ(got.nodes.size(), ref.nodes.size());
      EXPECT_EQ(got.prim, ref.prim);
      EXPECT_EQ(got.depth, ref.depth);
      for (std::size_t i = 0; i < got.nodes.size(); ++i) {
        const auto &g = got.nodes[i], &r = ref.nodes[i];
        ASSERT_EQ(g.first, r.first) << i;
        ASSERT_EQ(g.count, r.count) << i;
        ASSERT_EQ(g.children, r.children) << i;
        for (int a = 0; a < 3; ++a) {
          ASSERT_EQ(g.box.lo[a], r.box.lo[a]) << i;
          ASSERT_EQ(g.box.hi[a], r.box.hi[a]) << i;
        }
      }
    }
}

TEST(Refit, BoxesFollowMovedPrimitives) {
  auto boxes = random_boxes<double>(1000);
  const auto cent = centers(boxes);
  auto w = flatten<4>(build(Span<const Aabb<double>>(boxes), Span<const Vec3<double>>(cent)));
  for (auto& b : boxes)
    b = {b.lo * 2.0 + Vec3<double>{3, 0, 0}, b.hi * 2.0 + Vec3<double>{3, 0, 0}};
  refit(w, [&](std::uint32_t first, std::uint32_t count) {
    Aabb<double> b;
    for (std::uint32_t s = first; s < first + count; ++s) b.extend(boxes[w.prim[s]]);
    return b;
  });
  check_wide(w, boxes);
  Aabb<double> all;
  for (const auto& b : boxes) all.extend(b);
  EXPECT_EQ(w.box, all);
}

// A `BuildMethod` value outside the enumeration: `check` reports it, and `build` stops with a
// message in every build instead of silently building with SAH.
TEST(BuildDeathTest, OutOfRangeMethodIsLoud) {
  const auto boxes = random_boxes<double>(50);
  const auto cent = centers(boxes);
  BuildOptions o;
  EXPECT_EQ(check(o).code, ErrorCode::ok);
  o.method = static_cast<BuildMethod>(7);
  EXPECT_FALSE(is_valid(o.method));
  EXPECT_EQ(check(o).code, ErrorCode::invalid_argument);
  EXPECT_NE(check(o).message.find("BuildMethod value 7"), std::string::npos);
  EXPECT_DEATH((void)build(Span<const Aabb<double>>(boxes), Span<const Vec3<double>>(cent), o),
               "BuildMethod value out of range");
}

// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Run-time instruction-set dispatch (core/isa.hpp): every instruction set this CPU runs gives the
// brute force's values bit for bit, per point and per 8^3 tile; the choice follows `set_isa` and
// the EBGEOM_ISA environment variable (the ctest entries isa.<name>.* run the mesh SDF tests
// under each).

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "ebgeom/core/isa.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "test_support.hpp"

using namespace ebgeom;

namespace {
template <class T> bool same_bits(T a, T b) { return std::memcmp(&a, &b, sizeof(T)) == 0; }

/// The instruction sets `set_isa` accepts here (baseline always), restoring the active one.
std::vector<Isa> runnable_isas() {
  const Isa was = active_isa();
  std::vector<Isa> v;
  for (Isa i : {Isa::baseline, Isa::avx2, Isa::avx512})
    if (set_isa(i)) v.push_back(i);
  set_isa(was);
  return v;
}

/// A torus with its vertices moved at random (no symmetry, many near-ties), as a soup.
template <class T> PolygonSoup<T> bumpy_torus() {
  PolygonSoup<T> s = make_torus<T>(T(1), T(0.35), 40, 20).value();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  for (auto& v : s.vertices) v += Vec3<T>{T(u(rng)), T(u(rng)), T(u(rng))};
  return s;
}
} // namespace

template <class T> class IsaDispatchTest : public ::testing::Test {};
TYPED_TEST_SUITE(IsaDispatchTest, test::FloatTypes);

TEST(IsaDispatch, SetIsaChoosesAmongTheRunnableInstructionSets) {
  const Isa was = active_isa();
  EXPECT_LE(int(was), int(detected_isa()));
  EXPECT_TRUE(set_isa(Isa::baseline) || !EBGEOM_ISA_DISPATCH);
  for (Isa i : {Isa::baseline, Isa::avx2, Isa::avx512}) {
    const bool ok = set_isa(i);
    EXPECT_EQ(ok, int(i) <= int(detected_isa()) && (EBGEOM_ISA_DISPATCH || i == native_isa))
        << to_string(i);
    if (ok) {
      EXPECT_EQ(active_isa(), i);
      with_active_isa([&](auto isa) { EXPECT_EQ(decltype(isa)::value, i); });
    }
  }
  set_isa(was);
  EXPECT_EQ(active_isa(), was);
}

// EBGEOM_ISA names the instruction set (capped at what the CPU runs); the ctest entries
// isa.<name>.* set it.
TEST(IsaDispatch, EnvironmentVariableCapsTheChoice) {
  const char* e = std::getenv("EBGEOM_ISA");
  if (e == nullptr) {
    EXPECT_EQ(detail::isa_from_environment(), detected_isa());
    return;
  }
  for (Isa i : {Isa::baseline, Isa::avx2, Isa::avx512})
    if (std::string(e) == to_string(i)) {
      const Isa want = int(i) < int(detected_isa()) ? i : detected_isa();
      EXPECT_EQ(detail::isa_from_environment(), want);
      if (EBGEOM_ISA_DISPATCH) { // no test here calls set_isa first
        EXPECT_EQ(active_isa(), want);
      }
    }
}

namespace {
/// `MeshSdf<T, K>` on every runnable instruction set: single queries and one lattice tile equal
/// the brute force bit for bit.
template <class T, int K> void every_isa_equals_the_brute_force() {
  const Isa was = active_isa();
  for (const PolygonSoup<T>& soup : {bumpy_torus<T>(), make_icosphere<T>(3).value()}) {
    const auto sdf = MeshSdf<T, K>::build(soup).value();
    const auto ref = BruteForceMeshSdf<T>::build(soup).value();
    const Aabb<T> box = sdf.bounds().grown(T(0.3));
    const auto pts = test::random_points(box, 3000, 11);
    // One 8^3 tile of a lattice crossing the surface.
    std::vector<Vec3<T>> tile;
    for (int z = 0; z < 8; ++z)
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
          tile.push_back(Vec3<T>{T(0.6), T(-0.2), T(-0.3)} + Vec3<T>{T(x), T(y), T(z)} * T(0.09));
    for (Isa isa : runnable_isas()) {
      ASSERT_TRUE(set_isa(isa));
      for (const auto& p : pts) {
        const auto a = sdf.closest(p), b = ref.closest(p);
        ASSERT_TRUE(same_bits(a.distance, b.distance))
            << to_string(isa) << " K " << K << " p=" << p << ": " << a.distance << " vs "
            << b.distance;
        ASSERT_EQ(a.triangle, b.triangle) << to_string(isa);
        ASSERT_TRUE(same_bits(sdf.unsigned_distance(p), std::abs(b.distance))) << to_string(isa);
      }
      std::vector<T> out(tile.size());
      sdf.eval_lattice(tile, {8, 8, 8}, out);
      for (std::size_t l = 0; l < tile.size(); ++l)
        ASSERT_TRUE(same_bits(out[l], ref(tile[l]))) << to_string(isa) << " sample " << l;
      sdf.unsigned_lattice(tile, {8, 8, 8}, out);
      for (std::size_t l = 0; l < tile.size(); ++l)
        ASSERT_TRUE(same_bits(out[l], std::abs(ref(tile[l]))))
            << to_string(isa) << " unsigned sample " << l;
    }
  }
  set_isa(was);
}
} // namespace

TYPED_TEST(IsaDispatchTest, EveryInstructionSetEqualsTheBruteForceBitForBit) {
  every_isa_equals_the_brute_force<TypeParam, default_arity<TypeParam>>();
}

// The wider nodes a user may choose (16 floats or 8 doubles: one AVX-512 register per coordinate).
TYPED_TEST(IsaDispatchTest, WideNodesEqualTheBruteForceBitForBitOnEveryInstructionSet) {
  every_isa_equals_the_brute_force<TypeParam, 2 * default_arity<TypeParam>>();
}

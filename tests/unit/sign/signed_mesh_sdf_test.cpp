// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// SignedMeshSdf on watertight meshes: every signed mode agrees with pseudonormal away from the
// surface, the magnitude is MeshSdf's to the last bit, and `automatic` picks pseudonormal.
#include "ebgeom/sdf/signed_mesh_sdf.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "sign_support.hpp"
#include "test_support.hpp"

namespace ebgeom {
namespace {

template <class T> bool same_bits(T a, T b) { return std::memcmp(&a, &b, sizeof(T)) == 0; }

template <class T> class SignedMeshSdfTest : public ::testing::Test {};
TYPED_TEST_SUITE(SignedMeshSdfTest, test::FloatTypes);

constexpr SignMode all_modes[] = {SignMode::pseudonormal, SignMode::winding, SignMode::fast_winding,
                                  SignMode::unsigned_distance, SignMode::automatic};

template <class T> std::vector<PolygonSoup<T>> watertight() {
  return {make_icosphere<T>(3).value(), make_torus<T>(1, T(0.3)).value(),
          make_cube<T>(T(0.5)).value(), make_torus<T>(T(0.7), T(0.2), 24, 12).value()};
}

template <class T> SignedMeshSdf<T> with_mode(const PolygonSoup<T>& s, SignMode m) {
  SignOptions o;
  o.mode = m;
  return SignedMeshSdf<T>::build(s, o).value();
}

TYPED_TEST(SignedMeshSdfTest, EverySignedModeAgreesWithPseudonormalOnWatertightMeshes) {
  using T = TypeParam;
  for (const auto& soup : watertight<T>()) {
    const auto ref = MeshSdf<T>::build(soup).value();
    const auto pts = test::random_points(ref.bounds().grown(T(0.4)), 2000, 13);
    for (SignMode m : all_modes) {
      const auto s = with_mode(soup, m);
      int compared = 0;
      for (const auto& p : pts) {
        const T r = ref(p), v = s(p);
        ASSERT_EQ(std::abs(v), std::abs(r)) << to_string(m) << " " << p; // bit for bit
        if (std::abs(r) < T(1e-3)) continue; // float noise at the surface
        ++compared;
        if (m == SignMode::unsigned_distance)
          EXPECT_GE(v, T(0));
        else
          EXPECT_EQ(v, r) << to_string(m) << " at " << p;
      }
      EXPECT_GT(compared, 1500);
    }
  }
}

TYPED_TEST(SignedMeshSdfTest, BoundedIsTheValueWithinItsBoundInEveryMode) {
  using T = TypeParam;
  static_assert(has_bounded_query_v<SignedMeshSdf<T>>);
  const PolygonSoup<T> ball = make_icosphere<T>(3).value();
  for (const PolygonSoup<T>& soup : {ball, test::remove_cap(ball, T(0.3))}) {
    for (SignMode m : all_modes) {
      const auto s = with_mode(soup, m);
      int within = 0, beyond = 0;
      for (const auto& p : test::random_points(s.bounds().grown(T(0.5)), 1500, 29)) {
        const T v = s(p);
        for (T bound : {T(0.02), T(0.1), T(0.3), std::abs(v)}) {
          const T b = s.bounded(p, bound);
          if (std::abs(v) <= bound) {
            ++within;
            ASSERT_TRUE(b == v && std::signbit(b) == std::signbit(v))
                << to_string(m) << " " << p << ": " << b << " vs " << v;
          } else {
            ++beyond;
            ASSERT_GT(std::abs(b), bound) << to_string(m) << " " << p;
          }
        }
      }
      EXPECT_GT(within, 1500);
      EXPECT_GT(beyond, 1500);
    }
  }
  const auto s = with_mode(ball, SignMode::fast_winding);
  const T nan = std::numeric_limits<T>::quiet_NaN();
  EXPECT_TRUE(std::isnan(s.bounded({nan, T(0), T(0)}, T(1))));
}

// The split-sign protocol that banded grids use (`unsigned_distance`, `unsigned_within`,
// `sign_at`) rebuilds every mode's value bit for bit: the unsigned searches take the magnitude
// from the search's own squared distance, not from a second closest-point computation, so this
// checks that both give the same bits, on a closed and an open mesh, at random points and at
// points next to the surface (on vertices, edges and faces).
TYPED_TEST(SignedMeshSdfTest, SplitSignPartsRebuildTheValueInEveryMode) {
  using T = TypeParam;
  static_assert(has_split_sign_v<SignedMeshSdf<T>>);
  const PolygonSoup<T> ball = make_icosphere<T>(3).value();
  for (const PolygonSoup<T>& soup : {ball, test::remove_cap(ball, T(0.3))}) {
    std::vector<Vec3<T>> pts =
        test::random_points(make_triangle_mesh(soup).value().bounds().grown(T(0.5)), 1500, 7);
    for (std::size_t v = 0; v < soup.vertices.size(); v += 2)
      for (const T k : {T(0), T(1e-5), T(-1e-5), T(1e-2), T(-3e-2)})
        pts.push_back(soup.vertices[v] * (T(1) + k));
    for (std::size_t i = 0; i < soup.face_count(); ++i) {
      const auto f = soup.face(i);
      const Vec3<T> a = soup.vertices[f[0]], b = soup.vertices[f[1]], c = soup.vertices[f[2]];
      pts.push_back((a + b) * T(0.5));               // on an edge
      pts.push_back((a + b + c) * (T(1.01) / T(3))); // off a face
    }
    std::size_t within = 0, beyond = 0;
    for (SignMode m : all_modes) {
      const auto s = with_mode(soup, m);
      for (const auto& p : pts) {
        const T v = s(p), u = s.unsigned_distance(p);
        ASSERT_TRUE(same_bits(u, std::abs(v))) << to_string(m) << " " << p << ": " << u;
        if (v != T(0)) {
          ASSERT_TRUE(same_bits(apply_sign(u, s.sign_at(p)), v)) << to_string(m) << " " << p;
        }
        for (const T bound : {T(0.01), T(0.1)}) {
          const T w = s.unsigned_within(p, bound);
          if (std::abs(v) <= bound) {
            ++within;
            ASSERT_TRUE(same_bits(w, std::abs(v))) << to_string(m) << " " << p;
          } else {
            ++beyond;
            ASSERT_EQ(w, std::numeric_limits<T>::infinity()) << to_string(m) << " " << p;
          }
        }
      }
    }
    EXPECT_GT(within, 2000u);
    EXPECT_GT(beyond, 2000u);
  }
}

TYPED_TEST(SignedMeshSdfTest, BatchSignsAreThePointSignsInEveryMode) {
  using T = TypeParam;
  static_assert(has_batch_sign_v<SignedMeshSdf<T>>);
  const PolygonSoup<T> ball = make_icosphere<T>(3).value();
  for (const PolygonSoup<T>& soup : {ball, test::remove_cap(ball, T(0.3))}) {
    // Random points, points next to the surface (vertices pushed in and out along the radius by
    // 1e-6 to 1e-2) and a lattice across the hole's fill (w crosses 1/2 there).
    std::vector<Vec3<T>> pts =
        test::random_points(make_triangle_mesh(soup).value().bounds().grown(T(0.5)), 700, 41);
    for (std::size_t v = 0; v < soup.vertices.size(); v += 3)
      for (const T k : {T(1e-6), T(-1e-6), T(1e-3), T(-1e-3), T(1e-2)})
        pts.push_back(soup.vertices[v] * (T(1) + k));
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j)
        for (int z = 0; z < 8; ++z)
          pts.push_back(
              {T(-0.8) + T(0.14) * T(i), T(-0.8) + T(0.14) * T(j), T(0.2) + T(0.03) * T(z)});
    for (SignMode m : all_modes) {
      const auto s = with_mode(soup, m);
      std::vector<Sign> got(pts.size());
      s.signs_at(Span<const Vec3<T>>(pts), Span<Sign>(got));
      for (std::size_t i = 0; i < pts.size(); ++i)
        ASSERT_EQ(got[i], s.sign_at(pts[i])) << to_string(m) << " " << pts[i];
    }
  }
}

// The batch query (MeshSdf's Morton-ordered batch with the pseudonormal sign, one point at a time
// otherwise) gives every mode's single values bit for bit, through `evaluate` on 1 and 3 threads.
TYPED_TEST(SignedMeshSdfTest, BatchEvalIsThePointValuesInEveryMode) {
  using T = TypeParam;
  static_assert(has_batch_eval_v<SignedMeshSdf<T>> && has_ordered_batch_v<SignedMeshSdf<T>>);
  const PolygonSoup<T> ball = make_icosphere<T>(3).value();
  for (const PolygonSoup<T>& soup : {ball, test::remove_cap(ball, T(0.3))}) {
    std::vector<Vec3<T>> pts =
        test::random_points(make_triangle_mesh(soup).value().bounds().grown(T(0.5)), 3000, 43);
    for (std::size_t v = 0; v < soup.vertices.size(); v += 3) pts.push_back(soup.vertices[v]);
    pts.push_back({std::numeric_limits<T>::quiet_NaN(), T(0), T(0)});
    for (SignMode m : all_modes) {
      const auto s = with_mode(soup, m);
      for (int threads : {1, 3}) {
        ExecOptions ex;
        ex.threads = threads;
        ex.serial_threshold = 0;
        std::vector<T> got(pts.size(), T(-7));
        ASSERT_TRUE(evaluate(s, Span<const Vec3<T>>(pts), Span<T>(got), ex));
        for (std::size_t i = 0; i < pts.size(); ++i) {
          const T want = s(pts[i]);
          ASSERT_TRUE(std::memcmp(&got[i], &want, sizeof(T)) == 0)
              << to_string(m) << " " << threads << " threads " << pts[i] << " " << got[i] << " "
              << want;
        }
      }
    }
  }
}

TYPED_TEST(SignedMeshSdfTest, OutOfRangeSignModeIsAnErrorNotUnsigned) {
  using T = TypeParam;
  SignOptions o;
  o.mode = static_cast<SignMode>(9);
  const auto r = SignedMeshSdf<T>::build(make_cube<T>(T(0.5)).value(), o);
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::invalid_argument);
  EXPECT_NE(r.error().message.find("sign mode 9"), std::string::npos) << r.error().message;
}

TYPED_TEST(SignedMeshSdfTest, ClosestCarriesTheModesSign) {
  using T = TypeParam;
  const auto soup = make_torus<T>(1, T(0.3)).value();
  const auto ref = MeshSdf<T>::build(soup).value();
  for (SignMode m : all_modes) {
    const auto s = with_mode(soup, m);
    for (const auto& p : test::random_points(ref.bounds().grown(T(0.2)), 300, 17)) {
      const auto c = s.closest(p), r = ref.closest(p);
      EXPECT_EQ(c.distance, s(p));
      EXPECT_EQ(c.point, r.point);
      EXPECT_EQ(c.triangle, r.triangle);
    }
  }
}

TEST(SignChoice, AutomaticPicksPseudonormalOnValidMeshesAndSaysWhy) {
  const auto s = SignedMeshSdf<double>::build(make_icosphere<double>(2).value()).value();
  EXPECT_EQ(s.resolved_mode(), SignMode::pseudonormal);
  EXPECT_EQ(s.reason(), "closed, manifold and consistently oriented");
  const auto open =
      SignedMeshSdf<double>::build(test::remove_cap(make_icosphere<double>(2).value(), 0.8))
          .value();
  EXPECT_EQ(open.resolved_mode(), SignMode::fast_winding);
  EXPECT_NE(open.reason().find("not closed"), std::string::npos) << open.reason();
  EXPECT_NE(open.reason().find("1 holes"), std::string::npos) << open.reason();
  const auto fixed = with_mode(make_icosphere<double>(2).value(), SignMode::winding);
  EXPECT_EQ(fixed.resolved_mode(), SignMode::winding);
  EXPECT_EQ(fixed.reason(), "requested");
  // make() from a TriangleMesh validates its triangles the same way.
  const auto tm =
      SignedMeshSdf<double>::make(make_triangle_mesh(make_cube<double>().value()).value()).value();
  EXPECT_EQ(tm.resolved_mode(), SignMode::pseudonormal);
}

TEST(SignChoice, InwardMeshKeepsPseudonormalWithAWarning) {
  PolygonSoup<double> s = make_icosphere<double>(1).value();
  flip_faces(s);
  const SignChoice c = choose_sign_mode(validate(s));
  EXPECT_EQ(c.mode, SignMode::pseudonormal);
  EXPECT_NE(c.reason.find("inward"), std::string::npos);
}

TEST(SignedMeshSdfErrors, BadInputIsAnError) {
  EXPECT_FALSE(SignedMeshSdf<double>::build(PolygonSoup<double>{}).has_value());
  PolygonSoup<double> s = make_cube<double>().value();
  s.vertices[0].x = std::nan("");
  for (SignMode m : all_modes) {
    SignOptions o;
    o.mode = m;
    EXPECT_FALSE(SignedMeshSdf<double>::build(s, o).has_value());
  }
  SignOptions o;
  o.mode = SignMode::fast_winding;
  o.winding.beta = -1;
  EXPECT_EQ(SignedMeshSdf<double>::build(make_cube<double>().value(), o).error().code,
            ErrorCode::invalid_argument);
}

static_assert(is_sdf_v<SignedMeshSdf<float>> && is_sdf_v<SignedMeshSdf<double>>);

TEST(SignedMeshSdfKind, ExactOnlyWithThePseudonormalSign) {
  const auto soup = make_icosphere<double>(1).value();
  EXPECT_EQ(with_mode(soup, SignMode::pseudonormal).dynamic_kind(), SdfKind::exact);
  EXPECT_EQ(with_mode(soup, SignMode::automatic).dynamic_kind(), SdfKind::exact);
  for (SignMode m : {SignMode::winding, SignMode::fast_winding, SignMode::unsigned_distance})
    EXPECT_EQ(with_mode(soup, m).dynamic_kind(), SdfKind::implicit) << to_string(m);
}

TEST(SignedMeshSdfNames, OneTableForTheLibraryAndTheTools) {
  // The spellings of `ebgeom --sign` and scene files (docs/cli.md), written out independently.
  const std::pair<SignMode, const char*> expected[] = {{SignMode::pseudonormal, "pseudonormal"},
                                                       {SignMode::winding, "winding"},
                                                       {SignMode::fast_winding, "fast-winding"},
                                                       {SignMode::unsigned_distance, "unsigned"},
                                                       {SignMode::automatic, "auto"}};
  for (const auto& [mode, name] : expected) {
    EXPECT_STREQ(to_string(mode), name);
    const Result<SignMode> back = parse_sign_mode(name);
    ASSERT_TRUE(back) << name;
    EXPECT_EQ(*back, mode) << name;
  }
  for (const char* bad : {"fast_winding", "unsigned_distance", "automatic", "Auto", "", "wind"}) {
    const Result<SignMode> r = parse_sign_mode(bad);
    ASSERT_FALSE(r) << bad;
    EXPECT_EQ(r.error().code, ErrorCode::invalid_argument);
    EXPECT_NE(r.error().what().find("fast-winding, unsigned or auto"), std::string::npos);
  }
}

} // namespace
} // namespace ebgeom

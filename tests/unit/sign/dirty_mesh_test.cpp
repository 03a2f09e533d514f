// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// The dirty-mesh suite: what each sign mode does on imperfect meshes. Every expectation here is
// listed in docs/sign.md ("Outcomes on imperfect meshes"); keep the two in step.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/mesh/validate.hpp"
#include "ebgeom/mesh/weld.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"
#include "sign_support.hpp"
#include "test_support.hpp"

namespace ebgeom {
namespace {

using V = Vec3<double>;
using Soup = PolygonSoup<double>;
using Sdf = SignedMeshSdf<double>;
using Truth = std::function<double(const V&)>; // signed distance of the intended solid
using Filter = std::function<bool(const V&)>;

constexpr SignMode signed_modes[] = {SignMode::pseudonormal, SignMode::winding,
                                     SignMode::fast_winding};
constexpr SignMode winding_modes[] = {SignMode::winding, SignMode::fast_winding};

Sdf with_mode(const Soup& s, SignMode m) {
  SignOptions o;
  o.mode = m;
  return Sdf::build(s, o).value();
}

const Soup& sphere() {
  static const Soup s = make_icosphere<double>(3).value();
  return s;
}
double ball(const V& p) { return norm(p) - 1; }

/// Number of probes (random points in [-1.6, 1.6]³ at least `margin` from the intended surface,
/// kept by `keep`) where the mode's sign differs from the intended solid's. Checks finiteness.
int wrong_signs(const Sdf& s, const Truth& truth, const Filter& keep, int* used = nullptr,
                double margin = 0.05) {
  int wrong = 0, n = 0;
  for (const V& p :
       test::random_points(Aabb<double>({-1.6, -1.6, -1.6}, {1.6, 1.6, 1.6}), 4000, 23)) {
    const double t = truth(p);
    if (std::abs(t) < margin || !keep(p)) continue;
    const double v = s(p);
    EXPECT_TRUE(std::isfinite(v));
    ++n;
    if ((v < 0) != (t < 0)) ++wrong;
  }
  if (used) *used = n;
  return wrong;
}

bool inside(const Sdf& s, const V& p) { return s(p) < 0; }

// ---- holes of several sizes -------------------------------------------------------------------

TEST(DirtyMesh, HolesOfSeveralSizes) {
  // One face (the top-most), a cap z > 0.7 (about 15% of the area), and the upper hemisphere.
  std::size_t top = 0;
  for (std::size_t f = 0; f < sphere().face_count(); ++f)
    if (test::face_centroid(sphere(), f).z > test::face_centroid(sphere(), top).z) top = f;
  const double top_z = test::face_centroid(sphere(), top).z;
  for (double cut : {top_z - 1e-9, 0.7, 0.0}) {
    SCOPED_TRACE("hole above z = " + std::to_string(cut));
    const Soup holed = test::remove_cap(sphere(), cut);
    EXPECT_FALSE(validate(holed).closed());
    EXPECT_EQ(Sdf::build(holed).value().resolved_mode(), SignMode::fast_winding);
    // Away from the hole every mode finds the ball.
    for (SignMode m : signed_modes) {
      int used = 0;
      EXPECT_EQ(wrong_signs(
                    with_mode(holed, m), ball, [&](const V& p) { return p.z < cut - 0.3; }, &used),
                0)
          << to_string(m);
      EXPECT_GT(used, 500);
    }
  }
  // One face missing: the winding modes are right just above and just below the hole.
  {
    const Soup one = test::remove_cap(sphere(), top_z - 1e-9);
    const V c = test::face_centroid(sphere(), top);
    for (SignMode m : winding_modes) {
      EXPECT_FALSE(inside(with_mode(one, m), c * 1.1)) << to_string(m);
      EXPECT_TRUE(inside(with_mode(one, m), c * 0.9)) << to_string(m);
    }
  }
  // Medium hole: above it, pseudonormal takes the rim for the surface and says "inside"; the
  // winding number (about 0.2 there) says outside. The winding modes close the hole with a
  // surface spanning the rim: below the rim plane is inside, the missing cap above it outside.
  const Soup medium = test::remove_cap(sphere(), 0.7);
  EXPECT_TRUE(inside(with_mode(medium, SignMode::pseudonormal), {0, 0, 1.2}));
  EXPECT_TRUE(inside(with_mode(medium, SignMode::pseudonormal), {0, 0, 0.85}));
  for (SignMode m : winding_modes) {
    EXPECT_FALSE(inside(with_mode(medium, m), {0, 0, 1.2})) << to_string(m);
    EXPECT_FALSE(inside(with_mode(medium, m), {0, 0, 0.85})) << to_string(m);
    EXPECT_TRUE(inside(with_mode(medium, m), {0, 0, 0.6})) << to_string(m);
  }
  // Open hemisphere (a bowl): the winding modes read the bowl closed by its rim disk (inside =
  // the lower half ball); pseudonormal extends the ball's inside above the rim plane.
  const Soup bowl = test::remove_cap(sphere(), 0.0);
  for (SignMode m : winding_modes) {
    const Sdf s = with_mode(bowl, m);
    EXPECT_FALSE(inside(s, {0, 0, 0.3})) << to_string(m);
    EXPECT_FALSE(inside(s, {0.3, -0.2, 0.1})) << to_string(m);
    EXPECT_TRUE(inside(s, {0.3, -0.2, -0.1})) << to_string(m);
    const Truth half_ball = [](const V& p) { return std::max(norm(p) - 1, p.z); };
    // (fast winding may differ within its band around w = 1/2, near the rim disk)
    EXPECT_EQ(wrong_signs(
                  s, half_ball, [](const V&) { return true; }, nullptr, 0.15),
              0)
        << to_string(m);
  }
  EXPECT_TRUE(inside(with_mode(bowl, SignMode::pseudonormal), {0, 0, 0.3}));
}

// ---- flipped faces ----------------------------------------------------------------------------

TEST(DirtyMesh, FlippedSingleFace) {
  const std::size_t f0 = 100;
  const Soup s = test::rebuild<double>(
      sphere(), [](std::size_t) { return true; }, [&](std::size_t f) { return f == f0; });
  EXPECT_FALSE(validate(s).consistently_oriented());
  const Sdf a = Sdf::build(s).value();
  EXPECT_EQ(a.resolved_mode(), SignMode::fast_winding);
  EXPECT_NE(a.reason().find("inconsistently oriented"), std::string::npos);
  const V c = test::face_centroid(sphere(), f0);
  // Pseudonormal trusts the flipped face: both sides of it come out wrong.
  EXPECT_TRUE(inside(with_mode(s, SignMode::pseudonormal), c * 1.1));
  EXPECT_FALSE(inside(with_mode(s, SignMode::pseudonormal), c * 0.9));
  // The winding number outvotes one small face: right on both sides, and everywhere else.
  for (SignMode m : winding_modes) {
    const Sdf w = with_mode(s, m);
    EXPECT_FALSE(inside(w, c * 1.1)) << to_string(m);
    EXPECT_TRUE(inside(w, c * 0.9)) << to_string(m);
    EXPECT_EQ(wrong_signs(w, ball, [](const V&) { return true; }), 0) << to_string(m);
  }
}

TEST(DirtyMesh, FlippedPatch) {
  const Soup s = test::rebuild<double>(
      sphere(), [](std::size_t) { return true; },
      [&](std::size_t f) { return test::face_centroid(sphere(), f).z > 0.7; });
  // Away from the patch (z < 0) every mode is right.
  for (SignMode m : signed_modes)
    EXPECT_EQ(wrong_signs(with_mode(s, m), ball, [](const V& p) { return p.z < 0; }), 0)
        << to_string(m);
  // At a distance above the patch pseudonormal is wrong and the winding number right; right next
  // to a large flipped patch the winding number is wrong too (the patch fills half the view).
  EXPECT_TRUE(inside(with_mode(s, SignMode::pseudonormal), {0, 0, 1.3}));
  for (SignMode m : winding_modes) {
    EXPECT_FALSE(inside(with_mode(s, m), {0, 0, 1.3})) << to_string(m);
    EXPECT_TRUE(inside(with_mode(s, m), {0, 0, 1.03})) << to_string(m);
  }
}

// ---- duplicated faces -------------------------------------------------------------------------

TEST(DirtyMesh, DuplicatedFaces) {
  const auto all = [](std::size_t) { return true; };
  const Soup s = test::rebuild<double>(sphere(), all, nullptr, all);
  const ValidationReport<double> r = validate(s);
  EXPECT_EQ(r.duplicate_faces.count, sphere().face_count());
  EXPECT_EQ(Sdf::build(s).value().resolved_mode(), SignMode::fast_winding);
  // w = 2 inside, 0 outside: every mode is right everywhere.
  for (SignMode m : signed_modes)
    EXPECT_EQ(wrong_signs(with_mode(s, m), ball, [](const V&) { return true; }), 0) << to_string(m);
  EXPECT_NEAR(with_mode(s, SignMode::winding).winding_number({0, 0, 0}), 2.0, 1e-9);
}

TEST(DirtyMesh, DuplicatedFacesWithOppositeOrientation) {
  const auto all = [](std::size_t) { return true; };
  // A patch duplicated reversed cancels itself: the winding modes see a hole there.
  const auto cap = [&](std::size_t f) { return test::face_centroid(sphere(), f).z > 0.7; };
  const Soup patch = test::rebuild<double>(sphere(), all, nullptr, cap, /*dup_flip=*/true);
  for (SignMode m : winding_modes) {
    const Sdf w = with_mode(patch, m);
    EXPECT_EQ(wrong_signs(w, ball, [](const V& p) { return p.z < 0.4; }), 0) << to_string(m);
    EXPECT_FALSE(inside(w, {0, 0, 1.2})) << to_string(m);
    EXPECT_TRUE(inside(w, {0, 0, 0.6})) << to_string(m);
  }
  // The whole mesh duplicated reversed: w = 0 everywhere, so the winding modes find no inside.
  // Pseudonormal's sign then depends on which copy wins the distance tie: only finiteness is
  // promised.
  const Soup both = test::rebuild<double>(sphere(), all, nullptr, all, /*dup_flip=*/true);
  for (SignMode m : winding_modes) {
    const Sdf w = with_mode(both, m);
    for (const V& p : test::random_points(Aabb<double>({-1.5, -1.5, -1.5}, {1.5, 1.5, 1.5}), 500))
      EXPECT_GE(w(p), 0.0) << to_string(m) << " " << p;
  }
  const Sdf pn = with_mode(both, SignMode::pseudonormal);
  for (const V& p : test::random_points(Aabb<double>({-1.5, -1.5, -1.5}, {1.5, 1.5, 1.5}), 500))
    EXPECT_TRUE(std::isfinite(pn(p)));
}

// ---- self-intersecting and nested components --------------------------------------------------

TEST(DirtyMesh, OverlappingSelfIntersectingComponents) {
  // Two unit spheres centred at x = -0.5 and x = +0.5; the intended solid is their union.
  const Soup s =
      test::combine(test::combine(Soup{}, sphere(), V{-0.5, 0, 0}), sphere(), V{0.5, 0, 0});
  const Truth uni = [](const V& p) {
    return std::min(norm(p - V{-0.5, 0, 0}), norm(p - V{0.5, 0, 0})) - 1;
  };
  // Two closed shells whose boxes overlap: automatic takes the winding sign, right everywhere.
  const ValidationReport<double> r = validate(s);
  EXPECT_EQ(r.shells, 2u);
  EXPECT_TRUE(r.shells_overlap);
  EXPECT_EQ(Sdf::build(s).value().resolved_mode(), SignMode::fast_winding);
  EXPECT_EQ(wrong_signs(with_mode(s, SignMode::automatic), uni, [](const V&) { return true; }), 0);
  for (SignMode m : winding_modes)
    EXPECT_EQ(wrong_signs(with_mode(s, m), uni, [](const V&) { return true; }), 0) << to_string(m);
  // Inside one sphere next to the other's buried surface, pseudonormal says outside.
  EXPECT_FALSE(inside(with_mode(s, SignMode::pseudonormal), {0.55, 0, 0}));
  EXPECT_TRUE(inside(with_mode(s, SignMode::winding), {0.55, 0, 0}));
  EXPECT_GT(wrong_signs(with_mode(s, SignMode::pseudonormal), uni, [](const V&) { return true; }),
            0);
}

TEST(DirtyMesh, NestedShells) {
  const Soup inner = test::scaled(sphere(), 0.5);
  const Truth hollow = [](const V& p) { return std::max(norm(p) - 1, 0.5 - norm(p)); };
  // Hollow ball (inner shell reversed): every mode is right; automatic sees nested shells and
  // takes the winding sign (w = 0 in the cavity).
  const Soup h = test::combine(sphere(), inner, V{0, 0, 0}, /*reversed=*/true);
  EXPECT_EQ(Sdf::build(h).value().resolved_mode(), SignMode::fast_winding);
  for (SignMode m :
       {SignMode::pseudonormal, SignMode::winding, SignMode::fast_winding, SignMode::automatic})
    EXPECT_EQ(wrong_signs(with_mode(h, m), hollow, [](const V&) { return true; }), 0)
        << to_string(m);
  // Both shells outward: the winding number is 2 in the cavity, so the winding modes give the
  // union (a solid ball); pseudonormal follows the nearest shell (outside just around the inner
  // shell, inside within it).
  const Soup both = test::combine(sphere(), inner, V{0, 0, 0});
  for (SignMode m : winding_modes) {
    EXPECT_EQ(wrong_signs(with_mode(both, m), ball, [](const V&) { return true; }), 0)
        << to_string(m);
  }
  EXPECT_FALSE(inside(with_mode(both, SignMode::pseudonormal), {0, 0, 0.6}));
  EXPECT_TRUE(inside(with_mode(both, SignMode::pseudonormal), {0, 0, 0.1}));
  // A ball inside a ball, both outward, is topologically clean; automatic must still see the
  // nested shells and take the winding sign (pseudonormal is wrong around the inner shell).
  const ValidationReport<double> r = validate(both);
  EXPECT_TRUE(r.closed() && r.manifold() && r.consistently_oriented());
  EXPECT_EQ(r.shells, 2u);
  EXPECT_EQ(Sdf::build(both).value().resolved_mode(), SignMode::fast_winding);
  EXPECT_EQ(wrong_signs(with_mode(both, SignMode::automatic), ball, [](const V&) { return true; }),
            0);
  EXPECT_GT(
      wrong_signs(with_mode(both, SignMode::pseudonormal), ball, [](const V&) { return true; }), 0);
}

TEST(DirtyMesh, OverlappingClosedBoxes) {
  // Two closed, outward boxes overlapping in [0, 0.5] x [-0.5, 0.5]^2; the intended solid is their
  // union. Each is clean on its own, so only the shell test can steer automatic.
  const Soup a = make_box<double>({-1, -0.5, -0.5}, {0.5, 0.5, 0.5}).value();
  const Soup b = make_box<double>({0, -0.5, -0.5}, {1.4, 0.5, 0.5}).value();
  const Soup s = test::combine(a, b, V{0, 0, 0});
  auto box = [](const V& q, const V& lo, const V& hi) { // exact box SDF
    const V c = (lo + hi) * 0.5, h = (hi - lo) * 0.5;
    const V d{std::abs(q.x - c.x) - h.x, std::abs(q.y - c.y) - h.y, std::abs(q.z - c.z) - h.z};
    const V o{std::max(d.x, 0.0), std::max(d.y, 0.0), std::max(d.z, 0.0)};
    return norm(o) + std::min(std::max(d.x, std::max(d.y, d.z)), 0.0);
  };
  const Truth uni = [&](const V& p) {
    return std::min(box(p, {-1, -0.5, -0.5}, {0.5, 0.5, 0.5}),
                    box(p, {0, -0.5, -0.5}, {1.4, 0.5, 0.5}));
  };
  const ValidationReport<double> r = validate(s);
  EXPECT_TRUE(r.closed() && r.manifold() && r.consistently_oriented());
  EXPECT_EQ(r.shells, 2u);
  EXPECT_TRUE(r.shells_overlap);
  const Sdf automatic = Sdf::build(s).value();
  EXPECT_EQ(automatic.resolved_mode(), SignMode::fast_winding);
  EXPECT_NE(automatic.reason().find("2 closed shells"), std::string::npos) << automatic.reason();
  EXPECT_EQ(wrong_signs(automatic, uni, [](const V&) { return true; }), 0);
  EXPECT_GT(wrong_signs(with_mode(s, SignMode::pseudonormal), uni, [](const V&) { return true; }),
            0);
  // Two disjoint boxes keep the exact pseudonormal sign.
  const Soup apart = test::combine(a, b, V{0, 3, 0});
  EXPECT_FALSE(validate(apart).shells_overlap);
  EXPECT_EQ(Sdf::build(apart).value().resolved_mode(), SignMode::pseudonormal);
}

// ---- non-manifold edges -----------------------------------------------------------------------

TEST(DirtyMesh, NonManifoldEdges) {
  // Two unit cubes sharing only the edge x = y = 1 (4 faces on it), welded.
  const Soup a = make_box<double>({0, 0, 0}, {1, 1, 1}).value();
  const Soup b = make_box<double>({1, 1, 0}, {2, 2, 1}).value();
  const Soup s = weld(test::combine(a, b, V{0, 0, 0})).value().soup;
  const ValidationReport<double> r = validate(s);
  EXPECT_GT(r.non_manifold_edges.count, 0u);
  const Sdf a_s = Sdf::build(s).value();
  EXPECT_EQ(a_s.resolved_mode(), SignMode::fast_winding);
  EXPECT_NE(a_s.reason().find("not manifold"), std::string::npos);
  const Truth two = [](const V& p) {
    auto box = [](const V& q, const V& lo, const V& hi) {
      const V c = (lo + hi) * 0.5, h = (hi - lo) * 0.5;
      const V d{std::abs(q.x - c.x) - h.x, std::abs(q.y - c.y) - h.y, std::abs(q.z - c.z) - h.z};
      const V o{std::max(d.x, 0.0), std::max(d.y, 0.0), std::max(d.z, 0.0)};
      return norm(o) + std::min(std::max(d.x, std::max(d.y, d.z)), 0.0);
    };
    return std::min(box(p, {0, 0, 0}, {1, 1, 1}), box(p, {1, 1, 0}, {2, 2, 1}));
  };
  for (SignMode m : signed_modes) {
    int used = 0;
    EXPECT_EQ(wrong_signs(
                  with_mode(s, m), two, [](const V&) { return true; }, &used),
              0)
        << to_string(m);
    EXPECT_GT(used, 500);
  }
  // A fin: one extra triangle on an edge of the sphere, sticking out (3 faces on that edge).
  Soup fin = sphere();
  const Index e0 = fin.indices[0], e1 = fin.indices[1];
  const V tip = (fin.vertices[e0] + fin.vertices[e1]) * 0.5 * 1.4;
  const Index t = fin.add_vertex(tip);
  fin.add_triangle(e0, e1, t);
  EXPECT_GT(validate(fin).non_manifold_edges.count, 0u);
  for (SignMode m : winding_modes)
    EXPECT_EQ(wrong_signs(with_mode(fin, m), ball, [&](const V& p) { return norm(p - tip) > 0.5; }),
              0)
        << to_string(m);
  // Pseudonormal is right inside the ball away from the fin, but outside, wherever the closest
  // feature is on the fin (its back side, and beyond its tip), reads as inside.
  const V fc = (fin.vertices[e0] + fin.vertices[e1] + tip) / 3.0;
  const V fn = normalized(cross(fin.vertices[e1] - fin.vertices[e0], tip - fin.vertices[e0]));
  EXPECT_EQ(wrong_signs(with_mode(fin, SignMode::pseudonormal), ball,
                        [&](const V& p) { return norm(p) < 1 && norm(p - fc) > 0.5; }),
            0);
  EXPECT_TRUE(inside(with_mode(fin, SignMode::pseudonormal), fc - fn * 0.05));
  EXPECT_FALSE(inside(with_mode(fin, SignMode::pseudonormal), fc + fn * 0.05));
  for (SignMode m : winding_modes) {
    EXPECT_FALSE(inside(with_mode(fin, m), fc - fn * 0.05)) << to_string(m);
    EXPECT_FALSE(inside(with_mode(fin, m), fc + fn * 0.05)) << to_string(m);
  }
}

// ---- points exactly on the surface ------------------------------------------------------------

TEST(DirtyMesh, PointsOnVerticesEdgesAndFacesGiveZero) {
  const Soup holed = test::remove_cap(sphere(), 0.7);
  for (const Soup* s : {&sphere(), &holed}) {
    const TriangleMesh<double> m = make_triangle_mesh(*s).value();
    std::vector<V> pts;
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
      pts.push_back(m.corner(t, 0));
      pts.push_back((m.corner(t, 1) + m.corner(t, 2)) * 0.5);
      pts.push_back((m.corner(t, 0) + m.corner(t, 1) + m.corner(t, 2)) / 3.0);
    }
    for (SignMode mode : {SignMode::pseudonormal, SignMode::winding, SignMode::fast_winding,
                          SignMode::unsigned_distance, SignMode::automatic}) {
      const Sdf sdf = with_mode(*s, mode);
      for (const V& p : pts) {
        const double v = sdf(p);
        ASSERT_TRUE(std::isfinite(v)) << to_string(mode) << " " << p;
        ASSERT_LE(std::abs(v), 1e-15) << to_string(mode) << " " << p;
        ASSERT_TRUE(std::isfinite(sdf.winding_number(p)));
      }
      for (std::size_t t = 0; t < m.triangle_count(); ++t) ASSERT_EQ(sdf(m.corner(t, 1)), 0.0);
    }
  }
}

} // namespace
} // namespace ebgeom

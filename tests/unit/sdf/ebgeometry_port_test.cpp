// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Every mapping in docs/from-ebgeometry.md, exercised: each test names the EBGeometry (or
// chombo-discharge) name it ports and checks the ebgeom equivalent against an independent value
// (closed form, brute force, or the definition EBGeometry's user guide gives).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "ebgeom/adapters/eb_function.hpp"
#include "ebgeom/bvh/build.hpp"
#include "ebgeom/bvh/traverse.hpp"
#include "ebgeom/bvh/wide_bvh.hpp"
#include "ebgeom/core/sphere.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/mesh/half_edge_mesh.hpp"
#include "ebgeom/sdf/any_sdf.hpp"
#include "ebgeom/sdf/brute_force_dcel_sdf.hpp"
#include "ebgeom/sdf/bvh_union.hpp"
#include "ebgeom/sdf/csg.hpp"
#include "ebgeom/sdf/dcel_sdf.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/transforms.hpp"
#include "test_support.hpp"

namespace {
using T = double;
using V = ebgeom::Vec3<T>;
const ebgeom::Aabb<T> probe = ebgeom::Aabb<T>::of(V{-2, -2, -2}, V{2, 2, 2});

/// EBGeometry's `SignedDistanceFunction<T>` subclass with `signedDistance`: in ebgeom, any struct
/// with `scalar_type`, `kind`, `operator()` and `bounds()` (no base class).
struct MyBall {
  using scalar_type = T;
  static constexpr ebgeom::SdfKind kind = ebgeom::SdfKind::exact;
  V c;
  T r;
  T operator()(const V& p) const noexcept { return ebgeom::norm(p - c) - r; }
  ebgeom::Aabb<T> bounds() const noexcept { return ebgeom::Aabb<T>::of(c).grown(r); }
};
} // namespace

// SignedDistanceFunction / ImplicitFunction, value / signedDistance, std::shared_ptr<SDF>.
TEST(FromEBGeometry, SignedDistanceFunctionIsTheSdfContractAndAnySdfThePointer) {
  static_assert(ebgeom::is_sdf_v<MyBall>);
  const MyBall b{{1, 0, 0}, 0.5};
  std::vector<ebgeom::AnySdf<T>> scene; // std::vector<std::shared_ptr<SignedDistanceFunction<T>>>
  scene.emplace_back(b);
  scene.emplace_back(ebgeom::Sphere<T>{{-1, 0, 0}, 0.25});
  for (const auto& p : ebgeom::test::random_points(probe, 200)) {
    const T ref = std::sqrt((p.x - 1) * (p.x - 1) + p.y * p.y + p.z * p.z) - 0.5;
    EXPECT_NEAR(b(p), ref, 1e-12); // signedDistance(p) / value(p)
    EXPECT_EQ(scene[0](p), b(p));  // through the type-erased handle
    EXPECT_EQ(scene[1].dynamic_kind(), ebgeom::SdfKind::exact);
  }
}

// flipSign: EBGeometry's examples pass flipSign = false, so the EB code sees +S (fluid inside the
// object); flipSign = true is -S (fluid outside), which is ebgeom's adapter default.
TEST(FromEBGeometry, FlipSignIsComplementOrTheAdaptersFluidSide) {
  const ebgeom::Sphere<T> s{{0, 0, 0}, 1};
  ebgeom::EbOptions no_flip;
  no_flip.fluid = ebgeom::FluidSide::inside; // = EBGeometry flipSign = false
  ebgeom::EbOptions flip;                    // default FluidSide::outside = flipSign = true
  const ebgeom::EbFunction<ebgeom::Sphere<T>> f_false(s, no_flip), f_true(s, flip);
  const auto flipped = ebgeom::complement(s); // an SDF with flipSign = true
  for (const auto& p : ebgeom::test::random_points(probe, 200)) {
    const T S = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z) - 1; // > 0 outside, EBGeometry's too
    EXPECT_EQ(f_false(p.x, p.y, p.z), s(p));
    EXPECT_EQ(f_true(p.x, p.y, p.z), -s(p));
    EXPECT_EQ(flipped(p), -s(p));
    EXPECT_NEAR(s(p), S, 1e-12);
  }
}

// Union(sdfs, flipSign), UnionBVH / FastUnion(sdfs, flipSign, bvConstructor), SmoothUnion.
TEST(FromEBGeometry, UnionsAndTheirBvhForm) {
  std::vector<ebgeom::Sphere<T>> balls;
  for (int i = 0; i < 50; ++i) balls.push_back({{-1.5 + 0.06 * i, 0.1 * (i % 3), 0}, 0.05});
  const auto three = ebgeom::unite(balls[0], balls[1], balls[2]); // Union of a fixed set
  const ebgeom::BvhUnion<ebgeom::Sphere<T>> fast(balls); // UnionBVH: bounds() replaces the BV
                                                         // constructor
  const auto smooth = ebgeom::smooth_unite(balls[0], balls[1], 0.05); // SmoothUnion(a, b, k)
  for (const auto& p : ebgeom::test::random_points(probe, 500)) {
    T ref = std::numeric_limits<T>::infinity();
    for (const auto& b : balls) ref = std::min(ref, b(p));
    EXPECT_EQ(fast(p), ref);
    EXPECT_EQ(fast.linear(p), ref); // the standard Union: every object per query
    EXPECT_EQ(three(p), std::min({balls[0](p), balls[1](p), balls[2](p)}));
    EXPECT_LE(smooth(p), std::min(balls[0](p), balls[1](p)) + 1e-15);
    EXPECT_GE(smooth(p), std::min(balls[0](p), balls[1](p)) - 0.05);
  }
}

// sdf.translate(t); sdf.rotate(angle, axis); transformPoint: nested value transforms, inside out.
TEST(FromEBGeometry, TranslateThenRotateIsRotateOfTranslate) {
  // EBGeometry: sdf.translate({0, 1, 0}); sdf.rotate(90, 0); moves a ball at the origin to
  // (0, 1, 0), then turns it 90 degrees about x, to (0, 0, 1)
  const auto moved = ebgeom::rotate(ebgeom::translate(ebgeom::Sphere<T>{{0, 0, 0}, 0.5}, {0, 1, 0}),
                                    ebgeom::Axis::x, 90);
  const ebgeom::Sphere<T> ref{{0, 0, 1}, 0.5};
  for (const auto& p : ebgeom::test::random_points(probe, 300))
    EXPECT_NEAR(moved(p), ref(p), 1e-12);
  EXPECT_NEAR(moved(V{0, 0, 1}), -0.5, 1e-15);
  // transformPoint: the point an SDF sees, R^T (p - t) for transform(s, R, t)
  const ebgeom::Mat3<T> R = ebgeom::Mat3<T>::coordinate_axis(ebgeom::Axis::z, 90);
  const auto placed = ebgeom::transform(ebgeom::Sphere<T>{{1, 0, 0}, 0.25}, R, V{0, 0, 2});
  EXPECT_NEAR(placed(V{0, 1, 2}), -0.25, 1e-15);
}

// Parser::PLY<T>::readIntoDCEL, DCEL::MeshT / FaceT / EdgeT / VertexT, chombo-discharge's
// DcelSdf (every face) and BvhSdf (BVH over the faces): ebgeom's reader, HalfEdgeMesh,
// BruteForceDcelSdf and DcelSdf (any BV: Aabb or BoundingSphere).
TEST(FromEBGeometry, ReadIntoDcelAndTheDcelSdfs) {
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\n"
                          "property float y\nproperty float z\nelement face 6\n"
                          "property list uchar int vertex_indices\nend_header\n"
                          "-1 -1 -1\n1 -1 -1\n1 1 -1\n-1 1 -1\n-1 -1 1\n1 -1 1\n1 1 1\n-1 1 1\n"
                          "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";
  auto soup = ebgeom::io::parse_mesh<T>(ply);
  ASSERT_TRUE(soup.has_value()) << soup.error().what();
  auto mesh = ebgeom::make_half_edge_mesh(*soup); // DCEL::MeshT<T>
  ASSERT_TRUE(mesh.has_value());
  EXPECT_EQ(mesh->face_count(), 6u);       // FaceT
  EXPECT_EQ(mesh->vertex_count(), 8u);     // VertexT
  EXPECT_EQ(mesh->half_edge_count(), 24u); // EdgeT (half-edges)
  // FaceT: area and unit normal; EdgeT: next/pair circulation; VertexT: its position
  for (ebgeom::Index f = 0; f < 6; ++f) {
    const ebgeom::HalfEdgeFace<T>& face = mesh->face(f);
    EXPECT_NEAR(face.area, 4.0, 1e-12);
    EXPECT_NEAR(ebgeom::norm(face.normal), 1.0, 1e-12);
    const ebgeom::HalfEdge& e = mesh->half_edge(face.edge);
    EXPECT_EQ(e.face, f);
    EXPECT_EQ(mesh->half_edge(e.pair).pair, face.edge); // closed mesh: every edge has a pair
    const ebgeom::HalfEdgeVertex<T>& v = mesh->vertex(e.origin);
    EXPECT_EQ(ebgeom::norm(v.position), std::sqrt(3.0));
  }
  const ebgeom::BruteForceDcelSdf<T> direct(*mesh);         // chombo-discharge DcelSdf
  const auto bvh = ebgeom::DcelSdf<T>::make(*mesh).value(); // BvhSdf (AABB)
  const auto bvh_s = ebgeom::DcelSdf<T, 4, ebgeom::BoundingSphere<T>>::make(*mesh).value();
  const ebgeom::Box<T> cube{{1, 1, 1}};
  for (const auto& p : ebgeom::test::random_points(probe, 500)) {
    EXPECT_NEAR(direct(p), cube(p), 1e-12) << p;
    EXPECT_EQ(bvh(p), direct(p));
    EXPECT_EQ(bvh_s(p), direct(p));
  }
}

// BVH::NodeT + topDownSortAndPartitionPrimitives(partitioner, stop function), flattenTree ->
// LinearBVH, EBGeometry::BVH::Build (TopDown / Morton / SAH), AABBT and BoundingSphereT.
TEST(FromEBGeometry, BuilderTreeFlattenAndBuildMethods) {
  const auto soup = ebgeom::make_icosphere<T>(2, 1.0).value();
  std::vector<ebgeom::Aabb<T>> boxes;
  std::vector<V> centroids;
  for (std::size_t f = 0; f < soup.face_count(); ++f) {
    ebgeom::Aabb<T> b;
    for (const auto v : soup.face(f)) b.extend(soup.vertices[v]);
    boxes.push_back(b);
    centroids.push_back(b.center());
  }
  const ebgeom::Span<const ebgeom::Aabb<T>> bs(boxes);
  const ebgeom::Span<const V> cs(centroids);
  // topDownSortAndPartitionPrimitives(EBGeometry's partitioner, defaultStopFunction)
  const ebgeom::bvh::BuildTree<T> tree = ebgeom::bvh::build_top_down<T>(
      bs, cs, ebgeom::bvh::ChunkPartition<4>{}, ebgeom::bvh::LeafSizeStop{4}); // BVH::NodeT
  ASSERT_FALSE(tree.empty());
  EXPECT_EQ(tree.prim.size(), boxes.size());
  const ebgeom::bvh::WideBvh<T, 4> flat = ebgeom::bvh::flatten<4>(tree); // flattenTree: LinearBVH
  // every primitive reachable through the flat tree: a nearest search from each centroid finds a
  // box at distance 0
  for (const V& c : centroids) {
    T best2 = std::numeric_limits<T>::infinity();
    ebgeom::bvh::nearest(flat, c, best2, [&](std::uint32_t first, std::uint32_t count, T& b2) {
      for (std::uint32_t i = first; i < first + count; ++i)
        b2 = std::min(b2, boxes[flat.prim[i]].distance2(c));
    });
    EXPECT_EQ(best2, T(0));
  }
  // BVH::Build::TopDown / Morton / SAH: BuildOptions::method; all give the same mesh SDF values
  for (auto m : {ebgeom::bvh::BuildMethod::median, ebgeom::bvh::BuildMethod::morton,
                 ebgeom::bvh::BuildMethod::sah_binned}) {
    ebgeom::bvh::BuildOptions o;
    o.method = m;
    const auto sdf = ebgeom::MeshSdf<T>::build(soup, o).value();
    const auto ref = ebgeom::MeshSdf<T>::build(soup).value();
    for (const auto& p : ebgeom::test::random_points(probe, 100)) EXPECT_EQ(sdf(p), ref(p));
  }
  // BoundingVolumes::BoundingSphereT: contains its points
  const auto s = ebgeom::BoundingSphere<T>::of_points(ebgeom::Span<const V>(soup.vertices));
  for (const V& v : soup.vertices) EXPECT_LE(ebgeom::norm(v - s.center), s.radius * (1 + 1e-12));
}

// The analytic shapes and the CSG / modifier IFs by name (EBGeometry's SphereSDF, BoxSDF, ...,
// IntersectionIF, DifferenceIF, ScaleIF, OffsetIF, AnnularIF, ElongateIF, ReflectIF, MollifyIF,
// FiniteRepetitionIF): each ebgeom equivalent against a value known in closed form.
TEST(FromEBGeometry, ShapesAndModifiersByName) {
  using namespace ebgeom;
  const V o{0, 0, 0}, x2{2, 0, 0};
  const Sphere<T> ball{o, 1};
  EXPECT_EQ(ball(x2), 1);                                                   // SphereSDF
  EXPECT_EQ((Box<T>{{1, 1, 1}}(x2)), 1);                                    // BoxSDF
  EXPECT_NEAR((RoundedBox<T>{{1, 1, 1}, 0.25}(x2)), 1, 1e-15);              // RoundedBoxSDF
  EXPECT_NEAR((Torus<T>{o, 1, 0.25}(x2)), 0.75, 1e-15);                     // TorusSDF
  EXPECT_NEAR((CappedCylinder<T>{{0, 0, -1}, {0, 0, 1}, 1}(x2)), 1, 1e-15); // CylinderSDF
  EXPECT_NEAR((InfiniteCylinder<T>{o, {0, 0, 1}, 0.5}(x2)), 1.5, 1e-15);    // InfiniteCylinderSDF
  EXPECT_NEAR((Capsule<T>{{0, 0, -1}, {0, 0, 1}, 0.5}(x2)), 1.5, 1e-15);    // CapsuleSDF
  EXPECT_NEAR((CappedCone<T>{{0, 0, -1}, {0, 0, 1}, 1, 1}(x2)), 1, 1e-12);  // ConeSDF (ra = rb)
  EXPECT_LT((InfiniteCone<T>::make(o, {0, 0, 1}, 0.5)(V{0, 0, 1})), 0);     // InfiniteConeSDF
  EXPECT_EQ((Plane<T>{{1, 0, 0}, 0.5}(x2)), 1.5);                           // PlaneSDF
  PerlinOptions<T> po;
  po.amplitude = 0;
  EXPECT_EQ(perlin_displace(ball, po)(x2), 1); // PerlinSDF with no noise is the shape
  const Sphere<T> right{{0.5, 0, 0}, 1};
  EXPECT_EQ(intersect(ball, right)(o), std::max(ball(o), right(o))); // IntersectionIF
  EXPECT_EQ(subtract(ball, right)(o), std::max(ball(o), -right(o))); // DifferenceIF
  EXPECT_EQ(scale(ball, T(2))(V{3, 0, 0}), 1);                       // ScaleIF
  EXPECT_EQ(offset(ball, T(0.5))(x2), 0.5);                          // OffsetIF (rounded)
  EXPECT_EQ(shell(ball, T(0.1))(o), 0.9);                            // AnnularIF
  EXPECT_NEAR(elongate(ball, V{1, 0, 0})(V{3, 0, 0}), 1, 1e-15);     // ElongateIF
  EXPECT_EQ(reflect(right, V{1, 0, 0})(V{-0.5, 0, 0}), -1);          // ReflectIF
  EXPECT_EQ(mirror(right, Axis::x)(V{-0.5, 0, 0}), -1);
  EXPECT_NEAR(mollify(Plane<T>{{1, 0, 0}, 0}, T(0.1))(x2), 2, 1e-12); // MollifyIF on a plane
  EXPECT_EQ(repeat(Sphere<T>{o, 0.1}, V{1, 0, 0}, {{2, 0, 0}})(V{2, 0, 0}), -0.1); // repetition
  EXPECT_EQ(repeat(Sphere<T>{o, 0.1}, V{1, 0, 0}, {{2, 0, 0}})(V{3, 0, 0}), 0.9);
  EXPECT_LE(exp_smooth_unite(ball, right, T(0.1))(o), std::min(ball(o), right(o)));
}

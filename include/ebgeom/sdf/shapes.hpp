// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Analytic shapes: small value types satisfying the SDF contract (sdf/concepts.hpp). S < 0
/// inside, > 0 outside. Each states its kind: `exact` (the true signed distance), `bound`
/// (1-Lipschitz, |S| <= distance, right sign) or `implicit` (sign only). Exact shapes use the
/// closed forms catalogued by Inigo Quilez ("distance functions", iquilezles.org), re-derived here
/// as 2D problems in the shape's meridian or cross-section. All evaluation is O(1), noexcept and
/// allocation-free; shapes are immutable after construction, so concurrent calls are safe.
///
/// Preconditions (documented per shape) are on sizes: radii and half extents are non-negative,
/// rounding radii do not exceed the size they round. The violations that a port from EBGeometry
/// is likely to hit are loud rather than silent: a negative radius (Sphere, Capsule,
/// CappedCylinder, InfiniteCylinder, Torus's tube) and a zero direction (InfiniteCylinder's axis,
/// Plane's normal) make every value NaN, instead of an empty shape, a ball or a plane through the
/// origin. Other violations give meaningless values, never undefined behaviour.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/sdf/concepts.hpp"

namespace ebgeom {

namespace detail {
/// Squared distance from `p` to segment [a, b] in 2D (a degenerate segment is a point).
template <class T>
inline T segment_distance2(const Vec2<T>& p, const Vec2<T>& a, const Vec2<T>& b) noexcept {
  const Vec2<T> ab = b - a, ap = p - a;
  const T l2 = dot(ab, ab);
  const T t = l2 > T(0) ? clamp(dot(ap, ab) / l2, T(0), T(1)) : T(0);
  return norm2(ap - ab * t);
}
/// Exact 2D signed distance to the axis-aligned rectangle |x| <= 0, |y| <= 0 shifted: takes
/// q = |p| - half (component-wise) and returns the box distance.
template <class T> inline T box2_from_q(T qx, T qy) noexcept {
  const T ox = std::max(qx, T(0)), oy = std::max(qy, T(0));
  return std::sqrt(ox * ox + oy * oy) + std::min(std::max(qx, qy), T(0));
}
/// Axial coordinate `h` (along a -> b, from a) and radial distance `rho` of `p`. `len` = |b - a|.
/// A degenerate axis (a == b) gives h = 0 and rho = |p - a|.
template <class T>
inline void axial_radial(const Vec3<T>& p, const Vec3<T>& a, const Vec3<T>& b, T& h, T& rho,
                         T& len) noexcept {
  const Vec3<T> ab = b - a, ap = p - a;
  len = norm(ab);
  const Vec3<T> w = len > T(0) ? ab / len : Vec3<T>::zero();
  h = dot(ap, w);
  rho = norm(ap - w * h);
}
/// Exact 2D signed distance to a regular convex polygon with `N` edges whose outward unit edge
/// normals are `n[i]` and whose apothem (center-to-edge distance) is `a`; `v[i]` are the unit-
/// apothem vertices, edge i running from v[i] to v[(i + 1) % N]. Inside: max_i (n_i.q - a);
/// outside: min over edges of the segment distance.
template <class T, int N>
inline T regular_polygon(const Vec2<T>& q, const double (&n)[N][2], const double (&v)[N][2],
                         T a) noexcept {
  T m = -std::numeric_limits<T>::infinity();
  for (int i = 0; i < N; ++i) m = std::max(m, T(n[i][0]) * q.x + T(n[i][1]) * q.y - a);
  if (m <= T(0)) return m;
  T d2 = std::numeric_limits<T>::infinity();
  for (int i = 0; i < N; ++i) {
    const int j = (i + 1) % N;
    d2 = std::min(d2, segment_distance2(q, Vec2<T>{T(v[i][0]) * a, T(v[i][1]) * a},
                                        Vec2<T>{T(v[j][0]) * a, T(v[j][1]) * a}));
  }
  return std::sqrt(d2);
}
/// Exact extrusion of a 2D signed distance `d2` along z to |z| <= half_height.
template <class T> inline T extrude(T d2, T z, T half_height) noexcept {
  return box2_from_q(d2, std::abs(z) - half_height);
}
constexpr double pi = 3.14159265358979323846;
constexpr double sqrt3 = 1.7320508075688772935;
/// `v` when `ok`, NaN otherwise: how shapes with an out-of-range size make themselves seen.
template <class T> constexpr T nan_unless(bool ok, T v) noexcept {
  return ok ? v : std::numeric_limits<T>::quiet_NaN();
}
} // namespace detail

/// Ball of `radius` (>= 0; negative gives NaN values) around `center`. Exact. Bounds: the
/// ball's box.
template <class T> struct Sphere {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> center;
  T radius;

  T operator()(const Vec3<T>& p) const noexcept {
    return detail::nan_unless(radius >= T(0), norm(p - center) - radius);
  }
  Aabb<T> bounds() const noexcept { return Aabb<T>::of(center).grown(radius); }
};

/// Axis-aligned box of half extents `half` around `center` (default the origin):
/// `Box<double>{{0.5, 0.5, 0.5}}`. Exact. Bounds: the box itself.
template <class T> struct Box {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> half;
  Vec3<T> center = Vec3<T>::zero();

  /// The box [lo, hi].
  static constexpr Box from_corners(const Vec3<T>& lo, const Vec3<T>& hi) noexcept {
    return {(hi - lo) * T(0.5), (lo + hi) * T(0.5)};
  }
  T operator()(const Vec3<T>& p) const noexcept {
    const Vec3<T> q = abs(p - center) - half;
    return norm(max(q, Vec3<T>::zero())) + std::min(max_component(q), T(0));
  }
  Aabb<T> bounds() const noexcept { return {center - half, center + half}; }
};

/// Box of outer half extents `half` whose edges and corners are rounded with `radius`
/// (0 <= radius <= min(half)). Exact: the inner box (half - radius) offset by `radius`, and an
/// offset of a convex set is exact inside and outside.
template <class T> struct RoundedBox {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> half;
  T radius;
  Vec3<T> center = Vec3<T>::zero();

  T operator()(const Vec3<T>& p) const noexcept {
    const Vec3<T> q = abs(p - center) - half + Vec3<T>::constant(radius);
    return norm(max(q, Vec3<T>::zero())) + std::min(max_component(q), T(0)) - radius;
  }
  Aabb<T> bounds() const noexcept { return {center - half, center + half}; }
};

/// Torus around the z axis through `center`: tube of radius `minor` around the circle of radius
/// `major` (0 <= minor <= major; a negative `minor` gives NaN values). Exact. Rotate it for other
/// axes.
template <class T> struct Torus {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> center;
  T major;
  T minor;

  T operator()(const Vec3<T>& p) const noexcept {
    const Vec3<T> q = p - center;
    const T rx = std::sqrt(q.x * q.x + q.y * q.y) - major;
    return detail::nan_unless(minor >= T(0), std::sqrt(rx * rx + q.z * q.z) - minor);
  }
  Aabb<T> bounds() const noexcept {
    const T r = major + minor;
    return {center - Vec3<T>{r, r, minor}, center + Vec3<T>{r, r, minor}};
  }
};

/// Capped torus (a bent capsule): tube of radius `minor` around the arc of radius `major` in the
/// xy plane through `center`, spanning angles up to `aperture` (radians, in [0, pi]) on either
/// side of +y, with spherical end caps. Build with `make` (stores sin and cos of the aperture).
/// Exact when minor <= major: the distance to an arc minus the tube radius.
template <class T> struct CappedTorus {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> center;
  T major;
  T minor;
  Vec2<T> sc; ///< (sin, cos) of the aperture

  static CappedTorus make(const Vec3<T>& center, T major, T minor, T aperture) noexcept {
    return {center, major, minor, {T(std::sin(aperture)), T(std::cos(aperture))}};
  }
  T operator()(const Vec3<T>& p) const noexcept {
    const Vec3<T> q = p - center;
    const T x = std::abs(q.x);
    // Inside the aperture (angle from +y below the aperture) the closest arc point is on the
    // circle, otherwise it is the end point major * (sin, cos).
    T d2;
    if (x * sc.y <= q.y * sc.x) {
      const T rx = std::sqrt(x * x + q.y * q.y) - major;
      d2 = rx * rx + q.z * q.z;
    } else {
      const T ex = x - major * sc.x, ey = q.y - major * sc.y;
      d2 = ex * ex + ey * ey + q.z * q.z;
    }
    return std::sqrt(d2) - minor;
  }
  Aabb<T> bounds() const noexcept {
    // the arc's box (y from major * cos(aperture), or -major past a half turn), grown by minor
    const T xmax = sc.y < T(0) ? major : major * sc.x;
    const T ymin = major * std::min(sc.y, T(1));
    return Aabb<T>{center + Vec3<T>{-xmax, ymin, 0}, center + Vec3<T>{xmax, major, 0}}.grown(minor);
  }
};

/// Cylinder of `radius` (>= 0; negative gives NaN values) around segment a-b (any orientation),
/// with flat caps. Exact: the 2D box distance in the (radial, axial) half-plane.
template <class T> struct CappedCylinder {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> a, b;
  T radius;

  T operator()(const Vec3<T>& p) const noexcept {
    T h, rho, len;
    detail::axial_radial(p, a, b, h, rho, len);
    return detail::nan_unless(
        radius >= T(0),
        detail::box2_from_q(rho - radius, std::abs(h - len * T(0.5)) - len * T(0.5)));
  }
  Aabb<T> bounds() const noexcept { return Aabb<T>::of(a, b).grown(radius); }
};

/// Capped cylinder a-b of outer `radius` whose rim edges are rounded with `rounding`
/// (0 <= rounding <= min(radius, |b - a| / 2)). Exact (2D rounded rectangle in the meridian).
template <class T> struct RoundedCylinder {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> a, b;
  T radius;
  T rounding;

  T operator()(const Vec3<T>& p) const noexcept {
    T h, rho, len;
    detail::axial_radial(p, a, b, h, rho, len);
    return detail::box2_from_q(rho - radius + rounding,
                               std::abs(h - len * T(0.5)) - len * T(0.5) + rounding) -
           rounding;
  }
  Aabb<T> bounds() const noexcept { return Aabb<T>::of(a, b).grown(radius); }
};

/// Infinite cylinder of `radius` around the line through `point` along `axis` (non-zero, any
/// length). Exact. Bounds: infinite. A zero axis or a negative radius gives NaN values.
template <class T> struct InfiniteCylinder {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> point;
  Vec3<T> axis;
  T radius;

  T operator()(const Vec3<T>& p) const noexcept {
    const Vec3<T> q = p - point;
    const T aa = dot(axis, axis);
    const T t = aa > T(0) ? dot(q, axis) / aa : T(0);
    return detail::nan_unless(aa > T(0) && radius >= T(0), norm(q - axis * t) - radius);
  }
  Aabb<T> bounds() const noexcept { return Aabb<T>::infinite(); }
};

/// Segment a-b swept by a ball of `radius` (>= 0; negative gives NaN values). Exact.
template <class T> struct Capsule {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> a, b;
  T radius;

  T operator()(const Vec3<T>& p) const noexcept {
    const Vec3<T> ab = b - a, ap = p - a;
    const T l2 = dot(ab, ab);
    const T h = l2 > T(0) ? clamp(dot(ap, ab) / l2, T(0), T(1)) : T(0);
    return detail::nan_unless(radius >= T(0), norm(ap - ab * h) - radius);
  }
  Aabb<T> bounds() const noexcept { return Aabb<T>::of(a, b).grown(radius); }
};

/// Truncated cone (frustum) from disk (a, `ra`) to disk (b, `rb`), flat caps; either radius may
/// be 0. Exact: the distance in the meridian half-plane to the three outline segments (bottom
/// cap, slanted side, top cap) of the trapezoid, negative inside it.
template <class T> struct CappedCone {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> a, b;
  T ra, rb;

  T operator()(const Vec3<T>& p) const noexcept {
    T h, rho, len;
    detail::axial_radial(p, a, b, h, rho, len);
    const Vec2<T> q{rho, h};
    const Vec2<T> a0{0, 0}, a1{ra, 0}, b1{rb, len}, b0{0, len};
    const T d2 =
        std::min({detail::segment_distance2(q, a0, a1), detail::segment_distance2(q, a1, b1),
                  detail::segment_distance2(q, b1, b0)});
    const bool inside = h >= T(0) && h <= len && (rho - ra) * len <= (rb - ra) * h;
    const T d = std::sqrt(d2);
    return inside ? -d : d;
  }
  Aabb<T> bounds() const noexcept {
    return merge(Aabb<T>::of(a).grown(ra), Aabb<T>::of(b).grown(rb));
  }
};

/// Infinite (one-nappe) cone with tip `apex`, opening along `axis` with half-angle in (0, pi/2).
/// Build with `make` (normalises the axis, stores sin and cos). Exact: the distance to the
/// generator in the meridian half-plane, or to the apex behind it. Bounds: infinite.
template <class T> struct InfiniteCone {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> apex;
  Vec3<T> axis; ///< unit
  Vec2<T> sc;   ///< (sin, cos) of the half-angle

  static InfiniteCone make(const Vec3<T>& apex, const Vec3<T>& axis, T half_angle) noexcept {
    return {apex, normalized(axis), {T(std::sin(half_angle)), T(std::cos(half_angle))}};
  }
  T operator()(const Vec3<T>& p) const noexcept {
    const Vec3<T> q = p - apex;
    const T h = dot(q, axis);
    const T rho = norm(q - axis * h);
    const T side = rho * sc.y - h * sc.x; // signed distance to the generator line
    const T along = rho * sc.x + h * sc.y;
    if (along <= T(0)) return std::sqrt(rho * rho + h * h); // behind the apex: outside
    return side;
  }
  Aabb<T> bounds() const noexcept { return Aabb<T>::infinite(); }
};

/// Half-space {p : dot(normal, p) <= offset * |normal|}: the plane at signed `offset` from the
/// origin along the (non-zero) `normal`, inside opposite the normal. Exact. Bounds: infinite. A
/// zero normal defines no plane: every value is NaN.
template <class T> struct Plane {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> normal;
  T offset;

  /// The plane through `point` with outward `normal`.
  static Plane through(const Vec3<T>& point, const Vec3<T>& normal) noexcept {
    const Vec3<T> n = normalized(normal);
    return {n, dot(n, point)};
  }
  T operator()(const Vec3<T>& p) const noexcept {
    const T n = norm(normal);
    return detail::nan_unless(n > T(0), (n > T(0) ? dot(normal, p) / n : T(0)) - offset);
  }
  Aabb<T> bounds() const noexcept { return Aabb<T>::infinite(); }
};
/// Alias: a plane is the boundary of its half-space.
template <class T> using HalfSpace = Plane<T>;

/// Axis-aligned ellipsoid with semi-axes `radii` (> 0) around `center`. Kind `bound`: no closed
/// form exists. Value: max(r_min (|q / radii| - 1), box(q)), where box is the exact SDF of the
/// ellipsoid's bounding box. Both terms are 1-Lipschitz and never exceed the true distance in
/// magnitude: the first because p -> p / radii is (1/r_min)-Lipschitz and maps the ellipsoid to
/// the unit ball; the second because the ellipsoid lies in the box (outside) and the first
/// term wins inside. (Quilez's popular k0 (k0 - 1) / k1 can overestimate, so it is not used.)
template <class T> struct Ellipsoid {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::bound;
  Vec3<T> center;
  Vec3<T> radii;

  T operator()(const Vec3<T>& p) const noexcept {
    const Vec3<T> q = p - center;
    const T scaled = min_component(radii) * (norm(div(q, radii)) - T(1));
    const Vec3<T> b = abs(q) - radii;
    const T box = norm(max(b, Vec3<T>::zero())) + std::min(max_component(b), T(0));
    return std::max(scaled, box);
  }
  Aabb<T> bounds() const noexcept { return {center - radii, center + radii}; }
};

/// Prism along z: an equilateral triangle of inradius `apothem` (one vertex on +y) extruded to
/// |z - center.z| <= half_height. Exact (exact 2D polygon distance, exact extrusion).
template <class T> struct TriangularPrism {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> center;
  T apothem;
  T half_height;

  T operator()(const Vec3<T>& p) const noexcept {
    // unit-apothem triangle: vertices at radius 2, angles 90, 210, 330 degrees; edge i from v[i]
    // to v[i+1] has the outward normal at angle 150, 270, 30 degrees.
    static constexpr double v[3][2] = {{0, 2}, {-detail::sqrt3, -1}, {detail::sqrt3, -1}};
    static constexpr double n[3][2] = {
        {-detail::sqrt3 / 2, 0.5}, {0, -1}, {detail::sqrt3 / 2, 0.5}};
    const Vec3<T> q = p - center;
    return detail::extrude(detail::regular_polygon<T, 3>({q.x, q.y}, n, v, apothem), q.z,
                           half_height);
  }
  Aabb<T> bounds() const noexcept {
    const T h = T(detail::sqrt3) * apothem;
    return {center + Vec3<T>{-h, -apothem, -half_height},
            center + Vec3<T>{h, T(2) * apothem, half_height}};
  }
};

/// Prism along z: a regular hexagon of inradius `apothem` (flat sides at +-y, vertices on +-x)
/// extruded to |z - center.z| <= half_height. Exact.
template <class T> struct HexagonalPrism {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> center;
  T apothem;
  T half_height;

  T operator()(const Vec3<T>& p) const noexcept {
    // unit apothem: circumradius 2/sqrt(3); vertices at 0, 60, ..., 300 degrees; edge normals at
    // 30, 90, ..., 330 degrees.
    constexpr double r = 2 / detail::sqrt3, h = 1 / detail::sqrt3;
    static constexpr double v[6][2] = {{r, 0}, {h, 1}, {-h, 1}, {-r, 0}, {-h, -1}, {h, -1}};
    static constexpr double n[6][2] = {
        {detail::sqrt3 / 2, 0.5},   {0, 1},  {-detail::sqrt3 / 2, 0.5},
        {-detail::sqrt3 / 2, -0.5}, {0, -1}, {detail::sqrt3 / 2, -0.5}};
    const Vec3<T> q = p - center;
    return detail::extrude(detail::regular_polygon<T, 6>({q.x, q.y}, n, v, apothem), q.z,
                           half_height);
  }
  Aabb<T> bounds() const noexcept {
    const T r = T(2 / detail::sqrt3) * apothem;
    return {center - Vec3<T>{r, apothem, half_height}, center + Vec3<T>{r, apothem, half_height}};
  }
};

// ---- Perlin noise displacement ---------------------------------------------------------------

/// Ken Perlin's improved gradient noise (Perlin 2002, "Improving noise"), with a permutation
/// table shuffled from `seed` (splitmix64 + Fisher-Yates, identical on every platform). Values
/// are clamped to [-1, 1]. 512 B. Thread-safe (immutable).
template <class T> struct PerlinNoise {
  std::uint8_t perm[256];

  explicit PerlinNoise(std::uint64_t seed = 0) noexcept {
    for (int i = 0; i < 256; ++i) perm[i] = std::uint8_t(i);
    std::uint64_t s = seed;
    for (int i = 255; i > 0; --i) {
      s += 0x9E3779B97F4A7C15ull; // splitmix64
      std::uint64_t z = s;
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
      z ^= z >> 31;
      const int j = int(z % std::uint64_t(i + 1));
      std::swap(perm[i], perm[j]);
    }
  }
  /// Noise at `p`, in [-1, 1]; 0 at integer lattice points and (rather than undefined
  /// integer conversions) at non-finite or huge (>= 1e15) coordinates.
  T operator()(const Vec3<T>& p) const noexcept {
    constexpr T big = T(1e15);
    if (!(std::abs(p.x) < big && std::abs(p.y) < big && std::abs(p.z) < big)) return T(0);
    const T fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
    const int X = int(std::int64_t(fx) & 255), Y = int(std::int64_t(fy) & 255),
              Z = int(std::int64_t(fz) & 255);
    const T x = p.x - fx, y = p.y - fy, z = p.z - fz;
    const T u = fade(x), v = fade(y), w = fade(z);
    const int A = hash(X) + Y, AA = hash(A) + Z, AB = hash(A + 1) + Z;
    const int B = hash(X + 1) + Y, BA = hash(B) + Z, BB = hash(B + 1) + Z;
    const T r = lerp1(
        w,
        lerp1(v, lerp1(u, grad(hash(AA), x, y, z), grad(hash(BA), x - 1, y, z)),
              lerp1(u, grad(hash(AB), x, y - 1, z), grad(hash(BB), x - 1, y - 1, z))),
        lerp1(v, lerp1(u, grad(hash(AA + 1), x, y, z - 1), grad(hash(BA + 1), x - 1, y, z - 1)),
              lerp1(u, grad(hash(AB + 1), x, y - 1, z - 1),
                    grad(hash(BB + 1), x - 1, y - 1, z - 1))));
    return clamp(r, T(-1), T(1));
  }

 private:
  int hash(int i) const noexcept { return perm[i & 255]; }
  static T fade(T t) noexcept { return t * t * t * (t * (t * T(6) - T(15)) + T(10)); }
  static T lerp1(T t, T a, T b) noexcept { return a + t * (b - a); }
  static T grad(int h, T x, T y, T z) noexcept {
    h &= 15; // the 12 cube-edge directions, 4 repeated (Perlin 2002)
    const T u = h < 8 ? x : y;
    const T v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
    return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
  }
};

/// Options of a Perlin displacement: octave k adds
/// amplitude * persistence^k * noise(frequency * lacunarity^k * p).
template <class T> struct PerlinOptions {
  T amplitude = T(0.1);
  Vec3<T> frequency = Vec3<T>::one();
  int octaves = 4;
  T persistence = T(0.5);
  T lacunarity = T(2);
  std::uint64_t seed = 0;
};

/// `shape` plus fractal Perlin noise (as EBGeometry's Perlin SDF): S(p) + sum of octaves.
/// Kind `implicit` (the noise gradient breaks the distance property). Bounds: the shape's box
/// grown by the largest possible displacement, amplitude * sum_k persistence^k, when the shape's
/// values outside its box are at least the box distance (true for exact and bound shapes).
template <class S> struct PerlinDisplaced {
  EBGEOM_REQUIRE_SDF(S);
  using T = sdf_scalar_t<S>;
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::implicit;
  S shape;
  PerlinOptions<T> options;
  PerlinNoise<T> noise;

  PerlinDisplaced(S s, const PerlinOptions<T>& opt) noexcept
      : shape(std::move(s)), options(opt), noise(opt.seed) {}

  T operator()(const Vec3<T>& p) const noexcept {
    T sum = 0, amp = options.amplitude;
    Vec3<T> f = options.frequency;
    for (int k = 0; k < options.octaves; ++k) {
      sum += amp * noise(mul(f, p));
      amp *= options.persistence;
      f *= options.lacunarity;
    }
    return shape(p) + sum;
  }
  /// amplitude * sum_k |persistence|^k: the largest |displacement|.
  T max_displacement() const noexcept {
    T sum = 0, amp = std::abs(options.amplitude);
    for (int k = 0; k < options.octaves; ++k, amp *= std::abs(options.persistence)) sum += amp;
    return sum;
  }
  Aabb<T> bounds() const noexcept { return shape.bounds().grown(max_displacement()); }
};

/// `shape` displaced by fractal Perlin noise (kind implicit).
template <class S>
PerlinDisplaced<S> perlin_displace(S shape, const PerlinOptions<sdf_scalar_t<S>>& opt) noexcept {
  return PerlinDisplaced<S>(std::move(shape), opt);
}

} // namespace ebgeom

// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `SignedMeshSdf<T, K, W>`: the exact distance of `MeshSdf` with a selectable sign, for meshes
/// that are not watertight (holes, flipped patches, duplicates, self-intersections). The magnitude
/// is always the exact unsigned distance to the triangles; only the sign comes from the mode:
///
/// | `SignMode` | inside when | cost per query |
/// | --- | --- | --- |
/// | `pseudonormal` | the closest feature's pseudonormal points away (Bærentzen & Aanæs 2005) |
/// nearest search | | `winding` | exact generalized winding number w > 1/2 (Jacobson et al. 2013) |
/// + O(n) | | `fast_winding` | Barill et al. 2018 approximation of w > 1/2 | + O(log n) | |
/// `unsigned_distance` | never (the value is the unsigned distance) | nearest search | |
/// `automatic` | `pseudonormal` when `validate` finds the mesh closed, manifold and consistently
/// oriented, else `fast_winding` | |
///
/// See docs/sign.md for the outcomes of each mode on imperfect meshes.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ebgeom/core/result.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"
#include "ebgeom/mesh/validate.hpp"
#include "ebgeom/sdf/concepts.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "ebgeom/sdf/split_sign.hpp"
#include "ebgeom/sdf/winding.hpp"

namespace ebgeom {

/// How a mesh SDF decides its sign (the magnitude is always the exact distance).
enum class SignMode : std::uint8_t {
  pseudonormal,      ///< closest feature's angle-weighted pseudonormal: exact on watertight meshes
  winding,           ///< exact generalized winding number > 1/2: robust, O(n) per query
  fast_winding,      ///< Barill et al. 2018 winding number > 1/2: robust, O(log n) per query
  unsigned_distance, ///< no sign: the unsigned distance (>= 0 everywhere)
  automatic,         ///< `pseudonormal` on valid closed meshes, `fast_winding` otherwise
};

/// The one name table of the sign modes, used by the library, the command-line tools (`--sign`)
/// and scene files (`"sign"`): "pseudonormal", "winding", "fast-winding", "unsigned", "auto".
inline constexpr std::pair<SignMode, const char*> sign_mode_names[] = {
    {SignMode::pseudonormal, "pseudonormal"},
    {SignMode::winding, "winding"},
    {SignMode::fast_winding, "fast-winding"},
    {SignMode::unsigned_distance, "unsigned"},
    {SignMode::automatic, "auto"}};

/// The name of a mode in `sign_mode_names` ("fast-winding" for `SignMode::fast_winding`).
inline const char* to_string(SignMode m) noexcept {
  for (const auto& n : sign_mode_names)
    if (n.first == m) return n.second;
  return "?";
}

/// The mode named `name` (`sign_mode_names`; exact, case-sensitive). Error `invalid_argument`
/// listing the names otherwise.
inline Result<SignMode> parse_sign_mode(std::string_view name) {
  for (const auto& n : sign_mode_names)
    if (name == n.second) return n.first;
  return Error{ErrorCode::invalid_argument,
               "unknown sign mode '" + std::string(name.substr(0, 40)) +
                   (name.size() > 40 ? "..." : "") +
                   "' (expected pseudonormal, winding, fast-winding, unsigned or auto)"};
}

/// The mode `automatic` resolves to, and why (one line).
struct SignChoice {
  SignMode mode = SignMode::pseudonormal;
  std::string reason;
};

/// What `automatic` picks for a mesh with validation report `r`: `pseudonormal` when the mesh is
/// closed (no boundary edge), manifold (edges and vertices), consistently oriented and has no two
/// shells whose boxes overlap (nested or intersecting shells), otherwise `fast_winding`. The reason
/// names the first failed condition with its count. An inward but otherwise valid mesh keeps
/// `pseudonormal` (every mode then reports the inside as outside; fix the orientation with
/// `orient_outward`), and the reason says so.
template <class T> SignChoice choose_sign_mode(const ValidationReport<T>& r) {
  SignChoice c;
  c.mode = SignMode::fast_winding;
  if (!r.offsets_ok || !r.bad_index_faces.empty() || !r.short_faces.empty() ||
      !r.non_finite_vertices.empty()) {
    c.reason = "the mesh is structurally invalid (bad offsets, indices, short faces or NaN)";
    return c;
  }
  if (!r.closed()) {
    c.reason = "not closed: " + std::to_string(r.boundary_edges.count) + " boundary edges in " +
               std::to_string(r.holes) + " holes";
    return c;
  }
  if (!r.non_manifold_edges.empty()) {
    c.reason = "not manifold: " + std::to_string(r.non_manifold_edges.count) +
               " edges with more than two faces";
    return c;
  }
  if (!r.non_manifold_vertices.empty()) {
    c.reason = "not manifold: " + std::to_string(r.non_manifold_vertices.count) +
               " vertices with more than one fan of faces";
    return c;
  }
  if (!r.consistently_oriented()) {
    c.reason = "inconsistently oriented: " + std::to_string(r.inconsistent_edges.count) +
               " edges whose two faces traverse them the same way";
    return c;
  }
  if (r.shells > 1 && r.shells_overlap) {
    c.reason = std::to_string(r.shells) +
               " closed shells with overlapping bounding boxes (nested or intersecting): the "
               "winding number decides, the nearest shell's pseudonormal may not";
    return c;
  }
  c.mode = SignMode::pseudonormal;
  c.reason = "closed, manifold and consistently oriented";
  if (!(r.signed_volume > 0))
    c.reason += " (but inward: negative volume, so inside reads as outside in every mode; "
                "use orient_outward)";
  return c;
}

/// Options of `SignedMeshSdf`.
struct SignOptions {
  SignMode mode = SignMode::automatic;
  WindingOptions winding; ///< fast winding accuracy (beta) and leaf size
};

/// Exact distance to a triangle mesh with the sign chosen by `SignMode` (see the file comment).
/// Wraps a `MeshSdf<T, K, W>` (the magnitude, bit for bit |`MeshSdf`'s value|) and, for
/// the winding modes, a `FastWindingNumber<T>` (its own default arity, 4). Sign convention: < 0
/// inside. Winding modes report inside where w > 1/2, so a value is negative only if w > 1/2 and
/// the distance is > 0. Never NaN for finite queries. Immutable; queries are const, allocation-free
/// and thread-safe. Follows the split-sign protocol (sdf/split_sign.hpp), so narrow bands stay fast
/// in every mode.
template <class T, int K = default_arity<T>, int W = default_block_width<T>> class SignedMeshSdf {
 public:
  using scalar_type = T;
  /// Exact magnitude; the sign is exact only with `pseudonormal` on valid meshes, so the static
  /// kind is the conservative `implicit`; `dynamic_kind()` gives the object's own.
  static constexpr SdfKind kind = SdfKind::implicit;

  /// Triangulates and validates `soup` (the validation decides `automatic`), then builds.
  /// Errors: those of `make_triangle_mesh` and `MeshSdf::make`.
  static Result<SignedMeshSdf> build(const PolygonSoup<T>& soup, const SignOptions& opt = {}) {
    Result<TriangleMesh<T>> m = make_triangle_mesh(soup);
    if (!m) return m.error();
    SignChoice choice;
    if (opt.mode == SignMode::automatic)
      choice = choose_sign_mode(validate(soup));
    else
      choice = {opt.mode, "requested"};
    return make_with(std::move(*m), choice, opt);
  }

  /// Builds from a triangle mesh; `automatic` validates its triangles as a soup.
  static Result<SignedMeshSdf> make(TriangleMesh<T> mesh, const SignOptions& opt = {}) {
    SignChoice choice;
    if (opt.mode == SignMode::automatic) {
      PolygonSoup<T> soup;
      soup.vertices = mesh.vertices;
      for (const auto& t : mesh.triangles) soup.add_triangle(t[0], t[1], t[2]);
      choice = choose_sign_mode(validate(soup));
    } else {
      choice = {opt.mode, "requested"};
    }
    return make_with(std::move(mesh), choice, opt);
  }

  /// Signed distance at `p` (< 0 inside; >= 0 everywhere for `unsigned_distance`).
  T operator()(const Vec3<T>& p) const noexcept {
    if (mode_ == SignMode::pseudonormal) return sdf_(p);
    return with_sign(std::abs(sdf_(p)), p);
  }

  /// Batch query (`evaluate` calls it): `out[i] = (*this)(pts[i])` bit for bit for i <
  /// min(pts.size(), out.size()). With the pseudonormal sign, `MeshSdf::eval` (the points in
  /// Morton order, faster than single queries on many scattered points); other modes query one
  /// point at a time.
  void eval(Span<const Vec3<T>> pts, Span<T> out) const noexcept {
    if (mode_ == SignMode::pseudonormal) return sdf_.eval(pts, out);
    const std::size_t n = std::min(pts.size(), out.size());
    for (std::size_t i = 0; i < n; ++i) out[i] = (*this)(pts[i]);
  }
  /// `eval` orders its points itself (`has_ordered_batch_v`).
  static constexpr bool batch_in_space_order = true;

  /// Closest point, triangle and feature of `MeshSdf::closest`, with `distance` signed by the
  /// mode (equal in magnitude to `MeshSdf::closest(p).distance`).
  MeshClosestPoint<T> closest(const Vec3<T>& p) const noexcept {
    MeshClosestPoint<T> c = sdf_.closest(p);
    const T d = std::abs(c.distance);
    switch (mode_) {
    case SignMode::pseudonormal:
      break;
    case SignMode::winding:
    case SignMode::fast_winding:
      c.distance = with_sign(d, p);
      break;
    default:
      c.distance = d;
    }
    return c;
  }

  /// Bounded query for grid samplers (`has_bounded_query_v`, as `MeshSdf::bounded`): exactly
  /// `(*this)(p)` (bit for bit) whenever |S(p)| <= `max_abs`, otherwise a value whose magnitude
  /// exceeds `max_abs` and whose sign means nothing. The search is bounded by `max_abs`; the
  /// winding modes compute their sign only for a value within it. With this, bands and coherent
  /// dense grids search as `MeshSdf`'s do.
  T bounded(const Vec3<T>& p, T max_abs) const noexcept {
    const T v = sdf_.bounded(p, max_abs);
    if (mode_ == SignMode::pseudonormal || !(std::abs(v) <= max_abs)) return v;
    return with_sign(std::abs(v), p);
  }

  /// Unsigned distance: |(*this)(p)| bit for bit (NaN for a non-finite p), without the closest
  /// point and its pseudonormal (`MeshSdf::unsigned_distance`).
  T unsigned_distance(const Vec3<T>& p) const noexcept { return sdf_.unsigned_distance(p); }

  /// Split-sign protocol: |S(p)| bit for bit when it is <= `max`, +infinity otherwise (a search
  /// bounded by `max`, faster than `unsigned_distance` far from the surface).
  T unsigned_within(const Vec3<T>& p, T max) const noexcept {
    const T d = sdf_.unsigned_bounded(p, max); // no pseudonormal read
    return d <= max ? d : std::numeric_limits<T>::infinity();
  }

  /// Split-sign protocol: the sign S has at `p` wherever |S(p)| > 0: from the winding number in
  /// the winding modes (negative where w > 1/2), always positive for `unsigned_distance`, from a
  /// full closest-point search with `pseudonormal`.
  Sign sign_at(const Vec3<T>& p) const noexcept {
    switch (mode_) {
    case SignMode::winding:
    case SignMode::fast_winding:
      return inside_by_winding(p) ? Sign::negative : Sign::positive;
    case SignMode::unsigned_distance:
      return Sign::positive;
    default:
      return std::signbit(sdf_(p)) ? Sign::negative : Sign::positive;
    }
  }

  /// Split-sign protocol, batch form: `out[i] = sign_at(pts[i])` for every i, the fast winding
  /// signs decided over runs of consecutive points (order them so that neighbours are near):
  /// `FastWindingNumber::above_half`, which bounds the fast winding numbers (the clusters far
  /// from a run's whole box once for the run, the rest in vectorised packets) and evaluates them
  /// exactly (bit for bit the per-point values) only where the bounds do not decide.
  void signs_at(Span<const Vec3<T>> pts, Span<Sign> out) const noexcept {
    EBGEOM_ASSERT(pts.size() == out.size());
    if (mode_ != SignMode::fast_winding) {
      for (std::size_t i = 0; i < pts.size(); ++i) out[i] = sign_at(pts[i]);
      return;
    }
    constexpr std::size_t B = FastWindingNumber<T>::batch_size;
    bool above[B];
    for (std::size_t i = 0; i < pts.size(); i += B) {
      const std::size_t n = std::min(pts.size() - i, B);
      fast_.above_half(pts.data() + i, n, above);
      for (std::size_t j = 0; j < n; ++j) out[i + j] = above[j] ? Sign::negative : Sign::positive;
    }
  }

  /// Split-sign protocol: a sign `sign_at` gives at every point of `box`, or `unknown`. Winding
  /// modes bound the winding number over the box (`FastWindingNumber::range_over`, or
  /// `winding_range` for the exact sum: O(n)) and answer only when the whole interval lies on
  /// one side of 1/2, so the answer is never wrong; `unknown` near the surface or where w
  /// crosses 1/2. `unsigned_distance`: always positive; `pseudonormal`: `unknown`.
  Sign sign_over(const Aabb<T>& box) const noexcept {
    int side = 0;
    switch (mode_) {
    case SignMode::fast_winding:
      side = fast_.range_over(box).side();
      break;
    case SignMode::winding:
      side = winding_range(sdf_.mesh(), box).side();
      break;
    case SignMode::unsigned_distance:
      return Sign::positive;
    default:
      return Sign::unknown;
    }
    return side > 0 ? Sign::negative : side < 0 ? Sign::positive : Sign::unknown;
  }

  /// Split-sign protocol, optional part: `sign_over` for several boxes inside one box (the
  /// scope), sharing the part of the work that is the same for all of them. With the fast winding
  /// sign, the walk of the tree above the scope (`FastWindingNumber::RangeScope`); otherwise
  /// `sign_over` itself. Never a sign `sign_at` would not give: `unknown` where unproven.
  class SignScope {
   public:
    Sign sign_over(const Aabb<T>& box) const noexcept {
      EBGEOM_ASSERT(sdf_ != nullptr); // filled by `sign_scope`
      if (sdf_->mode_ != SignMode::fast_winding) return sdf_->sign_over(box);
      const int side = sdf_->fast_.range_over(range_, box).side();
      return side > 0 ? Sign::negative : side < 0 ? Sign::positive : Sign::unknown;
    }

   private:
    friend class SignedMeshSdf;
    const SignedMeshSdf* sdf_ = nullptr;
    typename FastWindingNumber<T>::RangeScope range_;
  };

  /// Fills `out` for boxes inside `box` (see `SignScope`).
  void sign_scope(const Aabb<T>& box, SignScope& out) const noexcept {
    out.sdf_ = this;
    if (mode_ == SignMode::fast_winding) fast_.scope(box, out.range_);
  }

  /// Values at a tile of lattice samples, bit for bit `(*this)(pts[l])`: `MeshSdf::eval_lattice`
  /// with the pseudonormal sign; otherwise the unsigned distances of `MeshSdf::unsigned_lattice`,
  /// then the sign of the mode per sample (the fast winding sign in packets of nearby samples,
  /// `signs_at`).
  void eval_lattice(Span<const Vec3<T>> pts, const std::array<std::size_t, 3>& dims,
                    Span<T> out) const {
    if (mode_ == SignMode::pseudonormal) {
      sdf_.eval_lattice(pts, dims, out);
      return;
    }
    sdf_.unsigned_lattice(pts, dims, out);
    if (mode_ != SignMode::fast_winding) {
      for (std::size_t l = 0; l < pts.size(); ++l) out[l] = with_sign(std::abs(out[l]), pts[l]);
      return;
    }
    // Samples off the surface, in groups of 4x4x2 neighbours (x fastest).
    std::vector<std::size_t> idx;
    idx.reserve(pts.size());
    detail::for_each_in_sign_groups(dims, [&](std::size_t x, std::size_t y, std::size_t z) {
      const std::size_t l = x + dims[0] * (y + dims[1] * z);
      out[l] = std::abs(out[l]);
      if (out[l] > T(0)) idx.push_back(l);
    });
    std::vector<Vec3<T>> q(idx.size());
    std::vector<Sign> sg(idx.size());
    for (std::size_t i = 0; i < idx.size(); ++i) q[i] = pts[idx[i]];
    signs_at(Span<const Vec3<T>>(q), Span<Sign>(sg));
    for (std::size_t i = 0; i < idx.size(); ++i) out[idx[i]] = apply_sign(out[idx[i]], sg[i]);
  }

  /// Winding number at `p` by the resolved mode's method: exact for `winding`, fast otherwise
  /// (the fast structure exists only for the winding modes; pseudonormal and unsigned modes
  /// use the exact sum).
  T winding_number(const Vec3<T>& p) const noexcept {
    if (mode_ == SignMode::fast_winding) return fast_(p);
    return ebgeom::winding_number(sdf_.mesh(), p);
  }

  /// `exact` with the pseudonormal sign (as `MeshSdf`), `implicit` otherwise: a winding sign
  /// also changes across the surfaces that fill holes, far from the mesh, so evaluators must not
  /// propagate signs between far samples (`kind_of` in eval/evaluate.hpp reads this).
  SdfKind dynamic_kind() const noexcept {
    return mode_ == SignMode::pseudonormal ? SdfKind::exact : SdfKind::implicit;
  }

  /// The mode used (never `automatic`) and why it was chosen ("requested" unless automatic).
  SignMode resolved_mode() const noexcept { return mode_; }
  const std::string& reason() const noexcept { return reason_; }
  const MeshSdf<T, K, W>& mesh_sdf() const noexcept { return sdf_; }
  const TriangleMesh<T>& mesh() const noexcept { return sdf_.mesh(); }
  Aabb<T> bounds() const noexcept { return sdf_.bounds(); }
  std::size_t triangle_count() const noexcept { return sdf_.triangle_count(); }
  std::size_t memory_bytes() const noexcept {
    return sdf_.memory_bytes() + (mode_ == SignMode::fast_winding ? fast_.memory_bytes() : 0);
  }

 private:
  static Result<SignedMeshSdf> make_with(TriangleMesh<T> mesh, const SignChoice& choice,
                                         const SignOptions& opt) {
    if (int(choice.mode) > int(SignMode::automatic))
      return make_error(ErrorCode::invalid_argument, "sign mode ", int(choice.mode),
                        " is not a SignMode (expected pseudonormal, winding, fast_winding, "
                        "unsigned_distance or automatic)");
    SignedMeshSdf s;
    s.mode_ = choice.mode;
    s.reason_ = choice.reason;
    auto sdf = MeshSdf<T, K, W>::make(std::move(mesh)); // checks indices and coordinates
    if (!sdf) return sdf.error();
    s.sdf_ = std::move(*sdf);
    if (s.mode_ == SignMode::fast_winding) {
      auto f = FastWindingNumber<T>::make(s.sdf_.mesh(), opt.winding);
      if (!f) return f.error();
      s.fast_ = std::move(*f);
    }
    return s;
  }

  /// The value of a non-pseudonormal mode from the unsigned distance `d` at `p` (the winding
  /// number is computed only where d > 0).
  T with_sign(T d, const Vec3<T>& p) const noexcept {
    return d > T(0) && mode_ != SignMode::unsigned_distance && inside_by_winding(p) ? -d : d;
  }

  bool inside_by_winding(const Vec3<T>& p) const noexcept {
    const T w = mode_ == SignMode::fast_winding ? fast_(p) : ebgeom::winding_number(sdf_.mesh(), p);
    return w > T(0.5);
  }

  MeshSdf<T, K, W> sdf_;
  FastWindingNumber<T> fast_;
  SignMode mode_ = SignMode::pseudonormal;
  std::string reason_;
};

} // namespace ebgeom

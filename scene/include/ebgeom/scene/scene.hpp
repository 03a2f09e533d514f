// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// JSON scene files (docs/scene-format.md) compiled into a `SceneSdf<T>`: a tree of the library's
// shapes, transforms, CSG and mesh SDFs (nodes.hpp). Every error names the file and the JSON
// pointer of the offending value, e.g.
// `scene.json: /root/children/2/radius: expected a positive number, got -1`.

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "ebgeom/core/rotation.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/scene/error.hpp"
#include "ebgeom/scene/mesh_input.hpp"
#include "ebgeom/scene/mesh_registry.hpp"
#include "ebgeom/scene/nodes.hpp"
#include "ebgeom/scene/scene_sdf.hpp"
#include "ebgeom/sdf/shapes.hpp"

namespace ebgeom::scene {

using Json = nlohmann::json;

/// JSON documents nested deeper than this are refused before a tree is built.
inline constexpr std::size_t max_json_depth = 1000;

/// Parses JSON text read from `path` (named in messages). A first, non-recursive pass rejects
/// nesting deeper than `max_json_depth` and duplicate object keys, so every later recursive walk
/// is bounded. Throws ToolError (input): `FILE: line L, column C: what` (one short line).
Json parse_json_text(const std::string& text, const std::string& path);

/// Reads and parses a JSON file (`parse_json_text`). Throws ToolError (input).
Json read_json_file(const std::string& path);

/// `s` cut to at most `max` characters with "..." in the middle (long JSON pointers, keys).
std::string shorten(const std::string& s, std::size_t max);

/// `s` with control characters escaped (`\n`, `\t`, `\xHH`), so that a message quoting a key or
/// file name stays on one line.
std::string printable(const std::string& s);

/// True when `path` names a scene file (extension .json).
bool is_scene_path(const std::string& path);

/// The sign mode one mesh of a scene got, and why.
struct MeshSignUse {
  std::string where;  ///< JSON pointer of the mesh node
  std::string source; ///< mesh file, "generate: NAME" or "ref: NAME" (an in-memory mesh)
  SignMode requested = SignMode::automatic, used = SignMode::automatic;
  std::string reason; ///< "requested", or what `auto` found
};

/// Facts about a compiled scene, for summaries.
struct SceneInfo {
  std::size_t nodes = 0, primitives = 0, meshes = 0;
  std::vector<MeshSignUse> mesh_signs; ///< one per mesh node, in file order
};

/// `--json`'s "meshes": [{"node", "source", "sign", "sign_used", "reason"}] of a scene.
inline Json mesh_signs_json(const SceneInfo& info) {
  Json a = Json::array();
  for (const MeshSignUse& m : info.mesh_signs)
    a.push_back({{"node", m.where.empty() ? "/" : m.where},
                 {"source", m.source},
                 {"sign", to_string(m.requested)},
                 {"sign_used", to_string(m.used)},
                 {"reason", m.reason}});
  return a;
}

/// The summary's lines, one per mesh: `  sign      NODE (SOURCE): MODE (REASON)`.
inline void print_mesh_signs(const SceneInfo& info) {
  for (const MeshSignUse& m : info.mesh_signs)
    std::printf("  sign      %s (%s): %s (%s)\n", m.where.empty() ? "/" : m.where.c_str(),
                m.source.c_str(), to_string(m.used), m.reason.c_str());
}

namespace internal {

/// Appends the JSON text of `j` to `out` until `out` holds more than `budget` characters: O(budget)
/// work whatever the size of `j` (no full dump of a large or deep value).
inline void describe_into(const Json& j, std::string& out, std::size_t budget) {
  if (out.size() > budget) return;
  if (j.is_array() || j.is_object()) {
    out += j.is_array() ? '[' : '{';
    bool first = true;
    for (auto it = j.begin(); it != j.end() && out.size() <= budget; ++it) {
      if (!first) out += ',';
      first = false;
      if (j.is_object()) out += Json(it.key()).dump() + ':';
      describe_into(*it, out, budget);
    }
    out += j.is_array() ? ']' : '}';
  } else {
    out += j.dump();
  }
}

/// A short text of `j` for messages (at most 40 characters).
inline std::string describe(const Json& j) {
  std::string s;
  describe_into(j, s, 40);
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

/// Rigid transform plus uniform scale of a scene node: world = t + R (s * local).
template <class T> struct Xform {
  Mat3<T> r;
  Vec3<T> t = Vec3<T>::zero();
  T s = 1;
  Vec3<T> to_world(const Vec3<T>& p) const noexcept { return r * (p * s) + t; }
};

/// A compiled node: its SDF and the box that contains its zero level set and inside.
template <class T> struct Built {
  AnySdf<T> sdf;
  Aabb<T> box;
};

template <class T> class SceneCompiler {
 public:
  SceneCompiler(std::string file, SceneInfo& info, const MeshRegistry* meshes = nullptr)
      : file_(std::move(file)), info_(info), meshes_(meshes) {
    dir_ = std::filesystem::path(file_).parent_path().string();
  }

  [[noreturn]] void bad(const std::string& ptr, const std::string& msg) const {
    fail(exit_input, printable(file_ + ": " + (ptr.empty() ? "/" : shorten(ptr, 80)) + ": " + msg));
  }

  /// Triangles of the meshes compiled so far.
  std::size_t triangles() const noexcept { return triangles_; }

  /// Compiles a node.
  Built<T> node(const Json& j, const std::string& ptr) {
    if (!j.is_object()) bad(ptr, "expected a node object {\"type\": ...}, got " + describe(j));
    if (++depth_ > max_depth) bad(ptr, "nodes are nested deeper than " + std::to_string(max_depth));
    ++info_.nodes;
    const auto t = j.find("type");
    if (t == j.end())
      bad(ptr, "missing \"type\" (sphere, box, capsule, cylinder, cone, torus, plane, "
               "mesh, union, intersection, difference, transform)");
    if (!t->is_string()) bad(ptr + "/type", "expected a string, got " + describe(*t));
    const std::string type = *t;

    const bool has_xform = j.contains("translate") || j.contains("rotate") || j.contains("scale");
    Xform<T> x;
    if (has_xform) x = parse_xform(j, ptr);
    Built<T> n = body(type, j, ptr);
    Aabb<T>& b = n.box;
    const bool bounded = !b.is_empty() && finite_box(b);
    if (has_xform) {
      b = transform_box(x, b);
      n.sdf = AnySdf<T>(TransformNode<T>(std::move(n.sdf), x.r, x.t, x.s, b));
    }
    if (j.contains("offset")) {
      const T r = number(j, ptr, "offset", Need::finite);
      if (r > 0) b = b.grown(r);
      n.sdf = AnySdf<T>(ModifierNode<T>(ModifierNode<T>::Op::offset, std::move(n.sdf), r, b));
    }
    if (j.contains("shell")) {
      const T s = number(j, ptr, "shell", Need::positive);
      b = b.grown(s);
      n.sdf = AnySdf<T>(ModifierNode<T>(ModifierNode<T>::Op::shell, std::move(n.sdf), s, b));
    }
    // A transform or growth cannot make a bounded shape unbounded: only overflow can.
    if (bounded && (b.is_empty() || !finite_box(b))) { // NaN corners leave the box empty
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "the bounds of this node overflow %s precision (transformed or grown beyond "
                    "%.3g)%s",
                    precision_name<T>(), double(std::numeric_limits<T>::max()),
                    sizeof(T) == 4 ? "; use --precision double or smaller values"
                                   : "; use smaller values");
      bad(ptr, buf);
    }
    --depth_;
    return n;
  }

 private:
  enum class Need { finite, positive, non_negative };

  void check_keys(const Json& j, const std::string& ptr, const std::string& type,
                  std::initializer_list<const char*> allowed) const {
    static const char* common[] = {"type",   "name",  "comment", "translate",
                                   "rotate", "scale", "offset",  "shell"};
    for (auto it = j.begin(); it != j.end(); ++it) {
      bool ok = false;
      for (const char* c : common) ok = ok || it.key() == c;
      for (const char* a : allowed) ok = ok || it.key() == a;
      if (!ok) {
        std::string list;
        for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
        bad(ptr + "/" + it.key(), "unknown key for a " + type +
                                      " (its keys: " + (list.empty() ? std::string("none") : list) +
                                      "; any node: name, translate, rotate, scale, offset, shell)");
      }
    }
  }

  T number(const Json& j, const std::string& ptr, const char* key, Need need) const {
    const auto it = j.find(key);
    if (it == j.end()) bad(ptr, std::string("missing \"") + key + "\"");
    return number_value(*it, ptr + "/" + key, need);
  }
  T number_or(const Json& j, const std::string& ptr, const char* key, Need need, T dflt) const {
    return j.contains(key) ? number(j, ptr, key, need) : dflt;
  }
  T number_value(const Json& v, const std::string& where, Need need) const {
    const char* what = need == Need::positive       ? "a positive number"
                       : need == Need::non_negative ? "a number >= 0"
                                                    : "a finite number";
    if (!v.is_number()) bad(where, std::string("expected ") + what + ", got " + describe(v));
    const double d = v.get<double>();
    if (!std::isfinite(d) || (need == Need::positive && !(d > 0)) ||
        (need == Need::non_negative && !(d >= 0)))
      bad(where, std::string("expected ") + what + ", got " + describe(v));
    check_magnitude(d, where);
    return T(d);
  }
  /// Refuses a value whose magnitude the working precision cannot carry through squared
  /// distances (`max_magnitude<T>()`), or a non-zero value that rounds to zero in T.
  void check_magnitude(double d, const std::string& where) const {
    char buf[160];
    if (std::abs(d) > max_magnitude<T>()) {
      std::snprintf(buf, sizeof buf, "%.6g is too large for %s precision (at most %.3g)", d,
                    precision_name<T>(), max_magnitude<T>());
      bad(where,
          std::string(buf) + (sizeof(T) == 4 ? "; use --precision double" : "; rescale the scene"));
    }
    if (d != 0 && T(d) == T(0)) {
      std::snprintf(buf, sizeof buf, "%.6g is too small for %s precision (it rounds to 0)", d,
                    precision_name<T>());
      bad(where, std::string(buf) + (sizeof(T) == 4 ? "; use --precision double" : ""));
    }
  }
  /// A finite number in double precision (angles, reduced before use).
  double finite_double(const Json& j, const std::string& ptr, const char* key) const {
    const auto it = j.find(key);
    if (it == j.end()) bad(ptr, std::string("missing \"") + key + "\"");
    if (!it->is_number() || !std::isfinite(it->template get<double>()))
      bad(ptr + "/" + key, "expected a finite number, got " + describe(*it));
    return it->template get<double>();
  }
  Vec3<T> vec3(const Json& j, const std::string& ptr, const char* key, Need need) const {
    const auto it = j.find(key);
    if (it == j.end()) bad(ptr, std::string("missing \"") + key + "\"");
    return vec3_value(*it, ptr + "/" + key, need);
  }
  Vec3<T> vec3_or(const Json& j, const std::string& ptr, const char* key, Vec3<T> dflt) const {
    return j.contains(key) ? vec3(j, ptr, key, Need::finite) : dflt;
  }
  Vec3<T> vec3_value(const Json& v, const std::string& where, Need need) const {
    if (!v.is_array() || v.size() != 3)
      bad(where, "expected an array of 3 numbers [x, y, z], got " + describe(v));
    Vec3<T> r;
    for (int a = 0; a < 3; ++a) r[a] = number_value(v[a], where + "/" + std::to_string(a), need);
    return r;
  }

  Xform<T> parse_xform(const Json& j, const std::string& ptr) const {
    Xform<T> x;
    if (j.contains("scale")) {
      x.s = number(j, ptr, "scale", Need::positive);
      // Points are divided by the scale: below 1 / max_magnitude they would overflow.
      if (double(x.s) < 1 / max_magnitude<T>()) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "%.6g is too small for %s precision (at least %.3g)",
                      double(x.s), precision_name<T>(), 1 / max_magnitude<T>());
        bad(ptr + "/scale", buf);
      }
    }
    if (j.contains("rotate")) {
      const Json& r = j["rotate"];
      const std::string rp = ptr + "/rotate";
      if (!r.is_object())
        bad(rp, "expected {\"axis\": [x, y, z], \"degrees\": angle}, got " + describe(r));
      for (auto it = r.begin(); it != r.end(); ++it)
        if (it.key() != "axis" && it.key() != "degrees")
          bad(rp + "/" + it.key(), "unknown key (rotate has: axis, degrees)");
      const Vec3<T> axis = vec3(r, rp, "axis", Need::finite);
      if (!(norm(axis) > T(0))) bad(rp + "/axis", "the rotation axis must not be zero");
      // Reduced to (-360, 360) in double first: a huge angle in float would be inf. The
      // library's rotation (Rodrigues' formula, exact at quarter turns).
      x.r = Mat3<T>::axis_degrees(axis, T(std::fmod(finite_double(r, rp, "degrees"), 360.0)));
    }
    if (j.contains("translate")) x.t = vec3(j, ptr, "translate", Need::finite);
    return x;
  }

  /// Finite bounds, or the canonical empty box; false for infinite or NaN coordinates (a NaN
  /// corner, from 0 * inf in an overflowing transform, can make a box look empty).
  static bool finite_box(const Aabb<T>& b) {
    const T inf = std::numeric_limits<T>::infinity();
    bool empty = true, finite = true;
    for (int a = 0; a < 3; ++a) {
      empty = empty && b.lo[a] == inf && b.hi[a] == -inf;
      finite = finite && std::isfinite(b.lo[a]) && std::isfinite(b.hi[a]);
    }
    return empty || finite;
  }

  static Aabb<T> transform_box(const Xform<T>& x, const Aabb<T>& b) {
    if (b.is_empty()) return b;
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(b.lo[a]) || !std::isfinite(b.hi[a])) return Aabb<T>::infinite();
    Aabb<T> r;
    for (int c = 0; c < 8; ++c)
      r.extend(x.to_world(
          {(c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z}));
    return r;
  }

  Built<T> body(const std::string& type, const Json& j, const std::string& ptr) {
    if (type == "sphere") {
      check_keys(j, ptr, type, {"center", "radius"});
      const Vec3<T> c = vec3_or(j, ptr, "center", Vec3<T>::zero());
      const T r = number(j, ptr, "radius", Need::positive);
      return leaf(Sphere<T>{c, r}, Aabb<T>::of(c).grown(r));
    }
    if (type == "box") {
      check_keys(j, ptr, type, {"center", "size", "half_size", "rounding"});
      const Vec3<T> c = vec3_or(j, ptr, "center", Vec3<T>::zero());
      Vec3<T> h;
      if (j.contains("size") == j.contains("half_size"))
        bad(ptr, "a box needs exactly one of \"size\" (full edge lengths) or \"half_size\"");
      if (j.contains("size"))
        h = vec3(j, ptr, "size", Need::positive) * T(0.5);
      else
        h = vec3(j, ptr, "half_size", Need::positive);
      const T r = number_or(j, ptr, "rounding", Need::non_negative, T(0));
      if (r > min_component(h)) bad(ptr + "/rounding", "must not exceed the smallest half size");
      if (r > T(0)) return leaf(RoundedBox<T>{h, r, c}, Aabb<T>(c - h, c + h));
      return leaf(Box<T>{h, c}, Aabb<T>(c - h, c + h));
    }
    if (type == "capsule" || type == "cylinder") {
      check_keys(j, ptr, type, {"a", "b", "radius"});
      const Vec3<T> a = vec3(j, ptr, "a", Need::finite), b = vec3(j, ptr, "b", Need::finite);
      const T r = number(j, ptr, "radius", Need::positive);
      if (type == "cylinder" && !(norm(b - a) > T(0)))
        bad(ptr + "/b", "a cylinder needs distinct end points a and b");
      if (type == "capsule") return leaf(Capsule<T>{a, b, r}, Aabb<T>::of(a, b).grown(r));
      return leaf(CappedCylinder<T>{a, b, r}, Aabb<T>::of(a, b).grown(r));
    }
    if (type == "cone") {
      check_keys(j, ptr, type, {"a", "b", "radius_a", "radius_b"});
      const Vec3<T> a = vec3(j, ptr, "a", Need::finite), b = vec3(j, ptr, "b", Need::finite);
      const T ra = number(j, ptr, "radius_a", Need::non_negative);
      const T rb = number(j, ptr, "radius_b", Need::non_negative);
      if (!(norm(b - a) > T(0))) bad(ptr + "/b", "a cone needs distinct end points a and b");
      if (!(ra > 0 || rb > 0)) bad(ptr, "a cone needs radius_a > 0 or radius_b > 0");
      return leaf(CappedCone<T>{a, b, ra, rb},
                  merge(Aabb<T>::of(a).grown(ra), Aabb<T>::of(b).grown(rb)));
    }
    if (type == "torus") {
      check_keys(j, ptr, type, {"center", "major_radius", "minor_radius"});
      const Vec3<T> c = vec3_or(j, ptr, "center", Vec3<T>::zero());
      const T R = number(j, ptr, "major_radius", Need::positive);
      const T r = number(j, ptr, "minor_radius", Need::positive);
      return leaf(Torus<T>{c, R, r},
                  Aabb<T>(c - Vec3<T>{R + r, R + r, r}, c + Vec3<T>{R + r, R + r, r}));
    }
    if (type == "plane") {
      check_keys(j, ptr, type, {"normal", "point"});
      Vec3<T> n = vec3(j, ptr, "normal", Need::finite);
      if (!(norm(n) > T(0))) bad(ptr + "/normal", "the normal must not be zero");
      const Vec3<T> p = vec3_or(j, ptr, "point", Vec3<T>::zero());
      return leaf(Plane<T>::through(p, n), Aabb<T>::infinite());
    }
    if (type == "mesh") return mesh(j, ptr);
    if (type == "union" && j.contains("accelerate")) return accelerated_union(j, ptr);
    if (type == "union" || type == "intersection" || type == "difference") {
      check_keys(j, ptr, type, {"children", "smooth"});
      const auto ch = j.find("children");
      if (ch == j.end()) bad(ptr, "missing \"children\" (an array of nodes)");
      if (!ch->is_array() || ch->empty())
        bad(ptr + "/children", "expected a non-empty array of nodes, got " + describe(*ch));
      const T k = number_or(j, ptr, "smooth", Need::non_negative, T(0));
      Aabb<T> b;
      std::vector<AnySdf<T>> children;
      for (std::size_t i = 0; i < ch->size(); ++i) {
        Built<T> c = node((*ch)[i], ptr + "/children/" + std::to_string(i));
        const Aabb<T> cb = c.box;
        children.push_back(std::move(c.sdf));
        if (type == "union")
          b.extend(cb);
        else if (type == "intersection")
          b = i == 0 ? cb : Aabb<T>(max(b.lo, cb.lo), min(b.hi, cb.hi));
        else if (i == 0)
          b = cb;
      }
      const CsgOp op = type == "union"          ? CsgOp::unite
                       : type == "intersection" ? CsgOp::intersect
                                                : CsgOp::subtract;
      if (k > 0 && type == "union") b = b.grown(k);
      if (b.is_empty()) b = Aabb<T>(Vec3<T>::zero(), Vec3<T>::zero());
      return {AnySdf<T>(CsgNode<T>(op, std::move(children), k, b)), b};
    }
    if (type == "transform") {
      check_keys(j, ptr, type, {"child"});
      const auto c = j.find("child");
      if (c == j.end()) bad(ptr, "missing \"child\" (the node to transform)");
      return node(*c, ptr + "/child");
    }
    bad(ptr + "/type", "unknown node type \"" + shorten(type, 40) +
                           "\" (expected sphere, box, capsule, cylinder, cone, torus, plane, mesh, "
                           "union, intersection, difference or transform)");
  }

  /// A sharp union whose children are compiled separately and searched through a BVH of their
  /// boxes (`"accelerate": true`).
  Built<T> accelerated_union(const Json& j, const std::string& ptr) {
    check_keys(j, ptr, "union", {"children", "smooth", "accelerate"});
    if (!j["accelerate"].is_boolean()) bad(ptr + "/accelerate", "expected true or false");
    const auto ch = j.find("children");
    if (ch == j.end()) bad(ptr, "missing \"children\" (an array of nodes)");
    if (!ch->is_array() || ch->empty())
      bad(ptr + "/children", "expected a non-empty array of nodes, got " + describe(*ch));
    if (!j["accelerate"].get<bool>()) {
      Json copy = j;
      copy.erase("accelerate");
      return body("union", copy, ptr);
    }
    if (number_or(j, ptr, "smooth", Need::non_negative, T(0)) > 0)
      bad(ptr + "/accelerate", "an accelerated union must be sharp (no \"smooth\")");
    std::vector<AnySdf<T>> children;
    SdfKind children_kind = SdfKind::exact;
    for (std::size_t i = 0; i < ch->size(); ++i) {
      const std::string cp = ptr + "/children/" + std::to_string(i);
      Built<T> c = node((*ch)[i], cp);
      for (int a = 0; a < 3; ++a)
        if (!std::isfinite(c.box.lo[a]) || !std::isfinite(c.box.hi[a]))
          bad(cp, "children of an accelerated union must be bounded (a plane is not)");
      children_kind = weakest(children_kind, c.sdf.dynamic_kind());
      children.push_back(std::move(c.sdf));
    }
    const std::size_t count = children.size();
    auto u = BvhUnion<AnySdf<T>>::make(std::move(children));
    if (!u) bad(ptr, u.error().what());
    const Aabb<T> b = u->bounds();
    return {AnySdf<T>(BvhUnionNode<T>(std::move(*u), children_kind, count)), b};
  }

  template <class Shape> Built<T> leaf(Shape shape, const Aabb<T>& b) {
    ++info_.primitives;
    return {AnySdf<T>(std::move(shape)), b};
  }

  Built<T> mesh(const Json& j, const std::string& ptr) {
    check_keys(j, ptr, "mesh",
               {"path", "generate", "ref", "sign", "subdivisions", "radius", "major_radius",
                "minor_radius", "min", "max"});
    SignMode sign = SignMode::automatic;
    if (j.contains("sign")) {
      if (!j["sign"].is_string()) bad(ptr + "/sign", "expected a string");
      const Result<SignMode> m = ebgeom::parse_sign_mode(j["sign"].get<std::string>());
      if (!m) bad(ptr + "/sign", m.error().what());
      sign = *m;
    }
    PolygonSoup<T> soup;
    const PolygonSoup<T>* input = &soup; // an in-memory double mesh is used where it is
    std::string label, source;
    if (int(j.contains("path")) + int(j.contains("generate")) + int(j.contains("ref")) != 1)
      bad(ptr, "a mesh needs exactly one of \"path\" (a mesh file), \"generate\" or \"ref\" (an "
               "in-memory mesh)");
    if (j.contains("ref")) {
      if (!j["ref"].is_string()) bad(ptr + "/ref", "expected the name of an in-memory mesh");
      const std::string name = j["ref"];
      const MeshRegistry::MeshPtr m = meshes_ ? meshes_->find(name) : nullptr;
      if (!m)
        bad(ptr + "/ref",
            "no in-memory mesh is registered as \"" + shorten(name, 40) + "\"" +
                (meshes_ && !meshes_->empty()
                     ? " (" + std::to_string(meshes_->size()) + " registered)"
                     : std::string(" (none are: a scene file read on its own names mesh files "
                                   "with \"path\")")));
      label = "in-memory mesh \"" + name + "\"";
      source = "ref: " + name;
      if constexpr (std::is_same_v<T, double>) {
        input = m.get();
      } else {
        soup.indices = m->indices;
        soup.offsets = m->offsets;
        soup.vertices.reserve(m->vertices.size());
        for (const Vec3<double>& v : m->vertices) soup.vertices.push_back(Vec3<T>::from(v));
      }
    } else if (j.contains("path")) {
      if (!j["path"].is_string()) bad(ptr + "/path", "expected a file name string");
      std::filesystem::path p = j["path"].get<std::string>();
      if (p.is_relative() && !dir_.empty()) p = std::filesystem::path(dir_) / p;
      label = p.string();
      if (!std::filesystem::exists(p)) bad(ptr + "/path", "mesh file " + label + " does not exist");
      if (std::filesystem::is_directory(p))
        bad(ptr + "/path", label + " is a directory, not a mesh file");
      soup = load_mesh<T>(label);
      source = label;
    } else {
      if (!j["generate"].is_string()) bad(ptr + "/generate", "expected a string");
      const std::string g = j["generate"];
      label = file_ + ": " + ptr;
      Result<PolygonSoup<T>> r = make_error(ErrorCode::invalid_argument, "");
      if (g == "icosphere") {
        const T sub = number_or(j, ptr, "subdivisions", Need::non_negative, T(3));
        if (sub != std::floor(sub) || sub > 7) bad(ptr + "/subdivisions", "expected 0 to 7");
        r = make_icosphere<T>(int(sub), number_or(j, ptr, "radius", Need::positive, T(1)));
      } else if (g == "torus") {
        r = make_torus<T>(number(j, ptr, "major_radius", Need::positive),
                          number(j, ptr, "minor_radius", Need::positive));
      } else if (g == "box") {
        r = make_box<T>(vec3(j, ptr, "min", Need::finite), vec3(j, ptr, "max", Need::finite));
      } else if (g == "tetrahedron") {
        r = make_tetrahedron<T>(number_or(j, ptr, "radius", Need::positive, T(1)));
      } else if (g == "octahedron") {
        r = make_octahedron<T>(number_or(j, ptr, "radius", Need::positive, T(1)));
      } else if (g == "icosahedron") {
        r = make_icosahedron<T>(number_or(j, ptr, "radius", Need::positive, T(1)));
      } else {
        bad(ptr + "/generate", "unknown generator \"" + shorten(g, 40) +
                                   "\" (expected icosphere, torus, box, tetrahedron, "
                                   "octahedron or icosahedron)");
      }
      if (!r) bad(ptr, r.error().what());
      soup = std::move(*r);
      source = "generate: " + g;
    }
    auto sdf = std::make_shared<const SignedMeshSdf<T>>(build_mesh_sdf(*input, label, sign));
    info_.mesh_signs.push_back({ptr, source, sign, sdf->resolved_mode(), sdf->reason()});
    ++info_.meshes;
    triangles_ += sdf->triangle_count();
    const Aabb<T> b = sdf->bounds();
    return {AnySdf<T>(MeshNode<T>{std::move(sdf)}), b};
  }

  std::string file_, dir_;
  SceneInfo& info_;
  const MeshRegistry* meshes_ = nullptr;
  std::size_t triangles_ = 0;
  std::size_t depth_ = 0;
  static constexpr std::size_t max_depth = 200;
};

} // namespace internal

/// Compiles the scene `doc` (read from `file`, used in messages and to resolve relative mesh
/// paths) into the library's SDFs. Mesh nodes with `"ref": NAME` take the mesh registered under
/// NAME in `meshes` (mesh_registry.hpp; none when null). Throws ToolError (input) naming the
/// offending JSON pointer (an unknown reference too).
template <class T>
SceneSdf<T> compile_scene(const Json& doc, const std::string& file, SceneInfo* info = nullptr,
                          const MeshRegistry* meshes = nullptr) {
  SceneInfo si;
  internal::SceneCompiler<T> c(file, si, meshes);
  const Json* root = &doc;
  std::string ptr;
  if (doc.is_object() && doc.contains("root")) {
    for (auto it = doc.begin(); it != doc.end(); ++it)
      if (it.key() != "root" && it.key() != "version" && it.key() != "description" &&
          it.key() != "comment")
        c.bad("/" + it.key(), "unknown top-level key (expected root, version, description)");
    if (doc.contains("version") && doc["version"] != 1)
      c.bad("/version",
            "unsupported scene version " + internal::describe(doc["version"]) + " (expected 1)");
    root = &doc["root"];
    ptr = "/root";
  }
  internal::Built<T> b = c.node(*root, ptr);
  if (info) *info = si;
  return SceneSdf<T>(std::move(b.sdf), b.box, c.triangles());
}

/// Reads and compiles a scene file.
template <class T> SceneSdf<T> load_scene(const std::string& path, SceneInfo* info = nullptr) {
  return compile_scene<T>(read_json_file(path), path, info);
}

/// The SDF of `soup` (read from `path`, named in errors) with sign mode `sign`, as a scene of one
/// mesh (`SceneSdf::mesh`, `SceneSdf::visit`).
template <class T>
SceneSdf<T> mesh_scene(const PolygonSoup<T>& soup, const std::string& path, SignMode sign) {
  return SceneSdf<T>::of_mesh(
      std::make_shared<const SignedMeshSdf<T>>(build_mesh_sdf(soup, path, sign)), sign);
}

/// Reads the mesh file `path` (`load_mesh`) into a scene of one mesh (`mesh_scene`).
template <class T> SceneSdf<T> load_mesh_scene(const std::string& path, SignMode sign) {
  return mesh_scene<T>(load_mesh<T>(path), path, sign);
}

} // namespace ebgeom::scene

// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// In-memory meshes in scenes (`MeshRegistry`, `{"type": "mesh", "ref": NAME}`): a scene naming a
// registered mesh gives the values of the same scene naming the same mesh written to a file (a
// binary PLY, which keeps double coordinates) bit for bit, in float and double, alone and inside
// CSG, with the node's own sign mode; the mesh is shared, not copied; unknown references, a
// missing registry and malformed nodes are refused naming the JSON pointer.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/io/write_mesh.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/scene/mesh_registry.hpp"
#include "ebgeom/scene/scene.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"

using namespace ebgeom;

namespace {

/// A closed icosphere, moved off the origin, and an open cap of it (faces above z = 0.5 removed).
struct Meshes {
  std::shared_ptr<PolygonSoup<double>> closed = std::make_shared<PolygonSoup<double>>();
  std::shared_ptr<PolygonSoup<double>> open = std::make_shared<PolygonSoup<double>>();
  std::string closed_path, open_path;
};

const Meshes& meshes() {
  static const Meshes m = [] {
    Meshes r;
    *r.closed = *make_icosphere<double>(2, 0.8);
    for (auto& v : r.closed->vertices) v = v + Vec3<double>{0.31, -0.07, 0.013};
    r.open->vertices = r.closed->vertices;
    for (std::size_t f = 0; f < r.closed->face_count(); ++f) {
      const auto c = r.closed->face(f);
      bool high = true;
      for (Index i : c) high = high && r.closed->vertices[i].z > 0.5;
      if (high) continue;
      r.open->add_face(c);
    }
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("ebgeom-mesh-registry-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    r.closed_path = (dir / "closed.ply").string();
    r.open_path = (dir / "open.ply").string();
    EXPECT_TRUE(io::write_mesh(r.closed_path, *r.closed));
    EXPECT_TRUE(io::write_mesh(r.open_path, *r.open));
    return r;
  }();
  return m;
}

scene::MeshRegistry registry() {
  scene::MeshRegistry reg;
  reg.add("ball", meshes().closed);
  reg.add("cap", meshes().open);
  return reg;
}

std::vector<Vec3<double>> points() {
  std::vector<Vec3<double>> p;
  for (int k = 0; k < 11; ++k)
    for (int j = 0; j < 11; ++j)
      for (int i = 0; i < 11; ++i)
        p.push_back({-1.6 + 0.31 * i + 0.003, -1.5 + 0.29 * j - 0.011, -1.4 + 0.27 * k + 0.007});
  return p;
}

/// `json` with "@BALL" and "@CAP" replaced by `ball` and `cap`.
std::string with(std::string json, const std::string& ball, const std::string& cap) {
  for (auto [key, value] : {std::pair<std::string, std::string>{"@BALL", ball}, {"@CAP", cap}})
    for (std::size_t at; (at = json.find(key)) != std::string::npos;)
      json.replace(at, key.size(), value);
  return json;
}

/// The scene `json` with its meshes named by file and by reference: equal values, bit for bit.
template <class T> void expect_file_equals_ref(const std::string& json) {
  const std::string by_file = with(json, "\"path\": \"" + meshes().closed_path + "\"",
                                   "\"path\": \"" + meshes().open_path + "\"");
  const std::string by_ref = with(json, "\"ref\": \"ball\"", "\"ref\": \"cap\"");
  const scene::MeshRegistry reg = registry();
  scene::SceneInfo fi, ri;
  const auto f = scene::compile_scene<T>(scene::parse_json_text(by_file, "f.json"), "f.json", &fi);
  const auto r =
      scene::compile_scene<T>(scene::parse_json_text(by_ref, "r.json"), "r.json", &ri, &reg);
  EXPECT_EQ(r.triangle_count(), f.triangle_count());
  EXPECT_EQ(r.bounds().lo, f.bounds().lo);
  EXPECT_EQ(r.bounds().hi, f.bounds().hi);
  ASSERT_EQ(ri.mesh_signs.size(), fi.mesh_signs.size());
  for (std::size_t i = 0; i < ri.mesh_signs.size(); ++i) {
    EXPECT_EQ(ri.mesh_signs[i].used, fi.mesh_signs[i].used);
    EXPECT_EQ(ri.mesh_signs[i].source.rfind("ref: ", 0), 0u) << ri.mesh_signs[i].source;
  }
  std::vector<Vec3<T>> p;
  for (const auto& q : points()) p.push_back(Vec3<T>::from(q));
  std::vector<T> vf(p.size()), vr(p.size());
  ASSERT_TRUE(evaluate(f, Span<const Vec3<T>>(p), Span<T>(vf)));
  ASSERT_TRUE(evaluate(r, Span<const Vec3<T>>(p), Span<T>(vr)));
  for (std::size_t i = 0; i < p.size(); ++i) {
    ASSERT_EQ(vr[i], vf[i]) << by_ref << " at " << p[i];
    ASSERT_EQ(r(p[i]), vf[i]) << "single point at " << p[i];
  }
}

const char* scenes[] = {
    R"({"type": "mesh", @BALL})",
    R"({"type": "union", "children": [{"type": "mesh", @BALL},
        {"type": "sphere", "center": [-0.4, 0, 0], "radius": 0.5}]})",
    R"({"type": "difference", "smooth": 0.05, "children": [
        {"type": "box", "half_size": [1, 1, 1]}, {"type": "mesh", @BALL, "sign": "pseudonormal"}]})",
    R"({"type": "intersection", "children": [{"type": "mesh", @CAP, "sign": "winding"},
        {"type": "mesh", @BALL, "translate": [0.2, 0, 0], "scale": 0.9}]})",
    R"({"type": "union", "accelerate": true, "children": [{"type": "mesh", @CAP},
        {"type": "mesh", @BALL, "translate": [2, 0, 0]}]})",
};

} // namespace

TEST(MeshRegistry, ReferencedMeshEqualsTheSameMeshFromAFile) {
  for (const char* s : scenes) {
    expect_file_equals_ref<double>(s);
    expect_file_equals_ref<float>(s);
  }
}

TEST(MeshRegistry, ReferencedMeshEqualsTheLibrarysSignedMeshSdf) {
  const scene::MeshRegistry reg = registry();
  for (const char* sign : {"pseudonormal", "winding", "unsigned"}) {
    const std::string json =
        std::string(R"({"type": "mesh", "ref": "cap", "sign": ")") + sign + "\"}";
    const auto s = scene::compile_scene<double>(scene::parse_json_text(json, "s.json"), "s.json",
                                                nullptr, &reg);
    SignOptions opt;
    opt.mode = *parse_sign_mode(sign);
    const auto ref = SignedMeshSdf<double>::build(*meshes().open, opt);
    ASSERT_TRUE(ref);
    for (const auto& p : points()) ASSERT_EQ(s(p), (*ref)(p)) << sign << " at " << p;
  }
}

TEST(MeshRegistry, SharesTheMeshWithoutCopyingOrKeepingIt) {
  auto soup = std::make_shared<const PolygonSoup<double>>(*make_cube<double>(1.0));
  scene::MeshRegistry reg;
  reg.add("cube", soup);
  EXPECT_EQ(reg.find("cube").get(), soup.get());
  EXPECT_EQ(reg.find("nothing"), nullptr);
  EXPECT_EQ(reg.names(), std::vector<std::string>{"cube"});
  {
    const auto s = scene::compile_scene<double>(
        scene::parse_json_text(R"({"type": "mesh", "ref": "cube"})", "s.json"), "s.json", nullptr,
        &reg);
    EXPECT_EQ(soup.use_count(), 2); // here and in the registry: the scene built its own SDF
    EXPECT_EQ(s({0, 0, 0}), -1.0);
    EXPECT_EQ(s({3, 0, 0}), 2.0);
  }
  EXPECT_THROW(reg.add("", soup), std::invalid_argument);
  EXPECT_THROW(reg.add("x", nullptr), std::invalid_argument);
}

TEST(MeshRegistry, BadReferencesNameTheNode) {
  const scene::MeshRegistry reg = registry();
  const scene::MeshRegistry none;
  auto error = [](const std::string& json, const scene::MeshRegistry* r) -> std::string {
    try {
      scene::compile_scene<double>(scene::parse_json_text(json, "s.json"), "s.json", nullptr, r);
    } catch (const scene::ToolError& e) {
      EXPECT_EQ(e.code, scene::exit_input);
      return e.what();
    }
    return "(no error)";
  };
  const std::string csg = R"({"type": "union", "children": [{"type": "sphere", "radius": 1},
      {"type": "mesh", "ref": "bal"}]})";
  std::string e = error(csg, &reg);
  EXPECT_NE(e.find("s.json: /children/1/ref: no in-memory mesh is registered as \"bal\" (2 "
                   "registered)"),
            std::string::npos)
      << e;
  for (const scene::MeshRegistry* r : {&none, static_cast<const scene::MeshRegistry*>(nullptr)}) {
    e = error(csg, r);
    EXPECT_NE(e.find("/children/1/ref: no in-memory mesh is registered as \"bal\" (none are"),
              std::string::npos)
        << e;
  }
  e = error(R"({"type": "mesh", "ref": 3})", &reg);
  EXPECT_NE(e.find("/ref: expected the name of an in-memory mesh"), std::string::npos) << e;
  e = error(R"({"type": "mesh", "ref": "ball", "generate": "icosphere"})", &reg);
  EXPECT_NE(e.find("a mesh needs exactly one of \"path\" (a mesh file), \"generate\" or \"ref\""),
            std::string::npos)
      << e;
  // a reference to a mesh whose coordinates float cannot hold fails in float only
  scene::MeshRegistry big;
  auto huge = std::make_shared<PolygonSoup<double>>(*make_cube<double>(1.0));
  for (auto& v : huge->vertices)
    v = v * 1e100; // fine in double (up to about 2e152), infinite in float
  big.add("huge", huge);
  const std::string json = R"({"type": "mesh", "ref": "huge"})";
  EXPECT_NO_THROW(scene::compile_scene<double>(scene::parse_json_text(json, "s.json"), "s.json",
                                               nullptr, &big));
  try {
    scene::compile_scene<float>(scene::parse_json_text(json, "s.json"), "s.json", nullptr, &big);
    ADD_FAILURE() << "a mesh beyond float compiled in float";
  } catch (const scene::ToolError& x) {
    EXPECT_NE(std::string(x.what()).find("in-memory mesh \"huge\": vertex 0"), std::string::npos)
        << x.what();
  }
}

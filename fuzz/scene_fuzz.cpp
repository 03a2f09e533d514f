// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// libFuzzer target for JSON scene files (docs/scene-format.md): parsing (depth limit, duplicate
// keys, numbers at the edges of float and double) and compiling into a program in float and
// double, then evaluating it at a few points. The only allowed failure is an input error
// (ToolError with exit status 3) on one short line; anything else aborts. Mesh "path" keys are
// removed before compiling so that no file is read; mesh "ref" keys resolve against a registry
// holding one small in-memory mesh named "m" (any other name is an input error).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/scene/mesh_registry.hpp"
#include "ebgeom/scene/scene.hpp"

namespace {

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz check failed: %s\n", what);
    std::abort();
  }
}

void check_input_error(const ebgeom::scene::ToolError& e) {
  check(e.code == ebgeom::scene::exit_input, "scene errors are input errors (exit 3)");
  const std::string w = e.what();
  check(!w.empty(), "an error has a message");
  check(w.find('\n') == std::string::npos, "an error is one line");
  check(w.size() < 600, "an error line is short");
}

/// Drops every "path" key and caps icosphere subdivisions at 3 (a fast run); the depth is at most
/// max_json_depth after parsing.
void drop_paths(ebgeom::scene::Json& j) {
  if (j.is_object()) {
    j.erase("path");
    if (auto s = j.find("subdivisions"); s != j.end() && s->is_number() && *s > 3) *s = 3;
    for (auto& v : j) drop_paths(v);
  } else if (j.is_array()) {
    for (auto& v : j) drop_paths(v);
  }
}

/// The meshes that scenes may name by "ref": "m", an icosphere of 80 triangles.
const ebgeom::scene::MeshRegistry& registry() {
  static const ebgeom::scene::MeshRegistry r = [] {
    ebgeom::scene::MeshRegistry m;
    m.add("m", std::make_shared<const ebgeom::PolygonSoup<double>>(
                   ebgeom::make_icosphere<double>(1).value()));
    return m;
  }();
  return r;
}

template <class T> void compile_and_eval(const ebgeom::scene::Json& doc) {
  using namespace ebgeom;
  try {
    const scene::SceneSdf<T> prog = scene::compile_scene<T>(doc, "fuzz.json", nullptr, &registry());
    const std::vector<Vec3<T>> pts = {{0, 0, 0}, {T(0.5), T(-1), T(2)}, {T(1e3), 0, 0}};
    std::vector<T> out(pts.size());
    prog.eval(Span<const Vec3<T>>(pts), Span<T>(out));
  } catch (const scene::ToolError& e) {
    check_input_error(e);
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ebgeom;
  if (size > (1u << 20)) return 0;
  const std::string text(reinterpret_cast<const char*>(data), size);
  scene::Json doc;
  try {
    doc = scene::parse_json_text(text, "fuzz.json");
  } catch (const scene::ToolError& e) {
    check_input_error(e);
    return 0;
  }
  drop_paths(doc);
  compile_and_eval<float>(doc);
  compile_and_eval<double>(doc);
  return 0;
}

// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// The `ebgeom._ebgeom` extension: meshes, mesh SDFs, compiled scenes and grids over NumPy arrays.
// The pure-Python package `ebgeom` (python/ebgeom) wraps it; see docs/python.md.
//
// The scene compiler, the grid rules, the mesh SDF and the .npz/.vdb writers are the command-line
// tool's own (the scene component ebgeom/scene/ and the jobs component ebgeom/jobs/), so a grid
// sampled here is the CLI's grid bit for bit, and a file written here is the CLI's file byte for
// byte.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/eval/grid.hpp"
#include "ebgeom/eval/sparse_grid.hpp"
#include "ebgeom/eval/write_grid.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/io/write_mesh.hpp"
#include "ebgeom/mesh/validate.hpp"
#include "ebgeom/version.hpp"

#include "ebgeom/jobs/mesh_report.hpp"
#include "ebgeom/jobs/npz.hpp"
#include "ebgeom/jobs/sdf_job.hpp"
#include "ebgeom/jobs/vdb_output.hpp"
#include "ebgeom/scene/error.hpp"
#include "ebgeom/scene/gltf.hpp"
#include "ebgeom/scene/mesh_input.hpp"
#include "ebgeom/scene/mesh_registry.hpp"
#include "ebgeom/scene/scene.hpp"
#include "ebgeom/scene/system.hpp"

namespace py = pybind11;
using namespace ebgeom;

namespace {

static_assert(sizeof(Vec3<float>) == 3 * sizeof(float), "Vec3<float> must be three packed floats");
static_assert(sizeof(Vec3<double>) == 3 * sizeof(double), "Vec3<double> must be packed");

// ---- exceptions -------------------------------------------------------------------------------

/// Python exception types, created in the module init (subclasses of ValueError / OSError).
PyObject* g_parse_error = nullptr; // ebgeom.MeshFormatError(ValueError)
PyObject* g_scene_error = nullptr; // ebgeom.SceneError(ValueError)

struct ParseFailure {
  ebgeom::ParseError e;
  std::string text; // the message; e.what() when empty
};

/// Raises the Python exception for a reader error: OSError for I/O, MeshFormatError otherwise
/// (with attributes path, line, byte, code).
[[noreturn]] void raise_parse_error(const ebgeom::ParseError& e) { throw ParseFailure{e, {}}; }

// ---- arrays -----------------------------------------------------------------------------------

template <class T> using CArr = py::array_t<T, py::array::c_style | py::array::forcecast>;

/// `points` as a contiguous (N, 3) array of T: the caller's own buffer when it already is one
/// (no copy), otherwise one converted copy. Raises ValueError for other shapes.
template <class T> CArr<T> as_points(const py::handle& points) {
  py::array arr = py::array::ensure(points);
  if (!arr) throw py::value_error("points: expected an array-like of shape (N, 3)");
  if (arr.ndim() == 1 && arr.shape(0) == 3) arr = arr.attr("reshape")(1, 3);
  if (arr.ndim() != 2 || arr.shape(1) != 3)
    throw py::value_error("points: expected shape (N, 3), got " +
                          std::string(py::str(py::tuple(py::cast(
                              std::vector<py::ssize_t>(arr.shape(), arr.shape() + arr.ndim()))))));
  if (arr.dtype().kind() != 'f' && arr.dtype().kind() != 'i' && arr.dtype().kind() != 'u')
    throw py::type_error("points: expected a float or integer array, got dtype " +
                         std::string(py::str(arr.dtype())));
  // No copy when already T and C order; one converting copy otherwise.
  auto r = CArr<T>::ensure(arr);
  if (!r) throw py::error_already_set();
  return r;
}

template <class T> Span<const Vec3<T>> point_span(const CArr<T>& a) {
  return {reinterpret_cast<const Vec3<T>*>(a.data()), std::size_t(a.shape(0))};
}

/// An output array: `out` when given (checked: dtype T, C-contiguous, `n` values, writeable),
/// else a new one.
template <class T>
py::array_t<T> output_array(const py::object& out, std::size_t n, std::vector<py::ssize_t> shape) {
  if (out.is_none()) return py::array_t<T>(shape);
  if (!py::isinstance<py::array_t<T>>(out) || !(py::array(out).flags() & py::array::c_style) ||
      std::size_t(py::array(out).size()) != n || !py::array(out).writeable())
    throw py::value_error(std::string("out: expected a writeable C-contiguous ") +
                          (sizeof(T) == 4 ? "float32" : "float64") + " array of " +
                          std::to_string(n) + " values");
  return out.cast<py::array_t<T>>();
}

ExecOptions exec_of(int threads) {
  if (threads < 0) throw py::value_error("threads: expected 0 (all cores) or a positive count");
  ExecOptions e;
  e.threads = threads;
  return e;
}

// ---- meshes -----------------------------------------------------------------------------------

/// A polygon mesh (double precision). Remembers the file it came from, so a float SDF reads the
/// file's numbers as float exactly as the CLI does.
struct Mesh {
  PolygonSoup<double> soup;
  std::string path; // empty when built from arrays

  PolygonSoup<float> soup_float() const {
    if (!path.empty() && !scene::is_gltf_path(path)) {
      auto s = io::read_mesh<float>(path);
      if (s) return std::move(*s);
    }
    PolygonSoup<float> f;
    f.vertices.reserve(soup.vertices.size());
    for (const auto& v : soup.vertices) f.vertices.push_back({float(v.x), float(v.y), float(v.z)});
    f.indices = soup.indices;
    f.offsets = soup.offsets;
    return f;
  }
  template <class T> PolygonSoup<T> soup_as() const {
    if constexpr (std::is_same_v<T, double>)
      return soup;
    else
      return soup_float();
  }
};

std::shared_ptr<Mesh> read_mesh_py(const std::string& path) {
  {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
      throw py::error_already_set(
          (PyErr_SetFromErrnoWithFilename(PyExc_FileNotFoundError, path.c_str()),
           py::error_already_set()));
  }
  std::optional<Result<PolygonSoup<double>, ebgeom::ParseError>> r;
  if (scene::is_gltf_path(path)) { // glTF 2.0 through tinygltf, as the CLI reads it
    std::string failed;
    {
      py::gil_scoped_release nogil;
      try {
        r.emplace(scene::read_gltf(path));
      } catch (const scene::ToolError& e) {
        failed = e.what();
      }
    }
    if (!failed.empty()) {
      ebgeom::ParseError e;
      e.code = scene::gltf_available() ? ErrorCode::syntax : ErrorCode::unsupported;
      e.path = path;
      throw ParseFailure{e, failed};
    }
  } else {
    py::gil_scoped_release nogil;
    r.emplace(io::read_mesh<double>(path));
  }
  if (!*r) raise_parse_error(r->error());
  auto m = std::make_shared<Mesh>();
  m->soup = std::move(**r);
  m->path = path;
  return m;
}

/// A mesh from (V, 3) vertices and (F, K) faces or a list of index lists. ValueError with the
/// offending row for NaN/inf vertices, negative or out-of-range indices and wrong shapes.
std::shared_ptr<Mesh> mesh_from_arrays(const py::handle& vertices, const py::handle& faces) {
  auto m = std::make_shared<Mesh>();
  py::array varr = py::array::ensure(vertices);
  if (!varr || varr.ndim() != 2 || varr.shape(1) != 3)
    throw py::value_error("vertices: expected an array of shape (V, 3)");
  if (varr.dtype().kind() != 'f' && varr.dtype().kind() != 'i' && varr.dtype().kind() != 'u')
    throw py::type_error("vertices: expected a float or integer array, got dtype " +
                         std::string(py::str(varr.dtype())));
  auto v = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(varr);
  if (!v) throw py::error_already_set();
  const std::size_t nv = std::size_t(v.shape(0));
  m->soup.vertices.resize(nv);
  const double* vp = v.data();
  for (std::size_t i = 0; i < nv; ++i) {
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(vp[3 * i + a]))
        throw py::value_error("vertices: row " + std::to_string(i) +
                              " is not finite (NaN or infinity)");
    m->soup.vertices[i] = {vp[3 * i], vp[3 * i + 1], vp[3 * i + 2]};
  }
  auto add_face = [&](const std::vector<long long>& f, std::size_t row) {
    if (f.size() < 3)
      throw py::value_error("faces: row " + std::to_string(row) + " has " +
                            std::to_string(f.size()) + " corners; expected at least 3");
    for (long long c : f)
      if (c < 0 || std::uint64_t(c) >= nv)
        throw py::value_error("faces: row " + std::to_string(row) + " has index " +
                              std::to_string(c) + "; expected 0 to " +
                              std::to_string(long(nv) - 1));
    for (long long c : f) m->soup.indices.push_back(Index(c));
    m->soup.offsets.push_back(Index(m->soup.indices.size()));
  };
  py::array farr = py::array::ensure(faces);
  if (farr && farr.ndim() == 2 && farr.dtype().kind() != 'O') {
    if (farr.dtype().kind() != 'i' && farr.dtype().kind() != 'u')
      throw py::type_error("faces: expected an integer array, got dtype " +
                           std::string(py::str(farr.dtype())));
    auto f = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(farr);
    if (!f) throw py::error_already_set();
    const std::size_t nf = std::size_t(f.shape(0)), k = std::size_t(f.shape(1));
    std::vector<long long> row(k);
    for (std::size_t i = 0; i < nf; ++i) {
      for (std::size_t c = 0; c < k; ++c) row[c] = f.data()[i * k + c];
      add_face(row, i);
    }
  } else {
    std::size_t i = 0;
    for (const py::handle& face : faces) {
      std::vector<long long> row;
      for (const py::handle& c : face) row.push_back(c.cast<long long>());
      add_face(row, i++);
    }
  }
  if (m->soup.face_count() == 0) throw py::value_error("faces: the mesh has no faces");
  return m;
}

py::dict mesh_info(const Mesh& m) {
  ValidationReport<double> r;
  {
    py::gil_scoped_release nogil;
    r = validate(m.soup);
  }
  // The fields of `ebgeom info --json`, built by the same function.
  nlohmann::json j;
  if (!m.path.empty()) j["input"] = m.path;
  j.update(jobs::mesh_report_json(r, m.soup.triangle_count()));
  return py::module_::import("json").attr("loads")(j.dump()).cast<py::dict>();
}

// ---- SDF objects ------------------------------------------------------------------------------

/// What sample_grid needs of any SDF: a compiled scene (a mesh is a scene of one mesh, as in the
/// CLI), in float or double.
struct SdfBase {
  virtual ~SdfBase() = default;
  virtual bool is_double() const = 0;
};

template <class T> struct SdfImpl : SdfBase {
  scene::SceneSdf<T> prog;
  const SignedMeshSdf<T>* mesh = nullptr; // prog.mesh(): null for scenes
  bool is_double() const override { return std::is_same_v<T, double>; }
};

/// A float or double SDF (mesh or scene), the Python-visible handle.
struct Sdf {
  std::shared_ptr<SdfImpl<float>> f;
  std::shared_ptr<SdfImpl<double>> d;
  std::string label;

  bool is_double() const { return bool(d); }
  template <class T> SdfImpl<T>& impl() const {
    if constexpr (std::is_same_v<T, double>)
      return *d;
    else
      return *f;
  }
};

template <class T> void build_mesh_impl(Sdf& s, const Mesh& m, SignMode mode) {
  auto impl = std::make_shared<SdfImpl<T>>();
  const PolygonSoup<T> soup = m.soup_as<T>();
  SignOptions opt;
  opt.mode = mode;
  auto built = SignedMeshSdf<T>::build(soup, opt);
  if (!built) throw py::value_error((s.label.empty() ? "" : s.label + ": ") + built.error().what());
  impl->prog = scene::SceneSdf<T>::of_mesh(
      std::make_shared<const SignedMeshSdf<T>>(std::move(*built)), mode);
  impl->mesh = impl->prog.mesh();
  if constexpr (std::is_same_v<T, double>)
    s.d = impl;
  else
    s.f = impl;
}

SignMode parse_sign(const std::string& sign) {
  try {
    return scene::parse_sign_mode(sign, scene::exit_usage, "sign");
  } catch (const scene::ToolError& e) {
    throw py::value_error(e.what());
  }
}

bool parse_precision(const std::string& p) {
  if (p == "float" || p == "float32" || p == "single") return false;
  if (p == "double" || p == "float64") return true;
  throw py::value_error("precision: expected 'float' or 'double', got '" + p + "'");
}

Sdf make_mesh_sdf(const Mesh& m, const std::string& sign, const std::string& precision) {
  const SignMode mode = parse_sign(sign);
  const bool dbl = parse_precision(precision);
  Sdf s;
  s.label = m.path;
  py::gil_scoped_release nogil;
  if (dbl)
    build_mesh_impl<double>(s, m, mode);
  else
    build_mesh_impl<float>(s, m, mode);
  return s;
}

/// Compiles a scene given as JSON text; `file` names it in errors and anchors relative mesh paths.
/// Mesh nodes with "ref": NAME take `meshes[NAME]` as it is in memory (scene::MeshRegistry: shared,
/// no copy, no file): in double its vertices, in float each rounded to float, as `soup_float` does
/// for a mesh built from arrays, so the node's values are MeshSdf(mesh)'s.
Sdf make_scene(const std::string& json_text, const std::string& file, const std::string& precision,
               bool from_file, const std::map<std::string, std::shared_ptr<Mesh>>& meshes) {
  const bool dbl = parse_precision(precision);
  scene::MeshRegistry registry;
  for (const auto& [name, mesh] : meshes) {
    if (!mesh) throw py::type_error("meshes: expected ebgeom.Mesh values");
    // shares the Mesh object: the registry's pointer keeps it alive while the scene compiles
    registry.add(name, std::shared_ptr<const PolygonSoup<double>>(mesh, &mesh->soup));
  }
  Sdf s;
  s.label = file;
  py::gil_scoped_release nogil;
  try {
    const scene::Json doc = from_file ? scene::read_json_file(file)
                                      : scene::Json::parse(json_text, nullptr, true, true);
    if (dbl) {
      s.d = std::make_shared<SdfImpl<double>>();
      s.d->prog = scene::compile_scene<double>(doc, file, nullptr, &registry);
    } else {
      s.f = std::make_shared<SdfImpl<float>>();
      s.f->prog = scene::compile_scene<float>(doc, file, nullptr, &registry);
    }
  } catch (const scene::Json::exception& e) {
    py::gil_scoped_acquire gil;
    PyErr_SetString(g_scene_error, (file + ": invalid JSON: " + e.what()).c_str());
    throw py::error_already_set();
  } catch (const scene::ToolError& e) {
    py::gil_scoped_acquire gil;
    PyErr_SetString(g_scene_error, e.what());
    throw py::error_already_set();
  }
  return s;
}

template <class T>
py::array eval_as(const Sdf& s, const py::handle& points, int threads, const py::object& out) {
  const auto pts = as_points<T>(points);
  const std::size_t n = std::size_t(pts.shape(0));
  auto res = output_array<T>(out, n, {py::ssize_t(n)});
  const ExecOptions ex = exec_of(threads);
  const SdfImpl<T>& impl = s.impl<T>();
  T* o = res.mutable_data();
  {
    py::gil_scoped_release nogil;
    Result<Ok> ok = impl.mesh ? evaluate(*impl.mesh, point_span<T>(pts), Span<T>(o, n), ex)
                              : evaluate(impl.prog, point_span<T>(pts), Span<T>(o, n), ex);
    if (!ok) {
      py::gil_scoped_acquire gil;
      throw py::value_error(ok.error().what());
    }
  }
  return res;
}

py::array sdf_call(const Sdf& s, const py::handle& points, int threads, const py::object& out) {
  return s.is_double() ? eval_as<double>(s, points, threads, out)
                       : eval_as<float>(s, points, threads, out);
}

/// Closest points, normals (unit gradient of S), triangle ids and feature kinds of a mesh SDF, as
/// `ebgeom query` computes them.
template <class T> py::dict query_as(const Sdf& s, const py::handle& points, int threads) {
  const SdfImpl<T>& impl = s.impl<T>();
  if (!impl.mesh) throw py::value_error("query: closest points need a mesh SDF");
  const auto pts = as_points<T>(points);
  const std::size_t n = std::size_t(pts.shape(0));
  const py::ssize_t sn = py::ssize_t(n);
  py::array_t<T> dist(sn), cp({sn, py::ssize_t(3)}), nm({sn, py::ssize_t(3)});
  py::array_t<std::int64_t> tri(sn);
  py::array_t<std::uint8_t> feat(sn);
  T *d = dist.mutable_data(), *c = cp.mutable_data(), *nn = nm.mutable_data();
  std::int64_t* t = tri.mutable_data();
  std::uint8_t* f = feat.mutable_data();
  const Vec3<T>* p = reinterpret_cast<const Vec3<T>*>(pts.data());
  const auto& mesh = *impl.mesh;
  const ExecOptions ex = exec_of(threads);
  {
    py::gil_scoped_release nogil;
    const auto& sdf = mesh; // the CLI's query, plus the feature
    parallel_for(
        0, n, 256,
        [&](std::size_t b, std::size_t e) {
          for (std::size_t i = b; i < e; ++i) {
            const auto h = sdf.closest(p[i]);
            Vec3<T> dir = p[i] - h.point;
            const T len = norm(dir);
            dir = len > T(1e-12) * (T(1) + norm(p[i])) ? dir / len * (h.distance < 0 ? T(-1) : T(1))
                                                       : sdf.mesh().face_normals[h.triangle];
            d[i] = h.distance;
            for (int a = 0; a < 3; ++a) {
              c[3 * i + a] = h.point[a];
              nn[3 * i + a] = dir[a];
            }
            t[i] = std::int64_t(h.triangle);
            f[i] = std::uint8_t(h.feature);
          }
        },
        ex);
  }
  py::dict r;
  r["distance"] = dist;
  r["closest"] = cp;
  r["normal"] = nm;
  r["triangle"] = tri;
  r["feature"] = feat;
  return r;
}

py::dict sdf_query(const Sdf& s, const py::handle& points, int threads) {
  return s.is_double() ? query_as<double>(s, points, threads) : query_as<float>(s, points, threads);
}

py::dict sign_info(const Sdf& s) {
  py::dict r;
  auto fill = [&](const auto& impl) {
    if (!impl.mesh) {
      r["mode"] = py::none();
      r["reason"] = "a scene (each mesh in it has its own sign mode)";
      return;
    }
    r["requested"] = scene::sign_name(impl.prog.requested_sign());
    r["mode"] = scene::sign_name(impl.mesh->resolved_mode());
    r["reason"] = impl.mesh->reason();
  };
  if (s.is_double())
    fill(*s.d);
  else
    fill(*s.f);
  return r;
}

template <class T> py::tuple bounds_as(const Sdf& s) {
  const Aabb<T> b = s.impl<T>().prog.bounds();
  return py::make_tuple(py::make_tuple(double(b.lo.x), double(b.lo.y), double(b.lo.z)),
                        py::make_tuple(double(b.hi.x), double(b.hi.y), double(b.hi.z)));
}

template <class T> py::tuple mesh_arrays_as(const Sdf& s) {
  const SdfImpl<T>& impl = s.impl<T>();
  if (!impl.mesh) throw py::value_error("triangles: need a mesh SDF");
  const TriangleMesh<T>& m = impl.mesh->mesh();
  py::array_t<T> v({py::ssize_t(m.vertices.size()), py::ssize_t(3)});
  py::array_t<std::int64_t> t({py::ssize_t(m.triangles.size()), py::ssize_t(3)});
  for (std::size_t i = 0; i < m.vertices.size(); ++i)
    for (int a = 0; a < 3; ++a) v.mutable_data()[3 * i + a] = m.vertices[i][a];
  for (std::size_t i = 0; i < m.triangles.size(); ++i)
    for (int a = 0; a < 3; ++a) t.mutable_data()[3 * i + a] = std::int64_t(m.triangles[i][a]);
  return py::make_tuple(v, t);
}

// ---- grids ------------------------------------------------------------------------------------

/// The grid options of `sample_grid`, as the CLI's `--box/--res/--dx/--pad/--band/--nodes`.
struct GridArgs {
  std::vector<double> box;
  std::vector<std::size_t> res;
  double dx = 0, pad = 0.1, band = 0;
  bool nodes = false;
  int threads = 0;
};

GridArgs grid_args(const std::vector<double>& box, const std::vector<std::size_t>& res, double dx,
                   double pad, double band, bool nodes, int threads) {
  if (!box.empty() && box.size() != 6)
    throw py::value_error("box: expected 6 numbers (x0, y0, z0, x1, y1, z1)");
  if (!res.empty() && res.size() != 1 && res.size() != 3)
    throw py::value_error("res: expected N or (NX, NY, NZ)");
  for (std::size_t n : res)
    if (n < 1 || n > (std::size_t(1) << 21))
      throw py::value_error("res: each resolution must be in 1..2097152");
  if (!(dx >= 0) || !std::isfinite(dx)) throw py::value_error("dx: expected a positive number");
  if (dx > 0 && !res.empty()) throw py::value_error("give res or dx, not both");
  if (!(pad >= 0 && pad <= 100)) throw py::value_error("pad: expected 0 to 100");
  if (!(band >= 0) || !std::isfinite(band)) throw py::value_error("band: expected a number >= 0");
  exec_of(threads);
  return {box, res, dx, pad, band, nodes, threads};
}

/// The grid the CLI's options would sample (`make_spec`), its messages in Python's words.
template <class T> GridSpec<T> spec_of(const Sdf& s, const GridArgs& a) {
  jobs::SdfOptions o;
  o.input = s.label.empty() ? std::string("the SDF") : s.label;
  o.box = a.box;
  o.res = a.res;
  o.dx = a.dx;
  o.pad = a.pad;
  o.band = a.band;
  o.nodes = a.nodes;
  try {
    return jobs::make_spec<T>(o, s.impl<T>().prog.bounds());
  } catch (const scene::ToolError& e) {
    std::string w = e.what();
    for (auto [from, to] : {std::pair<std::string, std::string>{"--box", "box"},
                            {"--dx", "dx"},
                            {"--res/--dx", "res/dx"},
                            {"give --box", "give box="}})
      for (std::size_t at = w.find(from); at != std::string::npos; at = w.find(from, at + 1))
        w.replace(at, from.size(), to);
    throw py::value_error(w);
  }
}

template <class T> std::string grid_name(const GridSpec<T>& spec) {
  return "a " + std::to_string(spec.nx()) + " x " + std::to_string(spec.ny()) + " x " +
         std::to_string(spec.nz()) + " grid of " + (sizeof(T) == 4 ? "float" : "double");
}

/// `count * each` bytes, saturated at the largest uint64 (grids up to 2^21 per axis overflow).
std::uint64_t bytes_of(std::uint64_t count, std::uint64_t each) {
  return count > std::numeric_limits<std::uint64_t>::max() / each
             ? std::numeric_limits<std::uint64_t>::max()
             : count * each;
}

/// Raises MemoryError when `bytes` exceed the memory available (when it is known).
void require_memory(std::uint64_t bytes, const std::string& what, const std::string& hint) {
  const std::uint64_t avail = scene::available_memory_bytes();
  if (avail != 0 && bytes > avail) {
    PyErr_SetString(PyExc_MemoryError, (what + " needs " + scene::human_bytes(bytes) + " but " +
                                        scene::human_bytes(avail) + " are available; " + hint)
                                           .c_str());
    throw py::error_already_set();
  }
}

/// The geometry of a sampled grid: origin, spacing, box, dims, centering, band (length units).
template <class T> py::dict geometry_of(const GridSpec<T>& spec, double band) {
  const Vec3<T> org = spec.origin(), h = spec.spacing();
  py::dict r;
  r["origin"] = py::make_tuple(double(org.x), double(org.y), double(org.z));
  r["spacing"] = py::make_tuple(double(h.x), double(h.y), double(h.z));
  r["box"] = py::make_tuple(
      py::make_tuple(double(spec.box.lo.x), double(spec.box.lo.y), double(spec.box.lo.z)),
      py::make_tuple(double(spec.box.hi.x), double(spec.box.hi.y), double(spec.box.hi.z)));
  r["dims"] = py::make_tuple(spec.nx(), spec.ny(), spec.nz());
  r["centering"] = to_string(spec.centering);
  r["band"] = band;
  return r;
}

template <class T> GridOptions grid_options(const GridSpec<T>& spec, const GridArgs& a) {
  GridOptions gopt;
  gopt.exec = exec_of(a.threads);
  gopt.band = a.band * double(max_component(spec.spacing())); // as the CLI's --band
  return gopt;
}

/// The dense grid of `ebgeom sdf` with the same options: the geometry plus `values`.
template <class T> py::dict sample_grid_as(const Sdf& s, const GridArgs& a) {
  const GridSpec<T> spec = spec_of<T>(s, a);
  require_memory(bytes_of(spec.size(), sizeof(T)), grid_name(spec),
                 "lower res or raise dx, shrink the box, or sample only a narrow band as a "
                 "sparse grid (band=W, sparse=True)");
  py::array_t<T> values({py::ssize_t(spec.nz()), py::ssize_t(spec.ny()), py::ssize_t(spec.nx())});
  const GridOptions gopt = grid_options(spec, a);
  T* out = values.mutable_data();
  {
    py::gil_scoped_release nogil;
    auto ok = s.impl<T>().prog.visit(
        [&](const auto& sdf) { return sample_grid(sdf, spec, Span<T>(out, spec.size()), gopt); });
    if (!ok) {
      py::gil_scoped_acquire gil;
      throw py::value_error(ok.error().what());
    }
  }
  py::dict r = geometry_of(spec, gopt.band);
  r["values"] = values;
  return r;
}

py::dict sample_grid_py(const Sdf& s, const std::vector<double>& box,
                        const std::vector<std::size_t>& res, double dx, double pad, double band,
                        bool nodes, int threads) {
  const GridArgs a = grid_args(box, res, dx, pad, band, nodes, threads);
  return s.is_double() ? sample_grid_as<double>(s, a) : sample_grid_as<float>(s, a);
}

/// (NX, NY, NZ) and the bytes of the dense grid the options give, without sampling.
py::tuple grid_size_py(const Sdf& s, const std::vector<double>& box,
                       const std::vector<std::size_t>& res, double dx, double pad, bool nodes) {
  const GridArgs a = grid_args(box, res, dx, pad, 0, nodes, 0);
  auto size = [&](auto spec) {
    using T = typename decltype(spec)::scalar_type;
    return py::make_tuple(py::make_tuple(spec.nx(), spec.ny(), spec.nz()),
                          bytes_of(spec.size(), sizeof(T)));
  };
  return s.is_double() ? size(spec_of<double>(s, a)) : size(spec_of<float>(s, a));
}

// ---- sparse narrow-band grids -----------------------------------------------------------------

/// A sparse narrow band (`SparseGrid<T>`, float or double). Its arrays reach Python as read-only
/// views of the C++ vectors (no copy); the views keep this object alive.
struct Sparse {
  std::shared_ptr<SparseGrid<float>> f;
  std::shared_ptr<SparseGrid<double>> d;

  template <class Fn> decltype(auto) visit(Fn&& fn) const { return d ? fn(*d) : fn(*f); }
};

template <class T>
py::array view_of(const py::object& owner, const T* data, std::vector<py::ssize_t> shape) {
  py::array a(py::dtype::of<T>(), std::move(shape), data, owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

template <class T> py::dict sample_sparse_as(const Sdf& s, const GridArgs& a) {
  if (!(a.band > 0))
    throw py::value_error("a sparse grid holds a narrow band: give band=W (W > 0 samples)");
  const GridSpec<T> spec = spec_of<T>(s, a);
  const GridOptions gopt = grid_options(spec, a);
  const SdfImpl<T>& impl = s.impl<T>();
  // Before sampling only the tile table is known, unless the SDF is implicit (a winding sign):
  // then no tile can be skipped and every one is kept (as `ebgeom sdf -o OUT.npz --band W`).
  std::uint64_t tiles = 1;
  for (std::size_t n : spec.dims) tiles *= (n + grid_tile - 1) / grid_tile;
  // (A mesh with a winding sign is sampled through its own SDF, which signs far tiles by proof and
  // skips them as an exact SDF does.)
  if (kind_of(impl.prog) == SdfKind::implicit && !impl.mesh)
    require_memory(
        bytes_of(tiles, sizeof(std::int32_t) + 12 + grid_tile * grid_tile * grid_tile * sizeof(T)),
        "a band of " + grid_name(spec) + " of an implicit SDF (it keeps every tile)",
        "only the sign of this scene is meaningful, so no tile far from the surface can be "
        "skipped: give its meshes sign=\"pseudonormal\", or lower res");
  else
    require_memory(bytes_of(tiles, sizeof(std::int32_t)), "the tile table of " + grid_name(spec),
                   "lower res or raise dx, or shrink the box");
  auto g = std::make_shared<SparseGrid<T>>();
  {
    py::gil_scoped_release nogil;
    Result<SparseGrid<T>> r = make_error(ErrorCode::invalid_argument, "not sampled");
    try {
      r = impl.prog.visit([&](const auto& sdf) { return sample_grid_sparse(sdf, spec, gopt); });
    } catch (const std::bad_alloc&) {
      py::gil_scoped_acquire gil;
      PyErr_SetString(PyExc_MemoryError,
                      ("the tiles of the narrow band of " + grid_name(spec) +
                       " do not fit in memory (" +
                       scene::human_bytes(scene::available_memory_bytes()) +
                       " available); lower res, narrow the band or shrink the box")
                          .c_str());
      throw py::error_already_set();
    }
    if (!r) {
      py::gil_scoped_acquire gil;
      throw py::value_error(r.error().what());
    }
    *g = std::move(*r);
  }
  Sparse sp;
  if constexpr (std::is_same_v<T, double>)
    sp.d = g;
  else
    sp.f = g;
  py::dict r = geometry_of(spec, double(g->band)); // the fill value, in T (the .npz's `band`)
  r["grid"] = py::cast(std::move(sp));
  return r;
}

py::dict sample_sparse_py(const Sdf& s, const std::vector<double>& box,
                          const std::vector<std::size_t>& res, double dx, double pad, double band,
                          bool nodes, int threads) {
  const GridArgs a = grid_args(box, res, dx, pad, band, nodes, threads);
  return s.is_double() ? sample_sparse_as<double>(s, a) : sample_sparse_as<float>(s, a);
}

/// The dense (NZ, NY, NX) array of a sparse grid: kept tiles' values, ±band in skipped tiles
/// (what the dense `sample_grid` with the same band gives).
template <class T> py::array to_dense_as(const SparseGrid<T>& g) {
  const GridSpec<T>& spec = g.spec;
  require_memory(bytes_of(spec.size(), sizeof(T)), grid_name(spec),
                 "a dense copy of this band does not fit; read the kept tiles (tiles, values) "
                 "instead");
  py::array_t<T> out({py::ssize_t(spec.nz()), py::ssize_t(spec.ny()), py::ssize_t(spec.nx())});
  T* o = out.mutable_data();
  const std::size_t W = grid_tile, nx = spec.nx(), ny = spec.ny(), nz = spec.nz();
  py::gil_scoped_release nogil;
  for (std::size_t tz = 0; tz < g.tiles[2]; ++tz)
    for (std::size_t ty = 0; ty < g.tiles[1]; ++ty)
      for (std::size_t tx = 0; tx < g.tiles[0]; ++tx) {
        const std::int32_t c = g.tile_code[tx + g.tiles[0] * (ty + g.tiles[1] * tz)];
        const T fill = c == SparseGrid<T>::inside ? -g.band : g.band;
        const T* v = c >= 0 ? g.values.data() + std::size_t(c) * W * W * W : nullptr;
        for (std::size_t z = 0; z < W && tz * W + z < nz; ++z)
          for (std::size_t y = 0; y < W && ty * W + y < ny; ++y) {
            T* row = o + tx * W + nx * (ty * W + y + ny * (tz * W + z));
            const std::size_t n = std::min(W, nx - tx * W);
            for (std::size_t x = 0; x < n; ++x) row[x] = v ? v[x + W * (y + W * z)] : fill;
          }
      }
  return std::move(out);
}

/// Writes a sparse grid as `ebgeom sdf -o OUT.npz --band W` (or OUT.vdb) does.
void save_sparse_py(const Sparse& s, const std::string& path) {
  const bool vdb = jobs::is_vdb_path(path);
  if (!jobs::is_npz_path(path) && !vdb)
    throw py::value_error(path + ": a sparse grid is saved as .npz (the narrow band's tiles) or "
                                 ".vdb (an OpenVDB level set); for .vti, .npy or .raw save "
                                 "to_dense()");
  if (vdb && !jobs::vdb_available())
    throw py::value_error(
        path + ": this ebgeom package was built without OpenVDB; install it (Debian: "
               "libopenvdb-dev libboost-iostreams-dev) and reinstall with "
               "EBGEOM_CMAKE_ARGS=-DEBGEOM_BUILD_CLI=ON, save the band as .npz, or write the level "
               "set with the command-line tool (ebgeom sdf INPUT -o OUT.vdb --band W)");
  Result<std::uint64_t> ok = std::uint64_t(0);
  {
    py::gil_scoped_release nogil;
    ok = s.visit([&](const auto& g) {
      return vdb ? jobs::write_vdb(path, g) : jobs::write_sparse_npz(path, g);
    });
  }
  if (!ok) {
    PyErr_SetString(ok.error().code == ErrorCode::io ? PyExc_OSError : PyExc_ValueError,
                    ok.error().what().c_str());
    throw py::error_already_set();
  }
}

/// Writes a (NZ, NY, NX) grid with the CLI's writers (.vti, .npy, .raw + .json, dense .npz).
template <class T>
void save_grid_as(const std::string& path, const CArr<T>& v, const std::vector<double>& box,
                  const std::string& centering) {
  GridSpec<T> spec;
  spec.dims = {{std::size_t(v.shape(2)), std::size_t(v.shape(1)), std::size_t(v.shape(0))}};
  spec.box = Aabb<T>({T(box[0]), T(box[1]), T(box[2])}, {T(box[3]), T(box[4]), T(box[5])});
  spec.centering = centering == "node" ? Centering::node : Centering::cell;
  WriteGridOptions w;
  w.dtype = sizeof(T) == 4 ? DType::float32 : DType::float64;
  Result<Ok> ok = Ok{};
  {
    py::gil_scoped_release nogil;
    const Span<const T> values(v.data(), spec.size());
    if (jobs::is_npz_path(path)) {
      auto written = jobs::write_dense_npz(path, spec, values);
      if (!written) ok = written.error();
    } else {
      ok = write_grid(path, spec, values, w);
    }
  }
  if (!ok) {
    if (ok.error().code == ErrorCode::io) {
      PyErr_SetString(PyExc_OSError, ok.error().what().c_str());
      throw py::error_already_set();
    }
    throw py::value_error(ok.error().what());
  }
}

void save_grid_py(const std::string& path, const py::array& values, const std::vector<double>& box,
                  const std::string& centering) {
  if (values.ndim() != 3) throw py::value_error("values: expected a (NZ, NY, NX) array");
  if (box.size() != 6) throw py::value_error("box: expected 6 numbers");
  if (values.dtype().is(py::dtype::of<double>()))
    save_grid_as<double>(
        path, py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(values), box,
        centering);
  else
    save_grid_as<float>(
        path, py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(values), box,
        centering);
}

/// Seconds one C++ `evaluate` call takes on `points` (already contiguous in the SDF's dtype) into
/// a preallocated buffer: the C++ side of bench/python_bench.py, timed in the same process.
template <class T> double time_eval_as(const Sdf& s, const py::handle& points, int threads) {
  const auto pts = as_points<T>(points);
  const std::size_t n = std::size_t(pts.shape(0));
  std::vector<T> out(n);
  const ExecOptions ex = exec_of(threads);
  const SdfImpl<T>& impl = s.impl<T>();
  py::gil_scoped_release nogil;
  const double t0 = scene::now_s();
  auto ok = impl.mesh ? evaluate(*impl.mesh, point_span<T>(pts), Span<T>(out), ex)
                      : evaluate(impl.prog, point_span<T>(pts), Span<T>(out), ex);
  const double t1 = scene::now_s();
  (void)ok;
  return t1 - t0;
}

} // namespace

PYBIND11_MODULE(_ebgeom, m) {
  m.doc() = "ebgeom's C++ core (use the `ebgeom` package, which wraps it)";
  m.attr("__version__") = EBGEOM_VERSION_STRING;

  py::object value_error = py::reinterpret_borrow<py::object>(PyExc_ValueError);
  g_parse_error = PyErr_NewExceptionWithDoc(
      "ebgeom.MeshFormatError",
      "A mesh file is malformed. Attributes: path, line (0 when unknown), byte, code.",
      PyExc_ValueError, nullptr);
  g_scene_error = PyErr_NewExceptionWithDoc(
      "ebgeom.SceneError",
      "A scene is malformed; the message names the file and the JSON pointer of the bad value.",
      PyExc_ValueError, nullptr);
  m.attr("MeshFormatError") = py::handle(g_parse_error);
  m.attr("SceneError") = py::handle(g_scene_error);

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const scene::ToolError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });

  py::class_<Mesh, std::shared_ptr<Mesh>>(m, "Mesh")
      .def(py::init(&mesh_from_arrays), py::arg("vertices"), py::arg("faces"))
      .def_property_readonly(
          "path", [](const Mesh& s) { return s.path; },
          "The file the mesh was read from; empty for a mesh built from arrays.")
      .def_property_readonly(
          "vertex_count", [](const Mesh& s) { return s.soup.vertex_count(); },
          "Number of vertices (unused ones included).")
      .def_property_readonly(
          "face_count", [](const Mesh& s) { return s.soup.face_count(); },
          "Number of faces (polygons of 3 or more corners).")
      .def_property_readonly(
          "triangle_count", [](const Mesh& s) { return s.soup.triangle_count(); },
          "Number of triangles once each face is fan-triangulated (what the SDF uses).")
      .def_property_readonly(
          "vertices",
          [](const Mesh& s) {
            py::array_t<double> v({py::ssize_t(s.soup.vertices.size()), py::ssize_t(3)});
            std::memcpy(v.mutable_data(), s.soup.vertices.data(),
                        s.soup.vertices.size() * sizeof(Vec3<double>));
            return v;
          },
          "(V, 3) float64 vertex positions (a new array on each access).")
      .def_property_readonly(
          "indices",
          [](const Mesh& s) {
            py::array_t<std::int64_t> v(py::ssize_t(s.soup.indices.size()));
            for (std::size_t i = 0; i < s.soup.indices.size(); ++i)
              v.mutable_data()[i] = s.soup.indices[i];
            return v;
          },
          "int64 vertex indices of every face, one after the other (see "
          "offsets).")
      .def_property_readonly(
          "offsets",
          [](const Mesh& s) {
            py::array_t<std::int64_t> v(py::ssize_t(s.soup.offsets.size()));
            for (std::size_t i = 0; i < s.soup.offsets.size(); ++i)
              v.mutable_data()[i] = s.soup.offsets[i];
            return v;
          },
          "int64, face_count + 1 values: face f is "
          "indices[offsets[f]:offsets[f + 1]].")
      .def("info", &mesh_info,
           "The validation report as a dict with the fields of `ebgeom info --json`: vertices,\n"
           "faces, triangles, edges, boundary_edges, holes, non_manifold_edges,\n"
           "non_manifold_vertices, inconsistent_edges, degenerate_faces, duplicate_faces,\n"
           "isolated_vertices, bad_index_faces, short_faces, non_finite_vertices, watertight,\n"
           "consistently_oriented, outward, area, volume, bbox ({lo, hi} or None),\n"
           "sdf_well_defined, verdict, auto_sign ({mode, reason}); input (the file) when read\n"
           "from a file.")
      .def(
          "write",
          [](const Mesh& s, const std::filesystem::path& fpath, bool ascii) {
            const std::string path = fpath.string();
            io::WriteOptions w;
            w.encoding = ascii ? io::Encoding::ascii : io::Encoding::binary;
            auto ok = io::write_mesh(path, s.soup, w);
            if (!ok) {
              PyErr_SetString(ok.error().code == ErrorCode::io ? PyExc_OSError : PyExc_ValueError,
                              ok.error().what().c_str());
              throw py::error_already_set();
            }
          },
          py::arg("path"), py::arg("ascii") = false,
          "Writes the mesh; the format comes from the extension (.stl, .ply, .obj, .off, .vtk), "
          "binary\n"
          "unless ascii=True. OSError when the file cannot be written.");

  m.def(
      "read_mesh",
      [](const std::string& path) {
        try {
          return read_mesh_py(path);
        } catch (const ParseFailure& f) {
          const ebgeom::ParseError& e = f.e;
          PyObject* type = e.code == ErrorCode::io ? PyExc_OSError : g_parse_error;
          py::object exc = py::reinterpret_steal<py::object>(
              PyObject_CallFunction(type, "s", (f.text.empty() ? e.what() : f.text).c_str()));
          if (!exc) throw py::error_already_set();
          exc.attr("path") = e.path;
          exc.attr("line") = e.line;
          exc.attr("byte") = e.byte_offset;
          exc.attr("code") = to_string(e.code);
          PyErr_SetObject(type, exc.ptr());
          throw py::error_already_set();
        }
      },
      py::arg("path"));

  py::class_<Sdf>(m, "Sdf")
      .def_property_readonly("precision",
                             [](const Sdf& s) { return s.is_double() ? "double" : "float"; })
      .def_property_readonly(
          "is_mesh", [](const Sdf& s) { return s.is_double() ? bool(s.d->mesh) : bool(s.f->mesh); })
      .def_property_readonly("sign_info", &sign_info)
      .def_property_readonly("kind",
                             [](const Sdf& s) {
                               const SdfKind k =
                                   s.is_double() ? kind_of(s.d->prog) : kind_of(s.f->prog);
                               return std::string(k == SdfKind::exact   ? "exact"
                                                  : k == SdfKind::bound ? "bound"
                                                                        : "implicit");
                             })
      .def_property_readonly("triangle_count",
                             [](const Sdf& s) {
                               return s.is_double() ? s.d->prog.triangle_count()
                                                    : s.f->prog.triangle_count();
                             })
      .def("bounds",
           [](const Sdf& s) { return s.is_double() ? bounds_as<double>(s) : bounds_as<float>(s); })
      .def("triangle_mesh",
           [](const Sdf& s) {
             return s.is_double() ? mesh_arrays_as<double>(s) : mesh_arrays_as<float>(s);
           })
      .def("eval", &sdf_call, py::arg("points"), py::arg("threads") = 0,
           py::arg("out") = py::none())
      .def("query", &sdf_query, py::arg("points"), py::arg("threads") = 0);

  py::class_<Sparse>(m, "SparseGrid")
      .def_property_readonly("precision", [](const Sparse& s) { return s.d ? "double" : "float"; })
      .def_property_readonly(
          "tiles",
          [](const py::object& self) {
            return self.cast<const Sparse&>().visit([&](const auto& g) {
              return view_of(self, reinterpret_cast<const std::uint32_t*>(g.kept_tiles.data()),
                             {py::ssize_t(g.kept_tiles.size()), 3});
            });
          })
      .def_property_readonly(
          "values",
          [](const py::object& self) {
            return self.cast<const Sparse&>().visit([&](const auto& g) {
              const py::ssize_t W = grid_tile;
              return view_of(self, g.values.data(), {py::ssize_t(g.kept_tiles.size()), W, W, W});
            });
          })
      .def_property_readonly("tile_code",
                             [](const py::object& self) {
                               return self.cast<const Sparse&>().visit([&](const auto& g) {
                                 return view_of(self, g.tile_code.data(),
                                                {py::ssize_t(g.tiles[2]), py::ssize_t(g.tiles[1]),
                                                 py::ssize_t(g.tiles[0])});
                               });
                             })
      .def_property_readonly(
          "memory_bytes",
          [](const Sparse& s) { return s.visit([](const auto& g) { return g.memory_bytes(); }); })
      .def("to_dense",
           [](const Sparse& s) {
             return s.visit([](const auto& g) { return py::object(to_dense_as(g)); });
           })
      .def("save", &save_sparse_py, py::arg("path"));

  m.def(
      "_points_address",
      [](const Sdf& s, const py::handle& points) {
        return s.is_double() ? std::uintptr_t(as_points<double>(points).data())
                             : std::uintptr_t(as_points<float>(points).data());
      },
      py::arg("sdf"), py::arg("points"),
      "The address of the buffer a query reads `points` from (the tests check the no-copy "
      "promise with it).");
  m.def(
      "_time_cpp_eval",
      [](const Sdf& s, const py::handle& points, int threads) {
        return s.is_double() ? time_eval_as<double>(s, points, threads)
                             : time_eval_as<float>(s, points, threads);
      },
      py::arg("sdf"), py::arg("points"), py::arg("threads") = 0);
  m.def("mesh_sdf", &make_mesh_sdf, py::arg("mesh"), py::arg("sign") = "auto",
        py::arg("precision") = "float");
  m.def("compile_scene", &make_scene, py::arg("json"), py::arg("file"),
        py::arg("precision") = "float", py::arg("from_file") = false,
        py::arg("meshes") = std::map<std::string, std::shared_ptr<Mesh>>{});
  m.def("sample_grid", &sample_grid_py, py::arg("sdf"), py::arg("box"), py::arg("res"),
        py::arg("dx"), py::arg("pad"), py::arg("band"), py::arg("nodes"), py::arg("threads"));
  m.def("sample_sparse", &sample_sparse_py, py::arg("sdf"), py::arg("box"), py::arg("res"),
        py::arg("dx"), py::arg("pad"), py::arg("band"), py::arg("nodes"), py::arg("threads"));
  m.def("grid_size", &grid_size_py, py::arg("sdf"), py::arg("box"), py::arg("res"), py::arg("dx"),
        py::arg("pad"), py::arg("nodes"));
  m.def("available_memory", &scene::available_memory_bytes,
        "Bytes of memory available to this process (0 when unknown), as the CLI reads it.");
  m.def("vdb_available", &jobs::vdb_available, "True when this build writes OpenVDB files.");
  m.def("save_grid", &save_grid_py, py::arg("path"), py::arg("values"), py::arg("box"),
        py::arg("centering"));
  (void)value_error;
}

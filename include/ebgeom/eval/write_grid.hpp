// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Writers for dense grids (and plain arrays), dependency-free:
///  - `.vti`: VTK XML ImageData, one point-data array, binary appended raw data (opens in
///    ParaView; `Origin` is the first sample, so cell-centred grids contour correctly); a piece of
///    a grid (`write_vti_piece`) and the `.pvti` that assembles pieces (`write_pvti`);
///  - `.npy`: NumPy format 1.0, float32 or float64, shape `(nz, ny, nx)`, C order;
///  - `.raw` + `.json` sidecar: the bare values (x fastest) and a JSON file describing dims,
///    spacing, origin, box, dtype, byte order and centring.
/// Every writer is atomic: it writes to a temporary file beside the target and renames it on
/// success, so a failure never leaves a partial output behind.

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <locale>
#include <sstream>
#include <string>
#include <vector>

#include "ebgeom/core/error.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/eval/grid.hpp"

namespace ebgeom {

/// Element type written to a file.
enum class DType : std::uint8_t { float32, float64 };

inline const char* to_string(DType d) noexcept {
  return d == DType::float32 ? "float32" : "float64";
}
inline std::size_t dtype_size(DType d) noexcept { return d == DType::float32 ? 4 : 8; }

/// Options of the grid writers.
struct WriteGridOptions {
  DType dtype = DType::float32;
  /// Name of the data array (VTI array name, JSON sidecar "name").
  std::string name = "sdf";
};

/// File format of a grid, chosen from the output path's extension.
enum class GridFormat : std::uint8_t { vti, npy, raw };

/// The format for `path` by its (case-sensitive, lower-case) extension `.vti`, `.npy` or `.raw`.
/// Errors: `unsupported` for any other extension.
inline Result<GridFormat> grid_format_of(const std::string& path) {
  auto ends = [&](const char* ext) {
    const std::size_t n = std::strlen(ext);
    return path.size() > n && path.compare(path.size() - n, n, ext) == 0;
  };
  if (ends(".vti")) return GridFormat::vti;
  if (ends(".npy")) return GridFormat::npy;
  if (ends(".raw")) return GridFormat::raw;
  return make_error(ErrorCode::unsupported, path,
                    ": unknown output format; expected an extension .vti, .npy or .raw");
}

/// Path of the JSON sidecar of a `.raw` file: `out.raw` -> `out.json`.
inline std::string raw_sidecar_path(const std::string& raw_path) {
  const std::size_t dot = raw_path.rfind('.');
  const std::size_t slash = raw_path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return raw_path + ".json";
  return raw_path.substr(0, dot) + ".json";
}

namespace detail {

inline bool host_is_little_endian() noexcept {
  const std::uint16_t one = 1;
  unsigned char b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

/// A file written under a temporary name and renamed onto `path` by `commit()`. Destroying an
/// uncommitted one removes the temporary.
class AtomicFile {
 public:
  explicit AtomicFile(std::string path) : path_(std::move(path)), tmp_(path_ + ".ebgeom-tmp") {
    out_.open(tmp_, std::ios::binary | std::ios::trunc);
  }
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile() {
    if (!committed_) {
      if (out_.is_open()) out_.close();
      std::remove(tmp_.c_str());
    }
  }
  bool is_open() const { return out_.is_open(); }
  std::ofstream& stream() { return out_; }
  Error open_error() const {
    return make_error(ErrorCode::io, path_, ": cannot open for writing (", std::strerror(errno),
                      ")");
  }
  /// Flushes and closes the temporary; it is renamed by `commit()`.
  Result<Ok> close() {
    out_.flush();
    const bool good = out_.good();
    out_.close();
    if (!good || out_.fail())
      return make_error(ErrorCode::io, path_, ": write failed (disk full?)");
    return Ok{};
  }
  Result<Ok> commit() {
    if (std::rename(tmp_.c_str(), path_.c_str()) != 0)
      return make_error(ErrorCode::io, path_, ": cannot rename the temporary file onto it (",
                        std::strerror(errno), ")");
    committed_ = true;
    return Ok{};
  }

 private:
  std::string path_, tmp_;
  std::ofstream out_;
  bool committed_ = false;
};

/// Streams `values` converted to `dtype`, in chunks, in host byte order.
template <class T> void write_values(std::ostream& os, Span<const T> values, DType dtype) {
  constexpr std::size_t chunk = 1 << 14;
  if (dtype == DType::float32) {
    std::vector<float> buf(std::min(chunk, values.size()));
    for (std::size_t s = 0; s < values.size(); s += chunk) {
      const std::size_t n = std::min(chunk, values.size() - s);
      for (std::size_t i = 0; i < n; ++i) buf[i] = static_cast<float>(values[s + i]);
      os.write(reinterpret_cast<const char*>(buf.data()), std::streamsize(n * sizeof(float)));
    }
  } else {
    std::vector<double> buf(std::min(chunk, values.size()));
    for (std::size_t s = 0; s < values.size(); s += chunk) {
      const std::size_t n = std::min(chunk, values.size() - s);
      for (std::size_t i = 0; i < n; ++i) buf[i] = static_cast<double>(values[s + i]);
      os.write(reinterpret_cast<const char*>(buf.data()), std::streamsize(n * sizeof(double)));
    }
  }
}

inline std::ostringstream number_stream() {
  std::ostringstream os;
  os.imbue(std::locale::classic());
  os.precision(17);
  return os;
}

inline std::string json_escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    if (c == '"' || c == '\\') {
      r += '\\';
      r += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char b[8];
      std::snprintf(b, sizeof b, "\\u%04x", c);
      r += b;
    } else {
      r += c;
    }
  }
  return r;
}

inline std::string xml_escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    switch (c) {
    case '&':
      r += "&amp;";
      break;
    case '<':
      r += "&lt;";
      break;
    case '>':
      r += "&gt;";
      break;
    case '"':
      r += "&quot;";
      break;
    default:
      r += c;
    }
  }
  return r;
}

template <class T> Result<Ok> check_grid_values(const GridSpec<T>& spec, std::size_t count) {
  if (auto ok = spec.validate(); !ok) return ok;
  if (count != spec.size())
    return make_error(ErrorCode::invalid_argument, "grid has ", spec.size(), " samples but ", count,
                      " values were given");
  return Ok{};
}

} // namespace detail

/// NumPy type string of `dtype` in host byte order: `<f4`, `<f8` (`>` on big-endian hosts).
inline std::string npy_descr(DType dtype) {
  std::string d(1, detail::host_is_little_endian() ? '<' : '>');
  return d + (dtype == DType::float32 ? "f4" : "f8");
}

/// The NumPy format 1.0 header of a C-order array of type `descr` (e.g. `<f4`, `<u4`, `<U4`) and
/// `shape` (slowest first; empty for a 0-d array): magic, version, length and the dict, padded
/// with spaces and a newline so the data starts at a multiple of 64 bytes. The array's bytes
/// follow it directly.
inline std::string npy_header(const std::string& descr, const std::vector<std::size_t>& shape) {
  std::string dict = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': (";
  for (std::size_t i = 0; i < shape.size(); ++i) {
    dict += std::to_string(shape[i]);
    if (shape.size() == 1 || i + 1 < shape.size()) dict += ",";
    if (i + 1 < shape.size()) dict += " ";
  }
  dict += "), }";
  // magic (6) + version (2) + header length (2) + dict + padding + '\n', a multiple of 64.
  std::size_t total = 10 + dict.size() + 1;
  total = (total + 63) / 64 * 64;
  dict.append(total - 10 - dict.size() - 1, ' ');
  dict += '\n';
  const std::size_t hlen = dict.size();
  std::string head = "\x93NUMPY";
  head += char(1);
  head += char(0);
  head += char(hlen & 0xff);
  head += char((hlen >> 8) & 0xff);
  return head + dict;
}

/// Writes an N-dimensional array as a NumPy `.npy` file (format 1.0, C order, host byte order,
/// header padded to 64 bytes, `npy_header`). `shape` lists the dimensions, slowest first; their
/// product must equal `values.size()`. Atomic (temporary + rename). Errors: `invalid_argument`,
/// `io`.
template <class T>
Result<Ok> write_npy(const std::string& path, Span<const T> values,
                     const std::vector<std::size_t>& shape, DType dtype = DType::float32) {
  std::size_t count = 1;
  for (std::size_t d : shape) count *= d;
  if (count != values.size())
    return make_error(ErrorCode::invalid_argument, path, ": shape holds ", count, " elements but ",
                      values.size(), " values were given");
  const std::string head = npy_header(npy_descr(dtype), shape);
  detail::AtomicFile f(path);
  if (!f.is_open()) return f.open_error();
  auto& os = f.stream();
  os.write(head.data(), std::streamsize(head.size()));
  detail::write_values(os, values, dtype);
  if (auto ok = f.close(); !ok) return ok;
  return f.commit();
}

/// Writes a grid as `.npy` with shape `(nz, ny, nx)` (C order: x fastest, as in memory).
template <class T>
Result<Ok> write_npy(const std::string& path, const GridSpec<T>& spec, Span<const T> values,
                     const WriteGridOptions& opt = {}) {
  if (auto ok = detail::check_grid_values(spec, values.size()); !ok) return ok;
  return write_npy(path, values, {spec.nz(), spec.ny(), spec.nx()}, opt.dtype);
}

namespace detail {

/// VTK extent text of the samples `r`: `i0 i1 j0 j1 k0 k1`, inclusive.
inline std::string vtk_extent(const GridRange& r) {
  return std::to_string(r.lo[0]) + ' ' + std::to_string(r.hi[0] - 1) + ' ' +
         std::to_string(r.lo[1]) + ' ' + std::to_string(r.hi[1] - 1) + ' ' +
         std::to_string(r.lo[2]) + ' ' + std::to_string(r.hi[2] - 1);
}

/// The `<?xml?>` line and the `<VTKFile>` tag of a file of `type` (`ImageData`, `PImageData`),
/// then the type's element opened with `WholeExtent` `whole`, the attributes `extra` (with a
/// leading space, or empty) and `spec`'s origin and spacing.
template <class T>
void vtk_image_head(std::ostream& xml, const char* type, const GridSpec<T>& spec,
                    const GridRange& whole, const char* extra) {
  const Vec3<T> o = spec.origin(), h = spec.spacing();
  xml << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"" << type << "\" version=\"1.0\" byte_order=\""
      << (host_is_little_endian() ? "LittleEndian" : "BigEndian") << "\" header_type=\"UInt64\">\n"
      << "  <" << type << " WholeExtent=\"" << vtk_extent(whole) << '"' << extra << " Origin=\""
      << double(o.x) << ' ' << double(o.y) << ' ' << double(o.z) << "\" Spacing=\"" << double(h.x)
      << ' ' << double(h.y) << ' ' << double(h.z) << "\">\n";
}

inline const char* vtk_type(DType d) noexcept {
  return d == DType::float32 ? "Float32" : "Float64";
}

} // namespace detail

/// Writes VTK XML ImageData (`.vti`) holding the samples `piece` of `spec` (`values`, x fastest
/// within `piece`) under a `WholeExtent` of `whole`, which must contain `piece`: pass the same
/// range for a file that stands on its own, the grid's for a piece of a larger one. One point-data
/// array `opt.name`, raw binary appended data (UInt64 header). `Origin` is the grid's first sample
/// and `Spacing` the sample spacing, so a piece lands where it belongs. Atomic. Errors:
/// `invalid_argument`, `io`.
template <class T>
Result<Ok> write_vti_piece(const std::string& path, const GridSpec<T>& spec, const GridRange& whole,
                           const GridRange& piece, Span<const T> values,
                           const WriteGridOptions& opt = {}) {
  if (auto ok = whole.validate(spec); !ok) return ok;
  if (auto ok = piece.validate(spec); !ok) return ok;
  for (int a = 0; a < 3; ++a)
    if (piece.lo[a] < whole.lo[a] || piece.hi[a] > whole.hi[a])
      return make_error(ErrorCode::invalid_argument, path, ": the piece's extent ",
                        detail::vtk_extent(piece), " is not inside the whole extent ",
                        detail::vtk_extent(whole));
  if (values.size() != piece.size())
    return make_error(ErrorCode::invalid_argument, "the piece has ", piece.size(), " samples but ",
                      values.size(), " values were given");
  auto xml = detail::number_stream();
  detail::vtk_image_head(xml, "ImageData", spec, whole, "");
  xml << "    <Piece Extent=\"" << detail::vtk_extent(piece) << "\">\n"
      << "      <PointData Scalars=\"" << detail::xml_escape(opt.name) << "\">\n"
      << "        <DataArray type=\"" << detail::vtk_type(opt.dtype) << "\" Name=\""
      << detail::xml_escape(opt.name)
      << "\" NumberOfComponents=\"1\" format=\"appended\" offset=\"0\"/>\n"
      << "      </PointData>\n"
      << "      <CellData/>\n"
      << "    </Piece>\n"
      << "  </ImageData>\n"
      << "  <AppendedData encoding=\"raw\">\n   _";
  detail::AtomicFile f(path);
  if (!f.is_open()) return f.open_error();
  auto& os = f.stream();
  const std::string head = xml.str();
  os.write(head.data(), std::streamsize(head.size()));
  const std::uint64_t nbytes = std::uint64_t(values.size()) * dtype_size(opt.dtype);
  os.write(reinterpret_cast<const char*>(&nbytes), sizeof nbytes);
  detail::write_values(os, values, opt.dtype);
  const std::string tail = "\n  </AppendedData>\n</VTKFile>\n";
  os.write(tail.data(), std::streamsize(tail.size()));
  if (auto ok = f.close(); !ok) return ok;
  return f.commit();
}

/// Writes a grid as VTK XML ImageData (`.vti`): `write_vti_piece` of the whole grid.
template <class T>
Result<Ok> write_vti(const std::string& path, const GridSpec<T>& spec, Span<const T> values,
                     const WriteGridOptions& opt = {}) {
  if (auto ok = detail::check_grid_values(spec, values.size()); !ok) return ok;
  const GridRange all = GridRange::all(spec);
  return write_vti_piece(path, spec, all, all, values, opt);
}

/// One piece named by a `.pvti`: its samples and its file, relative to the `.pvti`'s folder.
struct PvtiPiece {
  GridRange extent;
  std::string source;
};

/// Writes the parallel VTK ImageData file (`.pvti`) of `spec` assembling `pieces` (each written
/// by `write_vti_piece`; VTK pieces must share their boundary samples, or ParaView shows gaps).
/// Ghost level 0, one point-data array `opt.name`. Atomic. Errors: `invalid_argument`, `io`.
template <class T>
Result<Ok> write_pvti(const std::string& path, const GridSpec<T>& spec,
                      const std::vector<PvtiPiece>& pieces, const WriteGridOptions& opt = {}) {
  if (auto ok = spec.validate(); !ok) return ok;
  for (const PvtiPiece& p : pieces)
    if (auto ok = p.extent.validate(spec); !ok) return ok;
  auto xml = detail::number_stream();
  detail::vtk_image_head(xml, "PImageData", spec, GridRange::all(spec), " GhostLevel=\"0\"");
  xml << "    <PPointData Scalars=\"" << detail::xml_escape(opt.name) << "\">\n"
      << "      <PDataArray type=\"" << detail::vtk_type(opt.dtype) << "\" Name=\""
      << detail::xml_escape(opt.name) << "\" NumberOfComponents=\"1\"/>\n"
      << "    </PPointData>\n";
  for (const PvtiPiece& p : pieces)
    xml << "    <Piece Extent=\"" << detail::vtk_extent(p.extent) << "\" Source=\""
        << detail::xml_escape(p.source) << "\"/>\n";
  xml << "  </PImageData>\n</VTKFile>\n";
  detail::AtomicFile f(path);
  if (!f.is_open()) return f.open_error();
  const std::string text = xml.str();
  f.stream().write(text.data(), std::streamsize(text.size()));
  if (auto ok = f.close(); !ok) return ok;
  return f.commit();
}

/// JSON text of the sidecar describing a raw grid file `raw_file_name` (see `write_raw`).
template <class T>
std::string raw_sidecar_json(const GridSpec<T>& spec, const std::string& raw_file_name,
                             const WriteGridOptions& opt = {}) {
  const Vec3<T> o = spec.origin(), h = spec.spacing();
  auto js = detail::number_stream();
  auto vec = [&](const Vec3<T>& v) {
    js << '[' << double(v.x) << ", " << double(v.y) << ", " << double(v.z) << ']';
  };
  js << "{\n  \"file\": \"" << detail::json_escape(raw_file_name) << "\",\n"
     << "  \"name\": \"" << detail::json_escape(opt.name) << "\",\n"
     << "  \"dtype\": \"" << to_string(opt.dtype) << "\",\n"
     << "  \"byte_order\": \"" << (detail::host_is_little_endian() ? "little" : "big") << "\",\n"
     << "  \"dims\": [" << spec.nx() << ", " << spec.ny() << ", " << spec.nz() << "],\n"
     << "  \"layout\": \"x fastest: value (i, j, k) at index i + nx * (j + ny * k); as a C-order "
        "array, shape [nz, ny, nx]\",\n"
     << "  \"centering\": \"" << to_string(spec.centering) << "\",\n"
     << "  \"origin\": ";
  vec(o);
  js << ",\n  \"spacing\": ";
  vec(h);
  js << ",\n  \"box\": {\"lo\": ";
  vec(spec.box.lo);
  js << ", \"hi\": ";
  vec(spec.box.hi);
  js << "},\n  \"sign_convention\": \"negative inside, positive outside\"\n}\n";
  return js.str();
}

/// Writes the bare values (x fastest, `opt.dtype`, host byte order) to `path` and a JSON sidecar
/// (`raw_sidecar_path(path)`) with dims, spacing, origin, box, dtype, byte order and centring.
/// Both files appear only if both were written. Errors: `invalid_argument`, `io`.
template <class T>
Result<Ok> write_raw(const std::string& path, const GridSpec<T>& spec, Span<const T> values,
                     const WriteGridOptions& opt = {}) {
  if (auto ok = detail::check_grid_values(spec, values.size()); !ok) return ok;
  const std::string side = raw_sidecar_path(path);
  const std::size_t slash = path.find_last_of('/');
  const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  detail::AtomicFile raw(path), json(side);
  if (!raw.is_open()) return raw.open_error();
  if (!json.is_open()) return json.open_error();
  detail::write_values(raw.stream(), values, opt.dtype);
  const std::string js = raw_sidecar_json(spec, base, opt);
  json.stream().write(js.data(), std::streamsize(js.size()));
  if (auto ok = raw.close(); !ok) return ok;
  if (auto ok = json.close(); !ok) return ok;
  if (auto ok = json.commit(); !ok) return ok;
  return raw.commit();
}

/// Writes a grid in the format given by the extension of `path` (`.vti`, `.npy`, `.raw`).
/// Errors: `unsupported` extension, `invalid_argument`, `io`.
template <class T>
Result<Ok> write_grid(const std::string& path, const GridSpec<T>& spec, Span<const T> values,
                      const WriteGridOptions& opt = {}) {
  auto fmt = grid_format_of(path);
  if (!fmt) return fmt.error();
  switch (*fmt) {
  case GridFormat::vti:
    return write_vti(path, spec, values, opt);
  case GridFormat::npy:
    return write_npy(path, spec, values, opt);
  case GridFormat::raw:
    return write_raw(path, spec, values, opt);
  }
  return make_error(ErrorCode::unsupported, path, ": unknown output format");
}

} // namespace ebgeom

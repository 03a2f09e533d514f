// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `.raw` + `.json` sidecar: the bare values (x fastest) and a JSON file describing dims,
/// spacing, origin, box, dtype, byte order and centring.
#include <cstdint>
#include <string>
#include <vector>

#include "ebgeom/eval/grid_writer_common.hpp"

namespace ebgeom {

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

} // namespace ebgeom

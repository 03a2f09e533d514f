// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `.npy` writers: NumPy format 1.0, float32 or float64, C order (a grid has shape `(nz, ny, nx)`),
/// and `npy_header` for other writers of NumPy data.
#include <cstdint>
#include <string>
#include <vector>

#include "ebgeom/eval/grid_writer_common.hpp"

namespace ebgeom {

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

} // namespace ebgeom

// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "npy.hpp"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>

#include "common.hpp"

namespace ebgeom::cli {

namespace {

[[noreturn]] void bad(const std::string& path, std::size_t offset, const std::string& what) {
  fail(exit_input, path + ": byte " + std::to_string(offset) + ": " + what);
}

// Value of `key` in the header dict: the text after "'key':" up to the matching delimiter.
std::string dict_value(const std::string& h, const std::string& key) {
  const auto k = h.find("'" + key + "'");
  if (k == std::string::npos) return {};
  auto p = h.find(':', k);
  if (p == std::string::npos) return {};
  ++p;
  while (p < h.size() && h[p] == ' ') ++p;
  if (p >= h.size()) return {};
  if (h[p] == '\'') {
    const auto e = h.find('\'', p + 1);
    return e == std::string::npos ? std::string() : h.substr(p + 1, e - p - 1);
  }
  if (h[p] == '(') {
    const auto e = h.find(')', p);
    return e == std::string::npos ? std::string() : h.substr(p, e - p + 1);
  }
  const auto e = h.find_first_of(",}", p);
  return h.substr(p, e == std::string::npos ? std::string::npos : e - p);
}

} // namespace

std::vector<Vec3<double>> read_npy_points(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(exit_input, path + ": cannot open (" + std::string(std::strerror(errno)) + ")");
  std::string b;
  try {
    b.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } catch (const std::exception& e) {
    fail(exit_input, path + ": cannot read (" + e.what() + ")");
  }
  if (b.size() < 10 || b.compare(0, 6, "\x93NUMPY") != 0)
    bad(path, 0, "not a .npy file (bad magic)");
  const int major = static_cast<unsigned char>(b[6]);
  std::size_t hlen = 0, off = 0;
  if (major == 1) {
    hlen = std::size_t(std::uint8_t(b[8])) | std::size_t(std::uint8_t(b[9])) << 8;
    off = 10;
  } else if (major == 2 || major == 3) {
    if (b.size() < 12) bad(path, b.size(), "truncated header");
    hlen = std::size_t(std::uint8_t(b[8])) | std::size_t(std::uint8_t(b[9])) << 8 |
           std::size_t(std::uint8_t(b[10])) << 16 | std::size_t(std::uint8_t(b[11])) << 24;
    off = 12;
  } else {
    bad(path, 6, "unsupported .npy version " + std::to_string(major));
  }
  if (b.size() < off + hlen) bad(path, b.size(), "truncated header");
  const std::string h = b.substr(off, hlen);
  const std::string descr = dict_value(h, "descr");
  std::size_t width = 0;
  if (descr == "<f4")
    width = 4;
  else if (descr == "<f8")
    width = 8;
  else
    bad(path, off,
        "dtype '" + descr + "' is not supported; expected float32 ('<f4') or float64 ('<f8')");
  const std::string order = dict_value(h, "fortran_order");
  if (h.find("'fortran_order'") == std::string::npos)
    bad(path, off, "the header has no 'fortran_order' key (expected 'fortran_order': False)");
  if (order == "True")
    bad(path, off,
        "Fortran-order arrays are not supported; save a C-order array "
        "(numpy.ascontiguousarray)");
  if (order != "False")
    bad(path, off,
        "the header's 'fortran_order' is '" +
            (order.size() > 20 ? order.substr(0, 17) + "..." : order) +
            "', expected False or True");
  const std::string shape = dict_value(h, "shape");
  std::vector<std::uint64_t> dims;
  {
    std::size_t i = 1;
    while (i < shape.size()) {
      while (i < shape.size() && (shape[i] == ' ' || shape[i] == ',')) ++i;
      if (i >= shape.size() || shape[i] == ')') break;
      std::uint64_t v = 0;
      bool digits = false;
      while (i < shape.size() && shape[i] >= '0' && shape[i] <= '9') {
        if (v > (std::uint64_t(1) << 40)) bad(path, off, "shape " + shape + " is too large");
        v = v * 10 + std::uint64_t(shape[i++] - '0');
        digits = true;
      }
      if (!digits) bad(path, off, "cannot read the shape " + shape);
      dims.push_back(v);
    }
  }
  if (shape.empty() || dims.size() != 2 || dims[1] != 3)
    bad(path, off,
        "shape " + (shape.empty() ? std::string("?") : shape) +
            " is not (N, 3): expected one point (x, y, z) per row");
  const std::uint64_t n = dims[0];
  const std::uint64_t need = n * 3 * width;
  const std::size_t data = off + hlen;
  if (b.size() - data < need)
    bad(path, b.size(),
        "truncated data: shape " + shape + " needs " + std::to_string(need) + " bytes but " +
            std::to_string(b.size() - data) + " follow the header");
  std::vector<Vec3<double>> pts(n);
  for (std::uint64_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const char* p = b.data() + data + (i * 3 + std::uint64_t(c)) * width;
      double v;
      if (width == 4) {
        float f;
        std::memcpy(&f, p, 4);
        v = f;
      } else {
        std::memcpy(&v, p, 8);
      }
      if (!std::isfinite(v))
        bad(path, std::size_t(p - b.data()), "point " + std::to_string(i) + " has NaN/Inf");
      pts[i][c] = v;
    }
  return pts;
}

} // namespace ebgeom::cli

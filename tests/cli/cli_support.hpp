// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Helpers for the CLI tests: run the ebgeom binary, and read back .npy, .vti, .raw and PNG files
// with small readers written independently of the tool's writers.

#include <gtest/gtest.h>
#include <png.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace ebgeom::clitest {

struct RunResult {
  int code = -1;
  std::string out, err;
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Directories made by `test_dir`, removed when the test program exits (set
/// EBGEOM_KEEP_TEST_FILES to keep them for inspection).
struct TestDirs {
  std::vector<std::string> dirs;
  ~TestDirs() {
    if (std::getenv("EBGEOM_KEEP_TEST_FILES")) return;
    std::error_code ec;
    for (const auto& d : dirs) std::filesystem::remove_all(d, ec);
  }
};
inline TestDirs& test_dirs() {
  static TestDirs t;
  return t;
}

/// A fresh, empty directory for one test.
inline std::string test_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = std::string(info->test_suite_name()) + "_" + info->name();
  for (char& c : name)
    if (c == '/') c = '_';
  const std::string dir =
      ::testing::TempDir() + "ebgeom_cli_" + std::to_string(::getpid()) + "_" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  test_dirs().dirs.push_back(dir);
  return dir;
}

/// Runs `ebgeom ARGS` (ARGS is shell text) with stdin from /dev/null; captures exit code, stdout
/// and stderr.
inline RunResult run(const std::string& args) {
  static int counter = 0;
  // The process id keeps parallel test processes (ctest -j) apart.
  const std::string base = ::testing::TempDir() + "ebgeom_cli_run" + std::to_string(::getpid()) +
                           "_" + std::to_string(++counter);
  const std::string cmd = std::string("'") + EBGEOM_CLI_BINARY + "' " + args + " </dev/null >'" +
                          base + ".out' 2>'" + base + ".err'";
  const int st = std::system(cmd.c_str());
  RunResult r;
  r.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.out = slurp(base + ".out");
  r.err = slurp(base + ".err");
  std::remove((base + ".out").c_str());
  std::remove((base + ".err").c_str());
  return r;
}

inline bool exists(const std::string& p) { return std::filesystem::exists(p); }

/// Files in `dir` (names only).
inline std::vector<std::string> list_dir(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    names.push_back(e.path().filename().string());
  return names;
}

/// A decoded .npy array (values widened to double).
struct Npy {
  std::string descr;
  std::vector<std::size_t> shape;
  std::vector<double> data;
  bool fortran = true;
};

/// Minimal .npy reader (v1/v2 headers, little-endian f4/f8); fails the test on anything else.
inline Npy read_npy(const std::string& path) {
  Npy a;
  const std::string b = slurp(path);
  EXPECT_GE(b.size(), 10u) << path;
  if (b.size() < 10 || b.compare(0, 6, "\x93NUMPY") != 0) {
    ADD_FAILURE() << path << ": not a .npy file";
    return a;
  }
  std::size_t hlen, off;
  if (b[6] == 1) {
    hlen = std::size_t(std::uint8_t(b[8])) | std::size_t(std::uint8_t(b[9])) << 8;
    off = 10;
  } else {
    hlen = std::size_t(std::uint8_t(b[8])) | std::size_t(std::uint8_t(b[9])) << 8 |
           std::size_t(std::uint8_t(b[10])) << 16 | std::size_t(std::uint8_t(b[11])) << 24;
    off = 12;
  }
  const std::string h = b.substr(off, hlen);
  const auto d = h.find("'descr': '");
  a.descr = h.substr(d + 10, 3);
  a.fortran = h.find("'fortran_order': True") != std::string::npos;
  const auto s = h.find("'shape': (");
  std::string dims = h.substr(s + 10, h.find(')', s) - s - 10);
  std::istringstream is(dims);
  std::string tok;
  while (std::getline(is, tok, ','))
    if (tok.find_first_not_of(' ') != std::string::npos) a.shape.push_back(std::stoul(tok));
  std::size_t n = 1;
  for (auto x : a.shape) n *= x;
  const std::size_t w = a.descr == "<f4" ? 4 : (a.descr == "<f8" ? 8 : 0);
  if (w == 0) {
    ADD_FAILURE() << path << ": unexpected dtype " << a.descr;
    return a;
  }
  EXPECT_EQ(b.size(), off + hlen + n * w) << path;
  if (b.size() < off + hlen + n * w) return a;
  a.data.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (w == 4) {
      float f;
      std::memcpy(&f, b.data() + off + hlen + i * 4, 4);
      a.data[i] = f;
    } else {
      std::memcpy(&a.data[i], b.data() + off + hlen + i * 8, 8);
    }
  }
  return a;
}

/// Writes an .npy file (for inputs of `ebgeom query`), any descr, raw payload bytes.
inline void write_npy_bytes(const std::string& path, const std::string& descr,
                            const std::string& shape, const void* data, std::size_t bytes) {
  std::string h = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': " + shape + ", }";
  while ((10 + h.size() + 1) % 64) h += ' ';
  h += '\n';
  std::ofstream out(path, std::ios::binary);
  out.write("\x93NUMPY\x01\x00", 8);
  const char len[2] = {char(h.size() & 0xff), char(h.size() >> 8)};
  out.write(len, 2);
  out.write(h.data(), std::streamsize(h.size()));
  out.write(static_cast<const char*>(data), std::streamsize(bytes));
}

/// A decoded .vti file with one appended raw array.
struct Vti {
  int extent[6] = {0, 0, 0, 0, 0, 0};
  double origin[3] = {0, 0, 0}, spacing[3] = {0, 0, 0};
  std::string type;
  std::vector<double> data;
};

inline std::string xml_attr(const std::string& text, const std::string& name) {
  const auto p = text.find(" " + name + "=\"");
  if (p == std::string::npos) return {};
  const auto s = p + name.size() + 3;
  return text.substr(s, text.find('"', s) - s);
}

inline Vti read_vti(const std::string& path) {
  Vti v;
  const std::string b = slurp(path);
  const auto app = b.find("<AppendedData encoding=\"raw\">");
  if (b.find("<VTKFile type=\"ImageData\"") == std::string::npos || app == std::string::npos) {
    ADD_FAILURE() << path << ": not a raw-appended VTK ImageData file";
    return v;
  }
  EXPECT_EQ(xml_attr(b, "header_type"), "UInt64");
  EXPECT_EQ(xml_attr(b, "byte_order"), "LittleEndian");
  const std::string head = b.substr(0, app);
  std::istringstream(xml_attr(head, "WholeExtent")) >> v.extent[0] >> v.extent[1] >> v.extent[2] >>
      v.extent[3] >> v.extent[4] >> v.extent[5];
  std::istringstream(xml_attr(head, "Origin")) >> v.origin[0] >> v.origin[1] >> v.origin[2];
  std::istringstream(xml_attr(head, "Spacing")) >> v.spacing[0] >> v.spacing[1] >> v.spacing[2];
  v.type = xml_attr(head.substr(head.find("<DataArray")), "type");
  const auto us = b.find('_', app);
  std::uint64_t nbytes = 0;
  std::memcpy(&nbytes, b.data() + us + 1, 8);
  const std::size_t w = v.type == "Float32" ? 4 : 8;
  const std::size_t n = std::size_t(v.extent[1] + 1) * (v.extent[3] + 1) * (v.extent[5] + 1);
  EXPECT_EQ(nbytes, n * w);
  if (b.size() < us + 9 + n * w) {
    ADD_FAILURE() << path << ": truncated";
    return v;
  }
  v.data.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (w == 4) {
      float f;
      std::memcpy(&f, b.data() + us + 9 + i * 4, 4);
      v.data[i] = f;
    } else {
      std::memcpy(&v.data[i], b.data() + us + 9 + i * 8, 8);
    }
  }
  EXPECT_NE(b.find("</VTKFile>", us + 9 + n * w), std::string::npos);
  return v;
}

/// Decoded RGB(A) PNG: size and pixels (RGB).
struct Png {
  unsigned width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

inline Png read_png(const std::string& path) {
  Png p;
  png_image img;
  std::memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, path.c_str())) {
    ADD_FAILURE() << path << ": libpng cannot read it: " << img.message;
    return p;
  }
  img.format = PNG_FORMAT_RGB;
  p.width = img.width;
  p.height = img.height;
  p.rgb.resize(PNG_IMAGE_SIZE(img));
  if (!png_image_finish_read(&img, nullptr, p.rgb.data(), 0, nullptr))
    ADD_FAILURE() << path << ": decode failed: " << img.message;
  return p;
}

} // namespace ebgeom::clitest

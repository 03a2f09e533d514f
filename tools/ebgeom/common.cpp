// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "common.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace ebgeom::cli {

std::uint64_t available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (in >> key >> kib) {
    std::getline(in, unit);
    if (key == "MemAvailable:") return kib * 1024;
  }
  return 0;
}

std::string human_bytes(std::uint64_t bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB"};
  double v = double(bytes);
  int u = 0;
  while (v >= 1024 && u < 5) {
    v /= 1024;
    ++u;
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.1f %s", v, units[u]);
  return buf;
}

void require_memory(std::uint64_t bytes, const std::string& what, const std::string& hint) {
  const std::uint64_t avail = available_memory_bytes();
  if (avail != 0 && bytes > avail)
    fail(exit_resource, what + " needs " + human_bytes(bytes) + " of memory but only " +
                            human_bytes(avail) + " is available; " + hint);
}

void require_input_file(const std::string& path) {
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(st)) fail(exit_input, path + ": no such file");
  if (std::filesystem::is_directory(st)) fail(exit_input, path + ": is a directory, not a file");
}

bool stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

} // namespace ebgeom::cli

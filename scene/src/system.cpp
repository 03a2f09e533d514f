// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/scene/system.hpp"

#include "ebgeom/io/atomic_file.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace ebgeom::scene {

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

namespace {
const char* file_type_name(mode_t mode) {
  return S_ISFIFO(mode)   ? "a FIFO (named pipe)"
         : S_ISCHR(mode)  ? "a character device"
         : S_ISBLK(mode)  ? "a block device"
         : S_ISSOCK(mode) ? "a socket"
                          : "not a regular file";
}
} // namespace

void require_input_file(const std::string& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) fail(exit_input, path + ": no such file");
    fail(exit_input, path + ": cannot open (" + std::strerror(errno) + ")");
  }
  if (S_ISDIR(st.st_mode)) fail(exit_input, path + ": is a directory, not a file");
  if (!S_ISREG(st.st_mode))
    fail(exit_input, path + ": is " + file_type_name(st.st_mode) +
                         ", not a regular file; only regular files are read (save the data to a "
                         "file first)");
}

void require_output_target(const std::string& path) {
  if (auto ok = check_output_target(path); !ok) fail(exit_output, ok.error().what());
}

bool stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

} // namespace ebgeom::scene

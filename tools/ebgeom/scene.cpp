// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "scene.hpp"

#include <algorithm>

namespace ebgeom::cli {

Json read_json_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(exit_input, path + ": cannot open (" + std::string(std::strerror(errno)) + ")");
  std::string text;
  try {
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } catch (const std::exception& e) {
    fail(exit_input, path + ": cannot read (" + e.what() + ")");
  }
  if (in.bad()) fail(exit_input, path + ": cannot read");
  try {
    return Json::parse(text, nullptr, true, /*ignore_comments=*/true);
  } catch (const Json::parse_error& e) {
    // Locate the byte offset as line and column.
    const std::size_t at = std::min<std::size_t>(e.byte == 0 ? 0 : e.byte - 1, text.size());
    const std::size_t line = 1 + std::count(text.begin(), text.begin() + long(at), '\n');
    const std::size_t nl = text.rfind('\n', at == 0 ? 0 : at - 1);
    const std::size_t col = nl == std::string::npos ? at + 1 : at - nl;
    std::string what = e.what();
    const auto p = what.find("parse error");
    if (p != std::string::npos) what = what.substr(p);
    fail(exit_input, path + ": line " + std::to_string(line) + ", column " + std::to_string(col) +
                         ": invalid JSON: " + what);
  }
}

bool is_scene_path(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext == ".json" || ext == ".JSON";
}

} // namespace ebgeom::cli

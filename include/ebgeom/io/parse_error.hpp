// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Functions that build `ParseError`s with a location, shared by `ByteReader`, `TextReader` and the
/// format readers.

#include <cstdint>
#include <string>

#include "ebgeom/core/error.hpp"

namespace ebgeom::io {

/// A `ParseError` at byte `offset` (binary data; `line` 0) or at a text `line` (1-based; the byte
/// offset is kept too) of the input named `path`. The message is the concatenation of `parts`.
template <class... A>
ParseError make_parse_error(ErrorCode code, const std::string& path, std::uint64_t offset,
                            std::uint64_t line, const A&... parts) {
  ParseError e;
  e.code = code;
  e.message = detail::concat(parts...);
  e.path = path;
  e.byte_offset = offset;
  e.line = line;
  return e;
}

} // namespace ebgeom::io

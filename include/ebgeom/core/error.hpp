// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Error values: `ErrorCode`, `Error`, `ParseError` and the `Exception` thrown by `Result::value()`
/// on an error. The library itself never throws on bad input and never prints.

#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace ebgeom {

/// What went wrong, coarse enough to branch on. Messages carry the details.
enum class ErrorCode : std::uint8_t {
  ok = 0,
  io,            ///< a file could not be opened, read or written
  empty,         ///< the input holds nothing (empty file, mesh without faces)
  truncated,     ///< the input ends before what its header or syntax promises
  bad_magic,     ///< the content is not the format it claims (or no format was recognised)
  syntax,        ///< a token is not what the grammar expects
  bad_number,    ///< a number is malformed or out of range for its type
  non_finite,    ///< NaN or infinity where a finite value is required
  bad_index,     ///< an index is out of range (vertex index >= vertex count, zero OBJ index, ...)
  size_mismatch, ///< declared counts disagree with the data (or exceed a limit)
  unsupported,   ///< valid input that this library does not handle (e.g. VTK STRUCTURED_POINTS)
  degenerate,    ///< geometry that cannot be used (zero-area face, fewer than 3 vertices)
  invalid_mesh,  ///< topology that makes the requested operation undefined
  invalid_argument, ///< a parameter out of its documented range
  out_of_memory,    ///< a request larger than allowed or available
};

/// Stable lower-case name of a code, e.g. "truncated".
inline const char* to_string(ErrorCode c) noexcept {
  switch (c) {
  case ErrorCode::ok:
    return "ok";
  case ErrorCode::io:
    return "io";
  case ErrorCode::empty:
    return "empty";
  case ErrorCode::truncated:
    return "truncated";
  case ErrorCode::bad_magic:
    return "bad_magic";
  case ErrorCode::syntax:
    return "syntax";
  case ErrorCode::bad_number:
    return "bad_number";
  case ErrorCode::non_finite:
    return "non_finite";
  case ErrorCode::bad_index:
    return "bad_index";
  case ErrorCode::size_mismatch:
    return "size_mismatch";
  case ErrorCode::unsupported:
    return "unsupported";
  case ErrorCode::degenerate:
    return "degenerate";
  case ErrorCode::invalid_mesh:
    return "invalid_mesh";
  case ErrorCode::invalid_argument:
    return "invalid_argument";
  case ErrorCode::out_of_memory:
    return "out_of_memory";
  }
  return "unknown";
}

/// A general error: a code and a human-readable message (one line, no trailing newline).
struct Error {
  ErrorCode code = ErrorCode::ok;
  std::string message;

  /// One-line description, e.g. "invalid_argument: radius must be > 0".
  std::string what() const { return message.empty() ? to_string(code) : message; }
};

/// An error located in an input file. `line` is 1-based (0 when not a text position) and
/// `byte_offset` counts from the start of the file. `what()` prints
/// `bunny.ply: byte 1832 (line 12): vertex index 90211 >= vertex count 35947`.
struct ParseError {
  ErrorCode code = ErrorCode::ok;
  std::string message;
  std::string path;
  std::uint64_t byte_offset = 0;
  std::uint64_t line = 0;

  std::string what() const {
    std::ostringstream os;
    os << (path.empty() ? std::string("<input>") : path) << ": ";
    if (line > 0)
      os << "line " << line << ": ";
    else
      os << "byte " << byte_offset << ": ";
    os << message;
    return os.str();
  }
  /// Drops the location, keeping the code and the full text.
  operator Error() const { return Error{code, what()}; }
};

/// Thrown only by `Result::value()` on an error (and by tools), never by the library on its own.
class Exception : public std::runtime_error {
 public:
  Exception(ErrorCode code, const std::string& what) : std::runtime_error(what), code_(code) {}
  ErrorCode code() const noexcept { return code_; }

 private:
  ErrorCode code_;
};

namespace detail {
template <class... A> std::string concat(const A&... a) {
  std::ostringstream os;
  os.precision(17);
  (os << ... << a);
  return os.str();
}
} // namespace detail

/// Builds an `Error` whose message is the concatenation of `parts`.
template <class... A> Error make_error(ErrorCode code, const A&... parts) {
  return Error{code, detail::concat(parts...)};
}

} // namespace ebgeom

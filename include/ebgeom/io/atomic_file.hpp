// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Safe output files (POSIX): `AtomicFile` writes a file under a unique temporary name beside its
/// target and renames it onto the target only when everything was written; `OutputGroup` defers
/// those renames until every output of a job is written; `remove_temp_files_on_signals` removes
/// unfinished temporaries when the process is interrupted.
///
/// What each kind of output path gets (`check_output_target`):
///  - absent, or a regular file: written atomically (temporary + rename). A replaced file keeps its
///    permission bits; a new one gets 0666 less the umask;
///  - a FIFO or a character device (`/dev/null`, `/dev/stdout`, a named pipe), directly or through
///    a symbolic link: written through, in place, since that is what naming one means. Not atomic;
///    opening a FIFO waits for a reader;
///  - any other symbolic link (dangling, or to a regular file or directory): refused, since
///    renaming onto the link would replace the link itself;
///  - a directory, block device or socket: refused.
///
/// Temporaries are named `.NAME.XXXXXXXXXX.ebgeom-tmp` in the target's directory and created with
/// `O_CREAT | O_EXCL | O_NOFOLLOW`, so a planted file or link is never followed or shared.

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <ostream>
#include <random>
#include <streambuf>
#include <string>
#include <vector>

#include "ebgeom/core/error.hpp"
#include "ebgeom/core/result.hpp"

namespace ebgeom {

/// How an output path is written (see the file comment).
enum class OutputTargetKind : std::uint8_t {
  create,  ///< does not exist yet: created atomically
  replace, ///< a regular file: replaced atomically, keeping its permission bits
  stream,  ///< a FIFO or character device (perhaps through a link): written through in place
};

namespace detail {

/// The registry of temporary files that a signal handler removes: fixed slots (no allocation,
/// readable from a signal handler). A slot is 0 (free), 1 (being filled or emptied) or 2 (holds a
/// path to remove).
struct TempSlot {
  std::atomic<int> state{0};
  char path[4096];
};
constexpr int temp_slot_count = 64;

inline TempSlot* temp_slots() noexcept {
  static TempSlot slots[temp_slot_count];
  return slots;
}

/// Registers `path` for removal on a signal; returns the slot, or -1 when the path is too long or
/// every slot is taken (the file is then only removed by the normal paths).
inline int register_temp(const std::string& path) noexcept {
  if (path.size() >= sizeof(TempSlot::path)) return -1;
  TempSlot* s = temp_slots();
  for (int i = 0; i < temp_slot_count; ++i) {
    int expected = 0;
    if (s[i].state.compare_exchange_strong(expected, 1)) {
      std::memcpy(s[i].path, path.c_str(), path.size() + 1);
      s[i].state.store(2);
      return i;
    }
  }
  return -1;
}

inline void unregister_temp(int slot) noexcept {
  if (slot >= 0) temp_slots()[slot].state.store(0);
}

/// Removes every registered temporary. Async-signal-safe (atomics and `unlink` only).
inline void remove_registered_temps() noexcept {
  TempSlot* s = temp_slots();
  for (int i = 0; i < temp_slot_count; ++i)
    if (s[i].state.load() == 2) ::unlink(s[i].path);
}

inline void temp_cleanup_signal_handler(int sig) {
  remove_registered_temps();
  // The handler was installed with SA_RESETHAND: raising again ends the process as the signal
  // would have (exit status, core dump).
  ::raise(sig);
}

/// A stream buffer writing to a file descriptor, remembering the first error's `errno`.
class FdStreamBuf : public std::streambuf {
 public:
  FdStreamBuf() { setp(buf_, buf_ + sizeof buf_); }
  FdStreamBuf(const FdStreamBuf&) = delete;
  FdStreamBuf& operator=(const FdStreamBuf&) = delete;
  void attach(int fd) noexcept { fd_ = fd; }
  int error() const noexcept { return err_; }
  /// Writes out the buffer; false on error.
  bool flush_buffer() noexcept {
    const bool ok = write_all(pbase(), std::size_t(pptr() - pbase()));
    setp(buf_, buf_ + sizeof buf_);
    return ok;
  }

 protected:
  int_type overflow(int_type c) override {
    if (!flush_buffer()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (n <= 0) return 0; // nothing to copy (`s` may then be null)
    if (n <= epptr() - pptr()) {
      std::memcpy(pptr(), s, std::size_t(n));
      pbump(int(n));
      return n;
    }
    if (!flush_buffer() || !write_all(s, std::size_t(n))) return 0;
    return n;
  }
  int sync() override { return flush_buffer() ? 0 : -1; }

 private:
  bool write_all(const char* p, std::size_t n) noexcept {
    if (err_ != 0) return false;
    while (n > 0) {
      const ssize_t w = ::write(fd_, p, n);
      if (w < 0) {
        if (errno == EINTR) continue;
        err_ = errno;
        return false;
      }
      if (w == 0) {
        err_ = EIO;
        return false;
      }
      p += w;
      n -= std::size_t(w);
    }
    return true;
  }
  int fd_ = -1;
  int err_ = 0;
  char buf_[1 << 16];
};

inline std::string errno_text(int e) { return std::strerror(e); }

/// A fresh random suffix for a temporary name: 10 characters of [0-9a-z].
inline std::string temp_suffix() {
  static std::atomic<std::uint64_t> counter{0};
  std::uint64_t x = std::uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()) ^
                    (std::uint64_t(::getpid()) << 32) ^
                    (counter.fetch_add(1) * 0x9e3779b97f4a7c15u);
  try {
    std::random_device rd;
    x ^= (std::uint64_t(rd()) << 32) ^ rd();
  } catch (...) { // no entropy source: the clock, process id and counter still differ
  }
  const char* digits = "0123456789abcdefghijklmnopqrstuvwxyz";
  std::string s(10, '0');
  for (char& c : s) {
    x ^= x >> 31; // splitmix-style mixing
    x *= 0xbf58476d1ce4e5b9u;
    x ^= x >> 29;
    c = digits[x % 36];
  }
  return s;
}

} // namespace detail

/// What writing `path` would do (see the file comment), checked without opening it. Errors (`io`,
/// naming `path`): a directory, block device, socket, or a symbolic link to anything other than a
/// FIFO or character device; a path that cannot be looked up (missing directory, permissions).
inline Result<OutputTargetKind> check_output_target(const std::string& path) {
  if (path.empty()) return make_error(ErrorCode::io, "an empty output path");
  struct stat st;
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) {
      const std::size_t slash = path.find_last_of('/');
      const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash + 1);
      struct stat ds;
      if (::stat(dir.c_str(), &ds) != 0)
        return make_error(ErrorCode::io, path, ": cannot open for writing (", dir, ": ",
                          detail::errno_text(errno), ")");
      if (!S_ISDIR(ds.st_mode))
        return make_error(ErrorCode::io, path, ": cannot open for writing (", dir,
                          " is not a directory)");
      return OutputTargetKind::create;
    }
    return make_error(ErrorCode::io, path, ": cannot open for writing (", detail::errno_text(errno),
                      ")");
  }
  if (S_ISLNK(st.st_mode)) {
    struct stat to;
    if (::stat(path.c_str(), &to) == 0 && (S_ISFIFO(to.st_mode) || S_ISCHR(to.st_mode)))
      return OutputTargetKind::stream;
    return make_error(ErrorCode::io, path,
                      ": is a symbolic link; outputs never replace a link (renaming onto it would "
                      "replace the link itself): give the path of the file it points to, or remove "
                      "the link");
  }
  if (S_ISREG(st.st_mode)) return OutputTargetKind::replace;
  if (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode)) return OutputTargetKind::stream;
  const char* what = S_ISDIR(st.st_mode)    ? "a directory"
                     : S_ISBLK(st.st_mode)  ? "a block device"
                     : S_ISSOCK(st.st_mode) ? "a socket"
                                            : "not a regular file";
  return make_error(ErrorCode::io, path, ": is ", what,
                    "; outputs are regular files (or a FIFO or character device, written through)");
}

class OutputGroup;

/// A file written under a unique temporary name beside `path` and renamed onto `path` by
/// `commit()` (atomic replacement). Destroying an uncommitted one removes the temporary. A FIFO or
/// character device target is written through instead (see `check_output_target`). Inside an
/// `OutputGroup` (on this thread), `commit()` hands the temporary to the group, which renames it
/// with the group's other outputs. Not copyable or movable.
class AtomicFile {
 public:
  explicit AtomicFile(std::string path) : path_(std::move(path)), os_(&buf_) { open(); }
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile() { discard(); }

  bool is_open() const noexcept { return fd_ >= 0; }
  /// The stream to write; a write error sets its badbit and is reported by `close()`.
  std::ostream& stream() noexcept { return os_; }
  /// Why the file could not be opened (when `!is_open()`).
  Error open_error() const {
    return Error{ErrorCode::io,
                 open_error_.empty() ? path_ + ": cannot open for writing" : open_error_};
  }
  /// The path written for now (the temporary, or the target itself when written through).
  const std::string& temp_path() const noexcept { return stream_ ? path_ : tmp_; }
  const std::string& path() const noexcept { return path_; }
  OutputTargetKind kind() const noexcept { return kind_; }

  /// Flushes and closes the file; it is renamed by `commit()`. Errors: `io` with the system's
  /// reason (e.g. "No space left on device").
  Result<Ok> close() {
    if (fd_ < 0) return open_error();
    os_.flush();
    int err = buf_.flush_buffer() ? 0 : buf_.error();
    if (err == 0 && !os_.good()) err = buf_.error() ? buf_.error() : EIO;
    if (::close(fd_) != 0 && err == 0) err = errno;
    fd_ = -1;
    closed_ = true;
    if (err != 0)
      return make_error(ErrorCode::io, path_, ": write failed (", detail::errno_text(err), ")");
    return Ok{};
  }

  /// Renames the closed temporary onto the target (or hands it to the current `OutputGroup`).
  Result<Ok> commit();

  /// Removes the temporary (if any) now; a later `commit()` fails.
  void discard() noexcept {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    if (!committed_ && !tmp_.empty() && !stream_) ::unlink(tmp_.c_str());
    detail::unregister_temp(slot_);
    slot_ = -1;
    tmp_.clear();
  }

 private:
  void open() {
    auto kind = check_output_target(path_);
    if (!kind) {
      open_error_ = kind.error().what();
      return;
    }
    kind_ = *kind;
    if (kind_ == OutputTargetKind::stream) {
      stream_ = true;
      fd_ = ::open(path_.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
      if (fd_ < 0)
        open_error_ = path_ + ": cannot open for writing (" + detail::errno_text(errno) + ")";
      buf_.attach(fd_);
      return;
    }
    mode_t mode = 0666; // less the umask, applied by open()
    if (kind_ == OutputTargetKind::replace) {
      struct stat st;
      if (::stat(path_.c_str(), &st) == 0) mode = st.st_mode & 07777;
    }
    const std::size_t slash = path_.find_last_of('/');
    const std::string dir = slash == std::string::npos ? std::string() : path_.substr(0, slash + 1);
    std::string base = slash == std::string::npos ? path_ : path_.substr(slash + 1);
    if (base.size() > 200) base.resize(200); // keep the name under NAME_MAX
    int err = 0;
    for (int attempt = 0; attempt < 64; ++attempt) {
      std::string tmp = dir + "." + base + "." + detail::temp_suffix() + ".ebgeom-tmp";
      // Registered before it exists, so no signal can leave it behind.
      const int slot = detail::register_temp(tmp);
      const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC,
                            kind_ == OutputTargetKind::replace ? 0600 : 0666);
      if (fd >= 0) {
        if (kind_ == OutputTargetKind::replace) (void)::fchmod(fd, mode);
        fd_ = fd;
        slot_ = slot;
        tmp_ = std::move(tmp);
        buf_.attach(fd_);
        return;
      }
      err = errno;
      detail::unregister_temp(slot);
      if (err != EEXIST) break;
    }
    open_error_ = path_ + ": cannot create a temporary file in " + (dir.empty() ? "." : dir) +
                  " (" + detail::errno_text(err) + ")";
  }

  friend class OutputGroup;
  std::string path_, tmp_, open_error_;
  detail::FdStreamBuf buf_;
  std::ostream os_;
  int fd_ = -1;
  int slot_ = -1;
  OutputTargetKind kind_ = OutputTargetKind::create;
  bool stream_ = false, closed_ = false, committed_ = false;
};

/// The outputs of one job, made visible together: while an `OutputGroup` is alive on a thread,
/// `AtomicFile::commit()` there leaves the written temporary pending in the group; `commit()`
/// renames every pending temporary onto its target, and destroying the group uncommitted removes
/// them, so a job that fails after writing some outputs leaves none of them. (Outputs written
/// through, to a FIFO or device, cannot be held back.) Groups nest; destroy them in reverse order
/// of creation. Not copyable.
class OutputGroup {
 public:
  OutputGroup() : prev_(current()) { current() = this; }
  OutputGroup(const OutputGroup&) = delete;
  OutputGroup& operator=(const OutputGroup&) = delete;
  ~OutputGroup() {
    discard();
    current() = prev_;
  }

  /// Renames every pending output onto its target, in the order they were written. If one rename
  /// fails, the outputs not yet renamed are removed and the error is returned (the ones before it
  /// stay: a rename in the same directory fails only when the directory itself changed).
  Result<Ok> commit() {
    for (std::size_t i = 0; i < pending_.size(); ++i) {
      Pending& p = pending_[i];
      if (auto ok = rename_onto(p.tmp, p.path); !ok) {
        discard();
        return ok;
      }
      detail::unregister_temp(p.slot);
      p.slot = -1;
      p.tmp.clear();
    }
    pending_.clear();
    return Ok{};
  }

  /// Removes every pending temporary.
  void discard() noexcept {
    for (Pending& p : pending_) {
      if (!p.tmp.empty()) ::unlink(p.tmp.c_str());
      detail::unregister_temp(p.slot);
    }
    pending_.clear();
  }

  /// The group `AtomicFile::commit()` hands its file to on this thread, or null.
  static OutputGroup*& current() noexcept {
    static thread_local OutputGroup* group = nullptr;
    return group;
  }

  /// Renames the temporary `tmp` onto `path` after checking that `path` is still something an
  /// output may replace.
  static Result<Ok> rename_onto(const std::string& tmp, const std::string& path) {
    auto kind = check_output_target(path);
    if (!kind) return kind.error();
    if (*kind == OutputTargetKind::stream)
      return make_error(ErrorCode::io, path, ": became a FIFO or device while it was written");
    if (::rename(tmp.c_str(), path.c_str()) != 0)
      return make_error(ErrorCode::io, path, ": cannot rename the temporary file onto it (",
                        detail::errno_text(errno), ")");
    return Ok{};
  }

 private:
  friend class AtomicFile;
  struct Pending {
    std::string tmp, path;
    int slot;
  };
  std::vector<Pending> pending_;
  OutputGroup* prev_;
};

inline Result<Ok> AtomicFile::commit() {
  if (committed_) return Ok{};
  if (!closed_) {
    if (auto ok = close(); !ok) {
      discard();
      return ok;
    }
  }
  if (stream_) {
    committed_ = true;
    return Ok{};
  }
  if (tmp_.empty()) return open_error();
  if (OutputGroup* g = OutputGroup::current()) {
    g->pending_.push_back({tmp_, path_, slot_});
    slot_ = -1;
    tmp_.clear();
    committed_ = true;
    return Ok{};
  }
  if (auto ok = OutputGroup::rename_onto(tmp_, path_); !ok) {
    discard();
    return ok;
  }
  committed_ = true;
  detail::unregister_temp(slot_);
  slot_ = -1;
  tmp_.clear();
  return Ok{};
}

/// Installs handlers for SIGINT, SIGTERM, SIGHUP and SIGPIPE that remove the temporaries of
/// unfinished `AtomicFile`s and `OutputGroup`s, then end the process by the same signal (a
/// signal that is ignored stays ignored; one with a handler of the program's own is left alone).
/// For programs (the library never installs it by itself). SIGKILL cannot be caught: a killed
/// process leaves its `*.ebgeom-tmp` files.
inline void remove_temp_files_on_signals() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
    struct sigaction old;
    if (::sigaction(sig, nullptr, &old) != 0) continue;
    if (old.sa_handler != SIG_DFL) continue; // ignored, or the program's own handler
    struct sigaction sa;
    std::memset(&sa, 0, sizeof sa);
    sa.sa_handler = detail::temp_cleanup_signal_handler;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND;
    ::sigaction(sig, &sa, nullptr);
  }
}

namespace detail {
/// The former name of `ebgeom::AtomicFile`.
using AtomicFile = ebgeom::AtomicFile;
} // namespace detail

} // namespace ebgeom

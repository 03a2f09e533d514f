// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// A progress bar with ETA on stderr, shown only when enabled (stderr is a terminal and --quiet was
// not given). update() is thread-safe and throttled to ~10 redraws a second.

#include <atomic>
#include <cstddef>
#include <mutex>
#include <string>

namespace ebgeom::cli {

class Progress {
 public:
  Progress(std::string label, bool enabled);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  /// Reports `done` of `total` units. Thread-safe.
  void update(std::size_t done, std::size_t total);
  /// Clears the bar (called by the destructor too).
  void finish();
  bool enabled() const { return enabled_; }

 private:
  std::string label_;
  bool enabled_;
  bool drawn_ = false;
  double start_;
  std::atomic<double> last_draw_{0};
  std::mutex mutex_;
};

} // namespace ebgeom::cli

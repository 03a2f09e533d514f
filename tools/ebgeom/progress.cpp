// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "progress.hpp"

#include <cstdio>
#include <cstdlib>

#include "common.hpp"

namespace ebgeom::cli {

namespace {
/// Seconds before a bar appears: 0.5, or EBGEOM_PROGRESS_DELAY (seconds; the tests set 0 so that
/// a bar appears however fast the machine).
double progress_delay() {
  const char* e = std::getenv("EBGEOM_PROGRESS_DELAY");
  if (!e || !*e) return 0.5;
  char* end = nullptr;
  const double v = std::strtod(e, &end);
  return end && *end == '\0' && v >= 0 && v < 1e6 ? v : 0.5;
}
} // namespace

Progress::Progress(std::string label, bool enabled)
    : label_(std::move(label)), enabled_(enabled), start_(now_s()) {}

Progress::~Progress() { finish(); }

void Progress::update(std::size_t done, std::size_t total) {
  if (!enabled_ || total == 0) return;
  const double t = now_s();
  // Skip the first half second (short jobs stay silent) and redraw at most ten times a second.
  static const double delay = progress_delay();
  if (t - start_ < delay || (t - last_draw_.load(std::memory_order_relaxed) < 0.1 && done < total))
    return;
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;
  last_draw_.store(t, std::memory_order_relaxed);
  const double frac = double(done) / double(total);
  const int width = 30;
  const int fill = int(frac * width + 0.5);
  char bar[width + 1];
  for (int i = 0; i < width; ++i) bar[i] = i < fill ? '#' : '.';
  bar[width] = 0;
  const double elapsed = t - start_;
  const double eta = frac > 0 ? elapsed * (1 - frac) / frac : 0;
  std::fprintf(stderr, "\r%s [%s] %3d%%  ETA %5.1fs ", label_.c_str(), bar, int(frac * 100 + 0.5),
               eta);
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (drawn_) {
    std::fprintf(stderr, "\r%*s\r", int(label_.size()) + 60, "");
    std::fflush(stderr);
    drawn_ = false;
  }
}

} // namespace ebgeom::cli

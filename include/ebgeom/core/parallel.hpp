// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `parallel_for`: the one place ebgeom starts threads. OpenMP when compiled with it (`_OPENMP`),
/// otherwise a small `std::thread` pool per call; inline below a serial threshold.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace ebgeom {

/// How a batch is executed. `threads = 0` means all hardware threads (or OpenMP's default).
struct ExecOptions {
  int threads = 0;
  /// Ranges shorter than this run inline on the calling thread.
  std::size_t serial_threshold = 1024;
};

/// Number of threads `opt` resolves to (>= 1).
inline int resolve_threads(const ExecOptions& opt) noexcept {
  if (opt.threads > 0) return opt.threads;
#if defined(_OPENMP)
  return std::max(1, omp_get_max_threads());
#else
  return std::max(1u, std::thread::hardware_concurrency());
#endif
}

/// Calls `fn(chunk_begin, chunk_end)` on disjoint chunks of at most `grain` indices covering
/// [begin, end), dynamically scheduled over threads. `fn` must be safe to call concurrently on
/// disjoint chunks; results must not depend on which thread runs which chunk (they never do in
/// ebgeom: chunks write disjoint outputs). Exceptions must not escape `fn`.
template <class Fn>
void parallel_for(std::size_t begin, std::size_t end, std::size_t grain, Fn&& fn,
                  const ExecOptions& opt = {}) {
  if (end <= begin) return;
  grain = std::max<std::size_t>(grain, 1);
  const std::size_t n = end - begin;
  const std::size_t chunks = (n + grain - 1) / grain;
  const int threads = static_cast<int>(std::min<std::size_t>(resolve_threads(opt), chunks));
  if (threads <= 1 || n < opt.serial_threshold) {
    fn(begin, end);
    return;
  }
#if defined(_OPENMP)
  const long long nchunks = static_cast<long long>(chunks);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (long long c = 0; c < nchunks; ++c) {
    const std::size_t b = begin + static_cast<std::size_t>(c) * grain;
    fn(b, std::min(end, b + grain));
  }
#else
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (;;) {
      const std::size_t c = next.fetch_add(1, std::memory_order_relaxed);
      if (c >= chunks) return;
      const std::size_t b = begin + c * grain;
      fn(b, std::min(end, b + grain));
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(static_cast<std::size_t>(threads - 1));
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
#endif
}

} // namespace ebgeom

#pragma once
// The shared grid job of `ebgeom sdf` and `ebgeom demo`: sample an SDF on a dense grid with a
// progress bar, then write the grid and an optional PNG slice.

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "common.hpp"
#include "ebgeom/eval/grid.hpp"
#include "ebgeom/eval/write_grid.hpp"
#include "png_slice.hpp"
#include "progress.hpp"

namespace ebgeom::cli {

/// Summary statistics of a grid.
struct GridStats {
  double min = 0, max = 0, inside_fraction = 0;
};

template <class T> GridStats grid_stats(Span<const T> v) {
  GridStats s;
  s.min = std::numeric_limits<double>::infinity();
  s.max = -s.min;
  std::size_t inside = 0;
  for (T x : v) {
    s.min = std::min(s.min, double(x));
    s.max = std::max(s.max, double(x));
    inside += x < 0;
  }
  s.inside_fraction = v.empty() ? 0 : double(inside) / double(v.size());
  return s;
}

/// Samples `sdf` on `spec` (throws CliError on failure), showing a progress bar if `progress`.
template <class S>
std::vector<sdf_scalar_t<S>> sample_with_progress(const S& sdf,
                                                  const GridSpec<sdf_scalar_t<S>>& spec,
                                                  GridOptions opt, bool progress) {
  using T = sdf_scalar_t<S>;
  std::vector<T> values(spec.size());
  Progress bar("sampling", progress);
  if (bar.enabled()) opt.progress = [&bar](std::size_t d, std::size_t t) { bar.update(d, t); };
  auto ok = sample_grid(sdf, spec, Span<T>(values), opt);
  bar.finish();
  if (!ok) fail(exit_failure, ok.error().what());
  return values;
}

/// Writes `values` to `path` by extension; throws CliError (output) on failure.
template <class T>
void write_grid_or_fail(const std::string& path, const GridSpec<T>& spec, Span<const T> values,
                        DType dtype) {
  WriteGridOptions w;
  w.dtype = dtype;
  auto ok = write_grid(path, spec, values, w);
  if (!ok)
    fail(ok.error().code == ErrorCode::unsupported ? exit_usage : exit_output, ok.error().what());
}

} // namespace ebgeom::cli

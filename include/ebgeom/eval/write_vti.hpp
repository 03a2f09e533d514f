// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// VTK XML ImageData writers: `.vti` (one point-data array, binary appended raw data; `Origin`
/// is the first sample, so cell-centred grids contour correctly), a piece of a grid
/// (`write_vti_piece`) and the `.pvti` that assembles pieces (`write_pvti`).
#include <cstdint>
#include <string>
#include <vector>

#include "ebgeom/eval/grid_writer_common.hpp"

namespace ebgeom {

namespace detail {

/// VTK extent text of the samples `r`: `i0 i1 j0 j1 k0 k1`, inclusive.
inline std::string vtk_extent(const GridRange& r) {
  return std::to_string(r.lo[0]) + ' ' + std::to_string(r.hi[0] - 1) + ' ' +
         std::to_string(r.lo[1]) + ' ' + std::to_string(r.hi[1] - 1) + ' ' +
         std::to_string(r.lo[2]) + ' ' + std::to_string(r.hi[2] - 1);
}

/// The `<?xml?>` line and the `<VTKFile>` tag of a file of `type` (`ImageData`, `PImageData`),
/// then the type's element opened with `WholeExtent` `whole`, the attributes `extra` (with a
/// leading space, or empty) and `spec`'s origin and spacing.
template <class T>
void vtk_image_head(std::ostream& xml, const char* type, const GridSpec<T>& spec,
                    const GridRange& whole, const char* extra) {
  const Vec3<T> o = spec.origin(), h = spec.spacing();
  xml << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"" << type << "\" version=\"1.0\" byte_order=\""
      << (host_is_little_endian() ? "LittleEndian" : "BigEndian") << "\" header_type=\"UInt64\">\n"
      << "  <" << type << " WholeExtent=\"" << vtk_extent(whole) << '"' << extra << " Origin=\""
      << double(o.x) << ' ' << double(o.y) << ' ' << double(o.z) << "\" Spacing=\"" << double(h.x)
      << ' ' << double(h.y) << ' ' << double(h.z) << "\">\n";
}

inline const char* vtk_type(DType d) noexcept {
  return d == DType::float32 ? "Float32" : "Float64";
}

} // namespace detail

/// Writes VTK XML ImageData (`.vti`) holding the samples `piece` of `spec` (`values`, x fastest
/// within `piece`) under a `WholeExtent` of `whole`, which must contain `piece`: pass the same
/// range for a file that stands on its own, the grid's for a piece of a larger one. One point-data
/// array `opt.name`, raw binary appended data (UInt64 header). `Origin` is the grid's first sample
/// and `Spacing` the sample spacing, so a piece lands where it belongs. Atomic. Errors:
/// `invalid_argument`, `io`.
template <class T>
Result<Ok> write_vti_piece(const std::string& path, const GridSpec<T>& spec, const GridRange& whole,
                           const GridRange& piece, Span<const T> values,
                           const WriteGridOptions& opt = {}) {
  if (auto ok = whole.validate(spec); !ok) return ok;
  if (auto ok = piece.validate(spec); !ok) return ok;
  for (int a = 0; a < 3; ++a)
    if (piece.lo[a] < whole.lo[a] || piece.hi[a] > whole.hi[a])
      return make_error(ErrorCode::invalid_argument, path, ": the piece's extent ",
                        detail::vtk_extent(piece), " is not inside the whole extent ",
                        detail::vtk_extent(whole));
  if (values.size() != piece.size())
    return make_error(ErrorCode::invalid_argument, "the piece has ", piece.size(), " samples but ",
                      values.size(), " values were given");
  auto xml = detail::number_stream();
  detail::vtk_image_head(xml, "ImageData", spec, whole, "");
  xml << "    <Piece Extent=\"" << detail::vtk_extent(piece) << "\">\n"
      << "      <PointData Scalars=\"" << detail::xml_escape(opt.name) << "\">\n"
      << "        <DataArray type=\"" << detail::vtk_type(opt.dtype) << "\" Name=\""
      << detail::xml_escape(opt.name)
      << "\" NumberOfComponents=\"1\" format=\"appended\" offset=\"0\"/>\n"
      << "      </PointData>\n"
      << "      <CellData/>\n"
      << "    </Piece>\n"
      << "  </ImageData>\n"
      << "  <AppendedData encoding=\"raw\">\n   _";
  detail::AtomicFile f(path);
  if (!f.is_open()) return f.open_error();
  auto& os = f.stream();
  const std::string head = xml.str();
  os.write(head.data(), std::streamsize(head.size()));
  const std::uint64_t nbytes = std::uint64_t(values.size()) * dtype_size(opt.dtype);
  os.write(reinterpret_cast<const char*>(&nbytes), sizeof nbytes);
  detail::write_values(os, values, opt.dtype);
  const std::string tail = "\n  </AppendedData>\n</VTKFile>\n";
  os.write(tail.data(), std::streamsize(tail.size()));
  if (auto ok = f.close(); !ok) return ok;
  return f.commit();
}

/// Writes a grid as VTK XML ImageData (`.vti`): `write_vti_piece` of the whole grid.
template <class T>
Result<Ok> write_vti(const std::string& path, const GridSpec<T>& spec, Span<const T> values,
                     const WriteGridOptions& opt = {}) {
  if (auto ok = detail::check_grid_values(spec, values.size()); !ok) return ok;
  const GridRange all = GridRange::all(spec);
  return write_vti_piece(path, spec, all, all, values, opt);
}

/// One piece named by a `.pvti`: its samples and its file, relative to the `.pvti`'s folder.
struct PvtiPiece {
  GridRange extent;
  std::string source;
};

/// Writes the parallel VTK ImageData file (`.pvti`) of `spec` assembling `pieces` (each written
/// by `write_vti_piece`; VTK pieces must share their boundary samples, or ParaView shows gaps).
/// Ghost level 0, one point-data array `opt.name`. Atomic. Errors: `invalid_argument`, `io`.
template <class T>
Result<Ok> write_pvti(const std::string& path, const GridSpec<T>& spec,
                      const std::vector<PvtiPiece>& pieces, const WriteGridOptions& opt = {}) {
  if (auto ok = spec.validate(); !ok) return ok;
  for (const PvtiPiece& p : pieces)
    if (auto ok = p.extent.validate(spec); !ok) return ok;
  auto xml = detail::number_stream();
  detail::vtk_image_head(xml, "PImageData", spec, GridRange::all(spec), " GhostLevel=\"0\"");
  xml << "    <PPointData Scalars=\"" << detail::xml_escape(opt.name) << "\">\n"
      << "      <PDataArray type=\"" << detail::vtk_type(opt.dtype) << "\" Name=\""
      << detail::xml_escape(opt.name) << "\" NumberOfComponents=\"1\"/>\n"
      << "    </PPointData>\n";
  for (const PvtiPiece& p : pieces)
    xml << "    <Piece Extent=\"" << detail::vtk_extent(p.extent) << "\" Source=\""
        << detail::xml_escape(p.source) << "\"/>\n";
  xml << "  </PImageData>\n</VTKFile>\n";
  detail::AtomicFile f(path);
  if (!f.is_open()) return f.open_error();
  const std::string text = xml.str();
  f.stream().write(text.data(), std::streamsize(text.size()));
  if (auto ok = f.close(); !ok) return ok;
  return f.commit();
}

} // namespace ebgeom

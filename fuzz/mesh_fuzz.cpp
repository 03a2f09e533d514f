// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// libFuzzer target for format detection + every reader (`parse_mesh`), and for the writers:
// whatever reads back must encode and read back to the same mesh (PLY and OBJ keep numbering).
#include "fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ebgeom;
  const io::ByteView b = fuzz::view(data, size);
  io::ReadOptions opt = fuzz::fuzz_options();
  opt.stl_vertices = size % 2 ? io::StlVertices::keep : io::StlVertices::weld_exact;
  auto r = io::parse_mesh<double>(b, opt);
  fuzz::check_result(r);
  if (!r.has_value()) return 0;
  for (io::MeshFormat f :
       {io::MeshFormat::ply, io::MeshFormat::obj, io::MeshFormat::off, io::MeshFormat::vtk})
    for (io::Encoding e : {io::Encoding::binary, io::Encoding::ascii}) {
      io::WriteOptions w;
      w.format = f;
      w.encoding = e;
      auto bytes = io::encode_mesh(*r, w);
      fuzz::check(bytes.has_value(), "a mesh that was read can be written");
      io::ReadOptions again = opt;
      again.format = f; // the size rule could take written bytes for a binary STL
      auto back = io::parse_mesh<double>(*bytes, again);
      fuzz::check(back.has_value() && *back == *r, "what is written reads back identically");
    }
  return 0;
}

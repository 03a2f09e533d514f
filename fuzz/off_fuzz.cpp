// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// libFuzzer target for the OFF reader (ASCII and binary) (float and double).
#include "fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ebgeom;
  const io::ByteView b = fuzz::view(data, size);
  const io::ReadOptions opt = fuzz::fuzz_options();
  fuzz::check_result(io::parse_off<float>(b, opt));
  fuzz::check_result(io::parse_off<double>(b, opt));
  return 0;
}

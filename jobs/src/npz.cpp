// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/jobs/npz.hpp"

#include <zlib.h>

#include <algorithm>
#include <limits>

namespace ebgeom::jobs {

namespace {

// ZIP numbers are little-endian whatever the host (APPNOTE 4.4).
void put(std::string& s, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) s += char((v >> (8 * i)) & 0xff);
}

std::uint32_t crc_of(std::uint32_t crc, const void* data, std::uint64_t n) {
  const auto* p = static_cast<const Bytef*>(data);
  // zlib's length type may be 32 bits wide: feed it in pieces.
  constexpr std::uint64_t piece = std::uint64_t(1) << 30;
  while (n > 0) {
    const std::uint64_t k = std::min(n, piece);
    crc = std::uint32_t(crc32_z(crc, p, z_size_t(k)));
    p += k;
    n -= k;
  }
  return crc;
}

constexpr std::uint64_t u32_max = 0xffffffffu; // a field holding it defers to the ZIP64 record
constexpr std::uint16_t dos_date = (0 << 9) | (1 << 5) | 1; // 1980-01-01
constexpr std::uint16_t dos_time = 0;
constexpr std::uint32_t unix_file_0644 = 0100644u << 16; // external attributes, made by Unix

} // namespace

Result<std::uint64_t> write_npz(const std::string& path, const std::vector<NpzMember>& members,
                                const NpzOptions& opt) {
  const bool always = opt.zip64 == Zip64::always;
  AtomicFile f(path);
  if (!f.is_open()) return f.open_error();
  auto& os = f.stream();
  std::uint64_t at = 0;
  auto write = [&](const void* p, std::uint64_t n) {
    os.write(static_cast<const char*>(p), std::streamsize(n));
    at += n;
  };
  std::string central;
  for (const NpzMember& m : members) {
    const std::string name = m.name + ".npy";
    const std::uint64_t size = m.header.size() + m.bytes;
    const std::uint32_t crc = crc_of(crc_of(0, m.header.data(), m.header.size()), m.data, m.bytes);
    const std::uint64_t offset = at;
    const bool big = always || size >= u32_max;
    const bool far = always || offset >= u32_max;
    const int version = big || far ? 45 : 20; // 4.5: ZIP64; 2.0: plain
    std::string local;
    put(local, 0x04034b50, 4);
    put(local, version, 2);
    put(local, 0, 2); // flags
    put(local, 0, 2); // method: stored
    put(local, dos_time, 2);
    put(local, dos_date, 2);
    put(local, crc, 4);
    put(local, big ? u32_max : size, 4); // compressed size
    put(local, big ? u32_max : size, 4); // uncompressed size
    put(local, name.size(), 2);
    put(local, big ? 20 : 0, 2); // extra field length
    local += name;
    if (big) { // a local ZIP64 record holds both sizes
      put(local, 0x0001, 2);
      put(local, 16, 2);
      put(local, size, 8);
      put(local, size, 8);
    }
    write(local.data(), local.size());
    write(m.header.data(), m.header.size());
    write(m.data, m.bytes);

    std::string extra; // the central ZIP64 record: only the fields set to 0xffffffff, in order
    if (big) {
      put(extra, size, 8);
      put(extra, size, 8);
    }
    if (far) put(extra, offset, 8);
    put(central, 0x02014b50, 4);
    put(central, (3 << 8) | version, 2); // made by: Unix, spec version
    put(central, version, 2);
    put(central, 0, 2);
    put(central, 0, 2);
    put(central, dos_time, 2);
    put(central, dos_date, 2);
    put(central, crc, 4);
    put(central, big ? u32_max : size, 4);
    put(central, big ? u32_max : size, 4);
    put(central, name.size(), 2);
    put(central, extra.empty() ? 0 : extra.size() + 4, 2);
    put(central, 0, 2); // comment length
    put(central, 0, 2); // disk number
    put(central, 0, 2); // internal attributes
    put(central, unix_file_0644, 4);
    put(central, far ? u32_max : offset, 4);
    central += name;
    if (!extra.empty()) {
      put(central, 0x0001, 2);
      put(central, extra.size(), 2);
      central += extra;
    }
  }
  const std::uint64_t cd_offset = at, cd_size = central.size(), count = members.size();
  write(central.data(), central.size());
  const bool zip64_end = always || count >= 0xffff || cd_offset >= u32_max || cd_size >= u32_max;
  std::string end;
  if (zip64_end) {
    const std::uint64_t record = at;
    put(end, 0x06064b50, 4);
    put(end, 44, 8); // size of the rest of this record
    put(end, (3 << 8) | 45, 2);
    put(end, 45, 2);
    put(end, 0, 4); // this disk
    put(end, 0, 4); // disk of the central directory
    put(end, count, 8);
    put(end, count, 8);
    put(end, cd_size, 8);
    put(end, cd_offset, 8);
    put(end, 0x07064b50, 4); // locator
    put(end, 0, 4);
    put(end, record, 8);
    put(end, 1, 4); // disks
  }
  put(end, 0x06054b50, 4);
  put(end, 0, 2);
  put(end, 0, 2);
  put(end, zip64_end ? 0xffff : count, 2);
  put(end, zip64_end ? 0xffff : count, 2);
  put(end, zip64_end ? u32_max : cd_size, 4);
  put(end, zip64_end ? u32_max : cd_offset, 4);
  put(end, 0, 2); // comment length
  write(end.data(), end.size());
  if (auto ok = f.close(); !ok) return ok.error();
  if (auto ok = f.commit(); !ok) return ok.error();
  return at;
}

} // namespace ebgeom::jobs

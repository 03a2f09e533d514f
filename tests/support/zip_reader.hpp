// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// A small reader of ZIP archives of stored (uncompressed) entries, with ZIP64, and of the .npy
// arrays inside a NumPy .npz, written from the ZIP specification (APPNOTE 4.3, 4.5) independently
// of the tool's writer. Every structure is checked (signatures, sizes, offsets, the local header
// against the central one) and every entry's CRC-32 is recomputed with zlib.

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace ebgeom::clitest {

struct ZipEntry {
  std::string data;
  std::uint32_t crc = 0;
  bool zip64 = false; // sizes or offset came from a ZIP64 extra field
};

struct Zip {
  std::map<std::string, ZipEntry> entries;
  std::vector<std::string> order; // names in central-directory order
  bool zip64_end = false;         // a ZIP64 end of central directory record was present
  bool ok = false;
};

inline std::uint64_t le(const std::string& b, std::uint64_t at, int n) {
  std::uint64_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = v << 8 | std::uint8_t(b[std::size_t(at) + std::size_t(i)]);
  return v;
}

/// Parses `b` as a ZIP archive of stored entries; adds a test failure (and returns ok = false) on
/// anything malformed or unexpected.
inline Zip read_zip(const std::string& b) {
  Zip z;
  const bool failed_before = ::testing::Test::HasFailure(); // z.ok speaks of this archive only
  constexpr std::uint64_t ff32 = 0xffffffffu;
  if (b.size() < 22) {
    ADD_FAILURE() << "zip: too short";
    return z;
  }
  // The end record has no comment here, so it is the last 22 bytes.
  const std::uint64_t eocd = b.size() - 22;
  if (le(b, eocd, 4) != 0x06054b50) {
    ADD_FAILURE() << "zip: no end of central directory record at the end";
    return z;
  }
  EXPECT_EQ(le(b, eocd + 20, 2), 0u) << "comment";
  std::uint64_t count = le(b, eocd + 10, 2), cd_size = le(b, eocd + 12, 4),
                cd_off = le(b, eocd + 16, 4);
  EXPECT_EQ(le(b, eocd + 8, 2), count);
  std::uint64_t cd_end = eocd;
  if (count == 0xffff || cd_size == ff32 || cd_off == ff32) {
    z.zip64_end = true;
    if (eocd < 20 + 56 || le(b, eocd - 20, 4) != 0x07064b50) {
      ADD_FAILURE() << "zip: ZIP64 values without a ZIP64 locator";
      return z;
    }
    const std::uint64_t rec = le(b, eocd - 20 + 8, 8);
    EXPECT_EQ(le(b, eocd - 20 + 16, 4), 1u) << "disks";
    if (rec + 56 != eocd - 20 || le(b, rec, 4) != 0x06064b50) {
      ADD_FAILURE() << "zip: bad ZIP64 end of central directory record";
      return z;
    }
    EXPECT_EQ(le(b, rec + 4, 8), 44u);
    count = le(b, rec + 32, 8);
    EXPECT_EQ(le(b, rec + 24, 8), count);
    cd_size = le(b, rec + 40, 8);
    cd_off = le(b, rec + 48, 8);
    cd_end = rec;
  }
  if (cd_off + cd_size != cd_end) {
    ADD_FAILURE() << "zip: central directory [" << cd_off << ", +" << cd_size
                  << ") does not end at the end records (" << cd_end << ")";
    return z;
  }
  std::uint64_t p = cd_off, next_local = 0;
  for (std::uint64_t e = 0; e < count; ++e) {
    if (p + 46 > cd_end || le(b, p, 4) != 0x02014b50) {
      ADD_FAILURE() << "zip: bad central header " << e;
      return z;
    }
    EXPECT_EQ(le(b, p + 8, 2), 0u) << "flags";
    EXPECT_EQ(le(b, p + 10, 2), 0u) << "method: stored";
    const std::uint32_t crc = std::uint32_t(le(b, p + 16, 4));
    std::uint64_t csize = le(b, p + 20, 4), usize = le(b, p + 24, 4);
    const std::uint64_t nlen = le(b, p + 28, 2), xlen = le(b, p + 30, 2), clen = le(b, p + 32, 2);
    std::uint64_t off = le(b, p + 42, 4);
    const std::string name = b.substr(std::size_t(p + 46), std::size_t(nlen));
    bool zip64 = false;
    for (std::uint64_t x = p + 46 + nlen; x + 4 <= p + 46 + nlen + xlen;) {
      const std::uint64_t id = le(b, x, 2), len = le(b, x + 2, 2);
      if (id == 1) {
        zip64 = true;
        std::uint64_t f = x + 4;
        if (usize == ff32) usize = le(b, f, 8), f += 8;
        if (csize == ff32) csize = le(b, f, 8), f += 8;
        if (off == ff32) off = le(b, f, 8), f += 8;
        EXPECT_EQ(f, x + 4 + len) << name << ": ZIP64 field length";
      }
      x += 4 + len;
    }
    EXPECT_EQ(csize, usize) << name;
    // Entries follow each other with nothing in between, the first at byte 0.
    EXPECT_EQ(off, next_local) << name;
    if (off + 30 > cd_off || le(b, off, 4) != 0x04034b50) {
      ADD_FAILURE() << name << ": bad local header";
      return z;
    }
    EXPECT_EQ(le(b, off + 8, 2), 0u) << name << ": local method";
    EXPECT_EQ(le(b, off + 14, 4), crc) << name << ": local CRC";
    const std::uint64_t lnlen = le(b, off + 26, 2), lxlen = le(b, off + 28, 2);
    EXPECT_EQ(b.substr(std::size_t(off + 30), std::size_t(lnlen)), name);
    std::uint64_t lc = le(b, off + 18, 4), lu = le(b, off + 22, 4);
    if (lc == ff32 && lu == ff32) { // both sizes in the local ZIP64 field
      const std::uint64_t x = off + 30 + lnlen;
      EXPECT_EQ(le(b, x, 2), 1u) << name;
      EXPECT_EQ(le(b, x + 2, 2), 16u) << name;
      lu = le(b, x + 4, 8);
      lc = le(b, x + 12, 8);
    }
    EXPECT_EQ(lc, csize) << name;
    EXPECT_EQ(lu, usize) << name;
    const std::uint64_t data = off + 30 + lnlen + lxlen;
    if (data + usize > cd_off) {
      ADD_FAILURE() << name << ": data runs into the central directory";
      return z;
    }
    ZipEntry ent;
    ent.data = b.substr(std::size_t(data), std::size_t(usize));
    ent.crc = crc;
    ent.zip64 = zip64;
    uLong c = crc32(0L, Z_NULL, 0);
    for (std::size_t s = 0; s < ent.data.size(); s += std::size_t(1) << 30) {
      const std::size_t n = std::min(ent.data.size() - s, std::size_t(1) << 30);
      c = crc32(c, reinterpret_cast<const Bytef*>(ent.data.data() + s), uInt(n));
    }
    EXPECT_EQ(std::uint32_t(c), crc) << name << ": CRC-32";
    next_local = data + usize;
    z.order.push_back(name);
    z.entries[name] = std::move(ent);
    p += 46 + nlen + xlen + clen;
  }
  EXPECT_EQ(next_local, cd_off) << "bytes between the last entry and the central directory";
  EXPECT_EQ(p, cd_end);
  z.ok = failed_before || !::testing::Test::HasFailure();
  return z;
}

/// A .npy array: its type string, shape and raw data bytes.
struct NpyArray {
  std::string descr;
  std::vector<std::size_t> shape;
  std::string data;
  std::size_t count() const {
    std::size_t n = 1;
    for (std::size_t d : shape) n *= d;
    return n;
  }
  template <class V> V at(std::size_t i) const {
    V v;
    std::memcpy(&v, data.data() + i * sizeof(V), sizeof(V));
    return v;
  }
};

/// Parses .npy bytes (format 1.0, C order); fails the test on anything else.
inline NpyArray parse_npy(const std::string& b, const std::string& what) {
  NpyArray a;
  if (b.size() < 10 || b.compare(0, 8, std::string("\x93NUMPY\x01\x00", 8)) != 0) {
    ADD_FAILURE() << what << ": not a .npy 1.0 array";
    return a;
  }
  const std::size_t hlen = std::size_t(le(b, 8, 2));
  EXPECT_EQ((10 + hlen) % 64, 0u) << what;
  const std::string h = b.substr(10, hlen);
  EXPECT_NE(h.find("'fortran_order': False"), std::string::npos) << what << h;
  const auto d = h.find("'descr': '");
  a.descr = h.substr(d + 10, h.find('\'', d + 10) - d - 10);
  const auto s = h.find("'shape': (");
  std::istringstream is(h.substr(s + 10, h.find(')', s) - s - 10));
  std::string tok;
  while (std::getline(is, tok, ','))
    if (tok.find_first_not_of(' ') != std::string::npos) a.shape.push_back(std::stoul(tok));
  a.data = b.substr(10 + hlen);
  return a;
}

/// The arrays of an `.npz` archive's bytes by member name (without `.npy`); fails the test on a
/// malformed archive (`what` names it).
inline std::map<std::string, NpyArray> read_npz_bytes(const std::string& b,
                                                      const std::string& what) {
  std::map<std::string, NpyArray> m;
  const Zip z = read_zip(b);
  EXPECT_TRUE(z.ok) << what;
  for (const auto& [name, e] : z.entries)
    m[name.substr(0, name.size() - 4)] = parse_npy(e.data, name);
  return m;
}

} // namespace ebgeom::clitest

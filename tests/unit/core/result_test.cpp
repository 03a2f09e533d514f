// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/core/result.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "ebgeom/core/parallel.hpp"

using namespace ebgeom;

TEST(Result, ValueAndError) {
  Result<int> ok = 3;
  ASSERT_TRUE(ok.has_value());
  EXPECT_EQ(ok.value(), 3);
  Result<int> bad = make_error(ErrorCode::invalid_argument, "radius ", -1, " must be > 0");
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().code, ErrorCode::invalid_argument);
  EXPECT_EQ(bad.error().message, "radius -1 must be > 0");
  EXPECT_EQ(bad.value_or(7), 7);
  try {
    (void)bad.value();
    FAIL() << "value() on an error must throw";
  } catch (const Exception& e) {
    EXPECT_EQ(e.code(), ErrorCode::invalid_argument);
    EXPECT_STREQ(e.what(), "radius -1 must be > 0");
  }
}

TEST(Result, ParseErrorFormatsLocation) {
  ParseError e{ErrorCode::bad_index, "vertex index 9 >= vertex count 3", "m.obj", 120, 12};
  EXPECT_EQ(e.what(), "m.obj: line 12: vertex index 9 >= vertex count 3");
  e.line = 0;
  EXPECT_EQ(e.what(), "m.obj: byte 120: vertex index 9 >= vertex count 3");
  Result<int> r = e; // converts through Error
  EXPECT_EQ(r.error().code, ErrorCode::bad_index);
  Result<int, ParseError> rp = e;
  EXPECT_EQ(rp.error().byte_offset, 120u);
}

TEST(Parallel, CoversEveryIndexOnceForAnyThreadCount) {
  for (int threads : {1, 2, 3, 8}) {
    std::vector<std::atomic<int>> hits(10007);
    ExecOptions opt;
    opt.threads = threads;
    opt.serial_threshold = 1;
    parallel_for(
        0, hits.size(), 97,
        [&](std::size_t b, std::size_t e) {
          for (std::size_t i = b; i < e; ++i) hits[i].fetch_add(1);
        },
        opt);
    for (auto& h : hits) ASSERT_EQ(h.load(), 1) << "threads=" << threads;
  }
}

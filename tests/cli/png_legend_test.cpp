// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// The PNG slice's legend: no drawn text; the numbers in the PNG's tEXt chunks (read with libpng)
// and in --json; a colour bar, the zero contour and a scale bar of a round length.
#include <gtest/gtest.h>
#include <png.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>

#include "cli_support.hpp"

using namespace ebgeom::clitest;

namespace {

std::map<std::string, std::string> png_text_chunks(const std::string& path) {
  std::map<std::string, std::string> out;
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return out;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(f);
    ADD_FAILURE() << path << ": libpng failed";
    return out;
  }
  png_init_io(png, f);
  png_read_info(png, info);
  png_textp text = nullptr;
  const int n = png_get_text(png, info, &text, nullptr);
  for (int i = 0; i < n; ++i) out[text[i].key] = std::string(text[i].text, text[i].text_length);
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(f);
  return out;
}

} // namespace

TEST(PngLegend, InTextChunksAndJson) {
  const std::string dir = test_dir();
  std::ofstream(dir + "/s.json") << R"({"type": "sphere", "radius": 1})";
  const RunResult r = run("sdf '" + dir + "/s.json' -o '" + dir + "/s.npy' --res 9 7 5 --png '" +
                          dir + "/s.png' --slice x=0.25 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& leg = j["png"]["legend"];
  // colour scale: the slice's most negative and most positive values
  const Npy npy = read_npy(dir + "/s.npy");
  const auto& sl = leg["slice"];
  EXPECT_EQ(sl["axis"], "x");
  EXPECT_EQ(sl["count"], 9);
  const std::size_t i = sl["index"];
  EXPECT_EQ(i, 2u); // x = 0.25 of [-1.2, 1.2]: sample 2 of 9 (x = -0.533)
  double lo = 0, hi = 0;
  for (std::size_t k = 0; k < 5; ++k)
    for (std::size_t jj = 0; jj < 7; ++jj) {
      const double v = npy.data[i + 9 * (jj + 7 * k)];
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  EXPECT_NEAR(leg["colour_min"].get<double>(), lo, 1e-12);
  EXPECT_NEAR(leg["colour_max"].get<double>(), hi, 1e-12);
  // scale bar: 1, 2 or 5 times a power of ten; its pixels at 512 px for the 2.4-unit extent
  const double sb = leg["scale_bar"];
  const double mant = sb / std::pow(10.0, std::floor(std::log10(sb) + 1e-9));
  EXPECT_TRUE(std::abs(mant - 1) < 1e-9 || std::abs(mant - 2) < 1e-9 || std::abs(mant - 5) < 1e-9)
      << sb;
  EXPECT_EQ(leg["scale_bar_pixels"].get<int>(), int(std::lround(sb * 512 / 2.4)));

  const auto text = png_text_chunks(dir + "/s.png");
  ASSERT_TRUE(text.count("Title")) << text.size();
  EXPECT_NE(text.at("Title").find("x = -0.5333 (plane 3 of 9)"), std::string::npos)
      << text.at("Title");
  EXPECT_NEAR(std::stod(text.at("ebgeom:colour_min")), lo, 1e-3 * std::abs(lo));
  EXPECT_NEAR(std::stod(text.at("ebgeom:colour_max")), hi, 1e-3 * std::abs(hi));
  EXPECT_NEAR(std::stod(text.at("ebgeom:scale_bar")), sb, 1e-12);
  EXPECT_NE(text.at("Description").find("blue inside"), std::string::npos);
  EXPECT_EQ(text.at("Software").rfind("ebgeom ", 0), 0u);

  // The picture: the scale bar's row under the plot is black for exactly its pixels; the colour
  // bar runs from dark blue to dark red; the zero contour is drawn (black pixels in the plot).
  const Png png = read_png(dir + "/s.png");
  ASSERT_EQ(png.width, unsigned(j["png"]["width"].get<int>()));
  auto px = [&](int x, int y) {
    const std::uint8_t* p = &png.rgb[(std::size_t(y) * png.width + std::size_t(x)) * 3];
    return std::array<int, 3>{p[0], p[1], p[2]};
  };
  const int margin = 16, ph = 512, sy = margin + ph + 8;
  int run_len = 0;
  while (px(margin + run_len, sy + 5) == std::array<int, 3>{0, 0, 0}) ++run_len;
  EXPECT_EQ(run_len, leg["scale_bar_pixels"].get<int>());
  const int by = sy + 10 + 10 + 9; // middle row of the colour bar
  const auto left = px(margin + 2, by), right = px(margin + 509, by), mid = px(margin + 250, by);
  EXPECT_GT(left[2], left[0] + 40) << "blue at the left end";
  EXPECT_GT(right[0], right[2] + 40) << "red at the right end";
  EXPECT_GT(mid[0], 220);
  EXPECT_GT(mid[2], 220);
  int contour = 0;
  for (int y = margin; y < margin + ph; ++y)
    for (int x = margin; x < margin + 512; ++x) contour += px(x, y) == std::array<int, 3>{0, 0, 0};
  EXPECT_GT(contour, 500);
  // nothing is drawn below the colour bar (where the text used to be)
  for (unsigned y = unsigned(by + 12); y < png.height; ++y)
    for (unsigned x = 0; x < png.width; ++x)
      ASSERT_EQ(px(int(x), int(y)), (std::array<int, 3>{255, 255, 255})) << x << "," << y;
}

// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "png_slice.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "common.hpp"
#include "ebgeom/eval/write_grid.hpp"

namespace ebgeom::cli {

SliceSpec parse_slice(const std::string& text) {
  SliceSpec s;
  if (text.empty() || (text[0] != 'x' && text[0] != 'y' && text[0] != 'z'))
    fail(exit_usage,
         "--slice: expected x, y or z, optionally =FRACTION (e.g. z=0.5), got '" + text + "'");
  s.axis = text[0] - 'x';
  if (text.size() == 1) return s;
  if (text[1] != '=')
    fail(exit_usage,
         "--slice: expected x, y or z, optionally =FRACTION (e.g. z=0.5), got '" + text + "'");
  const std::string f = text.substr(2);
  char* end = nullptr;
  const double v = std::strtod(f.c_str(), &end);
  if (f.empty() || end != f.c_str() + f.size() || !(v >= 0 && v <= 1))
    fail(exit_usage, "--slice: the fraction must be a number in [0, 1], got '" + f + "'");
  s.fraction = v;
  return s;
}

namespace {

// 5x7 bitmap glyphs ('#' = ink), enough for numbers and the legend's lower-case words.
struct Glyph {
  char c;
  const char* rows[7];
};
const Glyph font[] = {
    {'0', {".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###."}},
    {'1', {"..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'2', {".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####"}},
    {'3', {"#####", "...#.", "..#..", "...#.", "....#", "#...#", ".###."}},
    {'4', {"...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#."}},
    {'5', {"#####", "#....", "####.", "....#", "....#", "#...#", ".###."}},
    {'6', {"..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###."}},
    {'7', {"#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#..."}},
    {'8', {".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###."}},
    {'9', {".###.", "#...#", "#...#", ".####", "....#", "...#.", ".##.."}},
    {'-', {".....", ".....", ".....", "#####", ".....", ".....", "....."}},
    {'+', {".....", "..#..", "..#..", "#####", "..#..", "..#..", "....."}},
    {'.', {".....", ".....", ".....", ".....", ".....", ".##..", ".##.."}},
    {'=', {".....", ".....", "#####", ".....", "#####", ".....", "....."}},
    {'(', {"...#.", "..#..", ".#...", ".#...", ".#...", "..#..", "...#."}},
    {')', {".#...", "..#..", "...#.", "...#.", "...#.", "..#..", ".#..."}},
    {'/', {".....", "....#", "...#.", "..#..", ".#...", "#....", "....."}},
    {':', {".....", ".##..", ".##..", ".....", ".##..", ".##..", "....."}},
    {'<', {"...#.", "..#..", ".#...", "#....", ".#...", "..#..", "...#."}},
    {'>', {".#...", "..#..", "...#.", "....#", "...#.", "..#..", ".#..."}},
    {'a', {".....", ".....", ".###.", "....#", ".####", "#...#", ".####"}},
    {'b', {"#....", "#....", "#.##.", "##..#", "#...#", "#...#", "####."}},
    {'c', {".....", ".....", ".###.", "#....", "#....", "#...#", ".###."}},
    {'d', {"....#", "....#", ".##.#", "#..##", "#...#", "#...#", ".####"}},
    {'e', {".....", ".....", ".###.", "#...#", "#####", "#....", ".###."}},
    {'f', {"..##.", ".#..#", ".#...", "###..", ".#...", ".#...", ".#..."}},
    {'g', {".....", ".####", "#...#", "#...#", ".####", "....#", ".###."}},
    {'h', {"#....", "#....", "#.##.", "##..#", "#...#", "#...#", "#...#"}},
    {'i', {"..#..", ".....", ".##..", "..#..", "..#..", "..#..", ".###."}},
    {'k', {"#....", "#....", "#..#.", "#.#..", "##...", "#.#..", "#..#."}},
    {'l', {".##..", "..#..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'m', {".....", ".....", "##.#.", "#.#.#", "#.#.#", "#...#", "#...#"}},
    {'n', {".....", ".....", "#.##.", "##..#", "#...#", "#...#", "#...#"}},
    {'o', {".....", ".....", ".###.", "#...#", "#...#", "#...#", ".###."}},
    {'p', {".....", ".....", "####.", "#...#", "####.", "#....", "#...."}},
    {'q', {".....", ".....", ".####", "#...#", ".####", "....#", "....#"}},
    {'r', {".....", ".....", "#.##.", "##..#", "#....", "#....", "#...."}},
    {'s', {".....", ".....", ".###.", "#....", ".###.", "....#", "####."}},
    {'t', {".#...", ".#...", "###..", ".#...", ".#...", ".#..#", "..##."}},
    {'u', {".....", ".....", "#...#", "#...#", "#...#", "#..##", ".##.#"}},
    {'v', {".....", ".....", "#...#", "#...#", "#...#", ".#.#.", "..#.."}},
    {'w', {".....", ".....", "#...#", "#...#", "#.#.#", "#.#.#", ".#.#."}},
    {'x', {".....", ".....", "#...#", ".#.#.", "..#..", ".#.#.", "#...#"}},
    {'y', {".....", ".....", "#...#", "#...#", ".####", "....#", ".###."}},
    {'z', {".....", ".....", "#####", "...#.", "..#..", ".#...", "#####"}},
};

struct Rgb {
  std::uint8_t r, g, b;
};

class Image {
 public:
  Image(int w, int h) : w_(w), h_(h), px_(std::size_t(w) * h * 3, 255) {}
  int width() const { return w_; }
  int height() const { return h_; }
  void set(int x, int y, Rgb c) {
    if (x < 0 || y < 0 || x >= w_ || y >= h_) return;
    std::uint8_t* p = &px_[(std::size_t(y) * w_ + x) * 3];
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
  }
  const std::uint8_t* row(int y) const { return &px_[std::size_t(y) * w_ * 3]; }
  static constexpr int scale = 2, advance = 6 * scale, line = 9 * scale;
  static int text_width(const std::string& s) { return int(s.size()) * advance; }
  void text(int x, int y, const std::string& s, Rgb c) {
    for (char ch : s) {
      for (const Glyph& g : font)
        if (g.c == ch)
          for (int r = 0; r < 7; ++r)
            for (int q = 0; q < 5; ++q)
              if (g.rows[r][q] == '#')
                for (int a = 0; a < scale; ++a)
                  for (int b = 0; b < scale; ++b) set(x + q * scale + b, y + r * scale + a, c);
      x += advance;
    }
  }

 private:
  int w_, h_;
  std::vector<std::uint8_t> px_;
};

Rgb mix(Rgb a, Rgb b, double t) {
  auto m = [t](int x, int y) { return std::uint8_t(std::lround(x + (y - x) * t)); };
  return {m(a.r, b.r), m(a.g, b.g), m(a.b, b.b)};
}

// Diverging map (ColorBrewer RdBu end points): t in [-1, 1], blue inside, red outside.
Rgb colour(double t) {
  const Rgb white{247, 247, 247};
  const Rgb in_mid{146, 197, 222}, in_end{5, 48, 97};
  const Rgb out_mid{244, 165, 130}, out_end{103, 0, 31};
  const double a = std::min(1.0, std::abs(t));
  if (t < 0) return a < 0.5 ? mix(white, in_mid, a * 2) : mix(in_mid, in_end, a * 2 - 1);
  return a < 0.5 ? mix(white, out_mid, a * 2) : mix(out_mid, out_end, a * 2 - 1);
}

Rgb shade(Rgb c, double f) {
  return {std::uint8_t(c.r * f), std::uint8_t(c.g * f), std::uint8_t(c.b * f)};
}

std::string number(double v) {
  char buf[32];
  const double a = std::abs(v);
  if (a != 0 && (a < 1e-3 || a >= 1e5))
    std::snprintf(buf, sizeof buf, "%.2e", v);
  else
    std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

void png_write_to_stream(png_structp png, png_bytep data, png_size_t n) {
  auto* os = static_cast<std::ostream*>(png_get_io_ptr(png));
  os->write(reinterpret_cast<const char*>(data), std::streamsize(n));
}
void png_flush_stream(png_structp png) { static_cast<std::ostream*>(png_get_io_ptr(png))->flush(); }

} // namespace

PngInfo write_png_slice(const std::string& path, const SliceData& s) {
  if (s.width == 0 || s.height == 0 || s.values.size() != s.width * s.height)
    fail(exit_failure, path + ": empty slice");
  // Plot size: the longer side 512 px, aspect from the physical extent.
  const double lu = double(s.width) * s.du, lv = double(s.height) * s.dv;
  const double px_per_unit = 512.0 / std::max(lu, lv);
  const int pw = std::max(16, std::min(4096, int(std::lround(lu * px_per_unit))));
  const int ph = std::max(16, std::min(4096, int(std::lround(lv * px_per_unit))));
  // Separate scales inside and outside, so both sides use the full colour range.
  double m_in = 0, m_out = 0;
  for (double v : s.values)
    if (std::isfinite(v)) (v < 0 ? m_in : m_out) = std::max(v < 0 ? m_in : m_out, std::abs(v));
  if (m_in == 0) m_in = m_out > 0 ? m_out : 1;
  if (m_out == 0) m_out = m_in;
  const double m = std::max(m_in, m_out);

  // Bilinear interpolation of the samples at every plot pixel (v grows upwards).
  std::vector<double> field(std::size_t(pw) * ph);
  for (int y = 0; y < ph; ++y) {
    const double fv =
        std::clamp((ph - 1 - y + 0.5) / ph * s.height - 0.5, 0.0, double(s.height - 1));
    const std::size_t v0 = std::size_t(fv), v1 = std::min(v0 + 1, s.height - 1);
    const double tv = fv - double(v0);
    for (int x = 0; x < pw; ++x) {
      const double fu = std::clamp((x + 0.5) / pw * s.width - 0.5, 0.0, double(s.width - 1));
      const std::size_t u0 = std::size_t(fu), u1 = std::min(u0 + 1, s.width - 1);
      const double tu = fu - double(u0);
      const double a = s.values[v0 * s.width + u0], b = s.values[v0 * s.width + u1];
      const double c = s.values[v1 * s.width + u0], d = s.values[v1 * s.width + u1];
      field[std::size_t(y) * pw + x] =
          (a * (1 - tu) + b * tu) * (1 - tv) + (c * (1 - tu) + d * tu) * tv;
    }
  }

  const int margin = 16;
  const std::string line1 = "blue inside (s<0)  red outside (s>0)  black s=0";
  char where[128];
  std::snprintf(where, sizeof where, "slice %c=%s (plane %zu/%zu)", s.axis_name,
                number(s.plane).c_str(), s.plane_index + 1, s.plane_count);
  const int text_w = std::max(Image::text_width(line1), Image::text_width(where));
  const int width = std::max(pw, text_w) + 2 * margin;
  const int bar_h = 18;
  const int height = margin + ph + margin + bar_h + 6 + 3 * Image::line + margin;
  Image img(width, height);
  const int x0 = (width - pw) / 2, y0 = margin;
  const double period = m / 8; // faint bands every m/8 of distance
  for (int y = 0; y < ph; ++y)
    for (int x = 0; x < pw; ++x) {
      const double v = field[std::size_t(y) * pw + x];
      if (!std::isfinite(v)) {
        img.set(x0 + x, y0 + y, {128, 128, 128});
        continue;
      }
      const double band = 0.92 + 0.08 * std::cos(2 * M_PI * v / period);
      img.set(x0 + x, y0 + y, shade(colour(v < 0 ? v / m_in : v / m_out), band));
    }
  // Zero level set: a sign change to the right or below.
  const Rgb black{0, 0, 0};
  for (int y = 0; y < ph; ++y)
    for (int x = 0; x < pw; ++x) {
      const double v = field[std::size_t(y) * pw + x];
      const bool neg = v < 0;
      if ((x + 1 < pw && (field[std::size_t(y) * pw + x + 1] < 0) != neg) ||
          (y + 1 < ph && (field[std::size_t(y + 1) * pw + x] < 0) != neg) || v == 0) {
        img.set(x0 + x, y0 + y, black);
        img.set(x0 + x + 1, y0 + y, black);
      }
    }
  // Frame.
  for (int x = -1; x <= pw; ++x) {
    img.set(x0 + x, y0 - 1, {60, 60, 60});
    img.set(x0 + x, y0 + ph, {60, 60, 60});
  }
  for (int y = -1; y <= ph; ++y) {
    img.set(x0 - 1, y0 + y, {60, 60, 60});
    img.set(x0 + pw, y0 + y, {60, 60, 60});
  }
  // Legend: a colour bar from -m to +m with ticks and labels.
  const int bw = width - 2 * margin, bx = margin, by = y0 + ph + margin;
  for (int x = 0; x < bw; ++x) {
    const Rgb c = colour(2.0 * (x + 0.5) / bw - 1.0);
    for (int y = 0; y < bar_h; ++y) img.set(bx + x, by + y, c);
  }
  for (int y = -3; y < bar_h + 3; ++y) {
    img.set(bx, by + y, black);
    img.set(bx + bw / 2, by + y, black);
    img.set(bx + bw - 1, by + y, black);
  }
  const int ty = by + bar_h + 6;
  const Rgb ink{20, 20, 20};
  const std::string lo = number(-m_in), hi = "+" + number(m_out);
  img.text(bx, ty, lo, ink);
  img.text(bx + bw / 2 - Image::text_width("0") / 2, ty, "0", ink);
  img.text(bx + bw - Image::text_width(hi), ty, hi, ink);
  img.text(bx, ty + Image::line, line1, ink);
  img.text(bx, ty + 2 * Image::line, where, ink);

  ebgeom::detail::AtomicFile file(path);
  if (!file.is_open()) fail(exit_output, file.open_error().what());
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_write_struct(&png, &info);
    fail(exit_failure, path + ": libpng initialisation failed");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    fail(exit_output, path + ": libpng failed to write the image");
  }
  png_set_write_fn(png, &file.stream(), png_write_to_stream, png_flush_stream);
  png_set_IHDR(png, info, png_uint_32(img.width()), png_uint_32(img.height()), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < img.height(); ++y) png_write_row(png, const_cast<png_bytep>(img.row(y)));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (auto ok = file.close(); !ok) fail(exit_output, ok.error().what());
  if (auto ok = file.commit(); !ok) fail(exit_output, ok.error().what());
  return {img.width(), img.height()};
}

} // namespace ebgeom::cli

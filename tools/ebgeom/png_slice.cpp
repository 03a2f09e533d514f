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
#include <string>
#include <utility>
#include <vector>

#include "common.hpp"
#include "ebgeom/eval/write_grid.hpp"
#include "ebgeom/version.hpp"

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

  // The scale bar: a round length (1, 2 or 5 times a power of ten) near a quarter of the plot.
  const double target = 0.25 * std::max(lu, lv) * double(pw) / double(std::max(pw, ph));
  const double p10 = std::pow(10.0, std::floor(std::log10(target)));
  double scale_len = p10;
  for (double f : {2.0, 5.0, 10.0})
    if (f * p10 <= target) scale_len = f * p10;
  const int scale_px = std::max(2, int(std::lround(scale_len * px_per_unit)));

  // No text is drawn (the numbers are in the file's tEXt chunks and in --json): the plot, a scale
  // bar under it, and the colour bar with ticks at -inside scale, 0 and +outside scale.
  const int margin = 16, bar_h = 18, scale_h = 10;
  const int width = pw + 2 * margin;
  const int height = margin + ph + 8 + scale_h + 10 + bar_h + margin;
  Image img(width, height);
  const int x0 = margin, y0 = margin;
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
  // Scale bar: scale_px pixels long (scale_len in the input's units), end ticks.
  const int sy = y0 + ph + 8;
  for (int x = 0; x < scale_px; ++x)
    for (int y = 4; y < 7; ++y) img.set(x0 + x, sy + y, black);
  for (int y = 0; y < scale_h; ++y) {
    img.set(x0, sy + y, black);
    img.set(x0 + scale_px - 1, sy + y, black);
  }
  // Colour bar from -m_in (left) through 0 (centre) to +m_out (right), with those three ticks.
  const int bw = pw, bx = x0, by = sy + scale_h + 10;
  for (int x = 0; x < bw; ++x) {
    const Rgb c = colour(2.0 * (x + 0.5) / bw - 1.0);
    for (int y = 0; y < bar_h; ++y) img.set(bx + x, by + y, c);
  }
  for (int y = -3; y < bar_h + 3; ++y) {
    img.set(bx, by + y, black);
    img.set(bx + bw / 2, by + y, black);
    img.set(bx + bw - 1, by + y, black);
  }

  PngInfo out;
  out.width = img.width();
  out.height = img.height();
  out.inside_scale = m_in;
  out.outside_scale = m_out;
  out.scale_bar = scale_len;
  out.scale_bar_pixels = scale_px;
  out.axis = s.axis_name;
  out.plane = s.plane;
  out.plane_index = s.plane_index;
  out.plane_count = s.plane_count;
  // The legend as text, in the file (PNG tEXt chunks: shown by image viewers' "properties").
  char where[128];
  std::snprintf(where, sizeof where, "%c = %s (plane %zu of %zu)", s.axis_name,
                number(s.plane).c_str(), s.plane_index + 1, s.plane_count);
  const std::string colours = "blue inside (S < 0) to white (S = 0) to red outside (S > 0); "
                              "left end of the colour bar " +
                              number(-m_in) + ", centre 0, right end +" + number(m_out) +
                              "; black line: S = 0; faint bands every " + number(period);
  const std::string scale = number(scale_len) + " (input units), the bar under the plot";
  const std::string title = std::string("ebgeom signed distance slice ") + where;
  const std::vector<std::pair<std::string, std::string>> text = {
      {"Title", title},
      {"Software", std::string("ebgeom ") + EBGEOM_VERSION_STRING},
      {"Description", colours},
      {"ebgeom:slice", where},
      {"ebgeom:colour_min", number(-m_in)},
      {"ebgeom:colour_max", number(m_out)},
      {"ebgeom:scale_bar", scale}};

  ebgeom::AtomicFile file(path);
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
  std::vector<png_text> chunks(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    chunks[i].compression = PNG_TEXT_COMPRESSION_NONE;
    chunks[i].key = const_cast<png_charp>(text[i].first.c_str());
    chunks[i].text = const_cast<png_charp>(text[i].second.c_str());
    chunks[i].text_length = text[i].second.size();
  }
  png_set_text(png, info, chunks.data(), int(chunks.size()));
  png_write_info(png, info);
  for (int y = 0; y < img.height(); ++y) png_write_row(png, const_cast<png_bytep>(img.row(y)));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (auto ok = file.close(); !ok) fail(exit_output, ok.error().what());
  if (auto ok = file.commit(); !ok) fail(exit_output, ok.error().what());
  return out;
}

} // namespace ebgeom::cli

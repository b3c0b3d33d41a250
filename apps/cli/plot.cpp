// nephele CLI — the line-chart plotter (see plot.h).
//
// Everything is drawn in pixel space on an 8-bit sRGB canvas. Lines and markers are drawn as
// signed-distance coverage into a float mask, one series at a time, and the mask is then
// composited once in the series' colour, so that a polyline's joints and its markers do not
// darken where they overlap. Text comes from stb_easy_font as axis-aligned quads in 1-px font
// units, filled scaled by an integer factor (so it stays crisp).
#include "plot.h"

#include <stb/stb_image_write.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

#include "nephele/error.h"

// stb_easy_font is a header of static functions, some of which this file does not use.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

namespace nephele::cli {
namespace {

namespace fs = std::filesystem;

constexpr int kMinSize = 64;
constexpr int kMaxSize = 8192;
constexpr int kMaxGridSize = 16384;

// --- colours and canvas ------------------------------------------------------------------

struct Rgb {
  unsigned char r, g, b;
};

constexpr Rgb kFrameColour{70, 70, 70};
constexpr Rgb kGridColour{226, 226, 226};
constexpr Rgb kMinorGridColour{242, 242, 242};
constexpr Rgb kTextColour{30, 30, 30};
constexpr Rgb kLegendBorder{190, 190, 190};
constexpr Rgb kWhite{255, 255, 255};

// Tableau 10: distinct, and readable on white.
constexpr std::array<Rgb, 10> kPalette{{{31, 119, 180},
                                        {255, 127, 14},
                                        {44, 160, 44},
                                        {214, 39, 40},
                                        {148, 103, 189},
                                        {140, 86, 75},
                                        {227, 119, 194},
                                        {127, 127, 127},
                                        {188, 189, 34},
                                        {23, 190, 207}}};

enum class Marker { kCircle, kSquare, kDiamond, kTriangleUp, kTriangleDown };
constexpr std::array<Marker, 5> kMarkers{Marker::kCircle, Marker::kSquare, Marker::kDiamond,
                                         Marker::kTriangleUp, Marker::kTriangleDown};

// A half-open pixel rectangle [x0, x1) x [y0, y1).
struct Box {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  Box intersect(const Box& o) const {
    return {std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
  }
};

// Clamps a real pixel coordinate to an int range without overflow (and NaN to lo).
int clamp_to_int(double v, int lo, int hi) {
  if (!(v > lo)) return lo;
  if (v > hi) return hi;
  return int(v);
}

class Canvas {
 public:
  Canvas(int width, int height)
      : width_(width), height_(height), rgba_(size_t(width) * size_t(height) * 4, 255) {}

  int width() const { return width_; }
  int height() const { return height_; }
  Box bounds() const { return {0, 0, width_, height_}; }

  // Mixes `colour` over the pixel with opacity `alpha` (in [0, 1]); outside pixels are ignored.
  void blend(int x, int y, Rgb colour, float alpha) {
    if (x < 0 || y < 0 || x >= width_ || y >= height_ || !(alpha > 0.0f)) return;
    alpha = std::min(alpha, 1.0f);
    unsigned char* p = &rgba_[(size_t(y) * size_t(width_) + size_t(x)) * 4];
    auto mix = [alpha](unsigned char under, unsigned char over) {
      return static_cast<unsigned char>(std::lround(under + (float(over) - float(under)) * alpha));
    };
    p[0] = mix(p[0], colour.r);
    p[1] = mix(p[1], colour.g);
    p[2] = mix(p[2], colour.b);
  }

  void fill(Box box, Rgb colour, float alpha = 1.0f) {
    box = box.intersect(bounds());
    for (int y = box.y0; y < box.y1; ++y) {
      for (int x = box.x0; x < box.x1; ++x) blend(x, y, colour, alpha);
    }
  }

  // A 1-px rectangle outline just inside `box`.
  void outline(Box box, Rgb colour) {
    fill({box.x0, box.y0, box.x1, box.y0 + 1}, colour);
    fill({box.x0, box.y1 - 1, box.x1, box.y1}, colour);
    fill({box.x0, box.y0, box.x0 + 1, box.y1}, colour);
    fill({box.x1 - 1, box.y0, box.x1, box.y1}, colour);
  }

  const std::vector<unsigned char>& rgba() const { return rgba_; }
  std::vector<unsigned char> take() { return std::move(rgba_); }

 private:
  int width_, height_;
  std::vector<unsigned char> rgba_;
};

// --- antialiased shapes --------------------------------------------------------------------

// Pixel (x, y) has its centre at (x + 0.5, y + 0.5).
struct Point {
  double x, y;
};

// Signed distance from (dx, dy) (relative to the marker centre) to a marker of size r.
double marker_distance(Marker marker, double dx, double dy, double r) {
  constexpr double kSqrt2 = 1.4142135623730951;
  switch (marker) {
    case Marker::kCircle:
      return std::hypot(dx, dy) - r;
    case Marker::kSquare:
      return std::max(std::abs(dx), std::abs(dy)) - 0.85 * r;
    case Marker::kDiamond:
      return (std::abs(dx) + std::abs(dy) - 1.25 * r) / kSqrt2;
    case Marker::kTriangleUp:
    case Marker::kTriangleDown: {
      // Equilateral triangle, circumradius R; the distance to the farthest edge's line.
      const double big_r = 1.3 * r;
      const double y = marker == Marker::kTriangleUp ? dy : -dy;  // y grows downwards
      const double d1 = y;
      const double d2 = 0.8660254037844386 * dx - 0.5 * y;
      const double d3 = -0.8660254037844386 * dx - 0.5 * y;
      return std::max({d1, d2, d3}) - 0.5 * big_r;
    }
  }
  return 0.0;
}

// Coverage in [0, 1] per pixel, accumulated with max() so overlapping shapes of one series
// do not add up.
class Mask {
 public:
  Mask(int width, int height) : width_(width), height_(height), v_(size_t(width) * height) {}

  void clear() {
    std::fill(v_.begin(), v_.end(), 0.0f);
    touched_ = {};
  }

  // A line of width 2 * half_width, with round caps, clipped to `clip`.
  void stroke(Point a, Point b, double half_width, Box clip) {
    const double reach = half_width + 1.0;
    const Box box = Box{clamp_to_int(std::floor(std::min(a.x, b.x) - reach), 0, width_),
                        clamp_to_int(std::floor(std::min(a.y, b.y) - reach), 0, height_),
                        clamp_to_int(std::ceil(std::max(a.x, b.x) + reach), 0, width_),
                        clamp_to_int(std::ceil(std::max(a.y, b.y) + reach), 0, height_)}
                        .intersect(clip);
    const double ex = b.x - a.x, ey = b.y - a.y;
    const double len2 = ex * ex + ey * ey;
    for (int y = box.y0; y < box.y1; ++y) {
      for (int x = box.x0; x < box.x1; ++x) {
        const double px = x + 0.5 - a.x, py = y + 0.5 - a.y;
        const double t = len2 > 0.0 ? std::clamp((px * ex + py * ey) / len2, 0.0, 1.0) : 0.0;
        const double d = std::hypot(px - t * ex, py - t * ey);
        put(x, y, half_width + 0.5 - d);
      }
    }
    touch(box);
  }

  void marker(Point c, Marker marker, double radius, Box clip) {
    const double reach = 1.5 * radius + 1.0;
    const Box box = Box{clamp_to_int(std::floor(c.x - reach), 0, width_),
                        clamp_to_int(std::floor(c.y - reach), 0, height_),
                        clamp_to_int(std::ceil(c.x + reach), 0, width_),
                        clamp_to_int(std::ceil(c.y + reach), 0, height_)}
                        .intersect(clip);
    for (int y = box.y0; y < box.y1; ++y) {
      for (int x = box.x0; x < box.x1; ++x) {
        put(x, y, 0.5 - marker_distance(marker, x + 0.5 - c.x, y + 0.5 - c.y, radius));
      }
    }
    touch(box);
  }

  // Draws the accumulated coverage onto `canvas` in `colour`.
  void composite(Canvas& canvas, Rgb colour) const {
    for (int y = touched_.y0; y < touched_.y1; ++y) {
      for (int x = touched_.x0; x < touched_.x1; ++x) {
        const float c = v_[size_t(y) * width_ + x];
        if (c > 0.0f) canvas.blend(x, y, colour, c);
      }
    }
  }

  // Max-merges the coverage into `into`, a mask of the same size.
  void merge_into(Mask& into) const {
    for (int y = touched_.y0; y < touched_.y1; ++y) {
      for (int x = touched_.x0; x < touched_.x1; ++x) into.put(x, y, v_[size_t(y) * width_ + x]);
    }
    into.touch(touched_);
  }

  double sum(Box box) const {
    box = box.intersect({0, 0, width_, height_});
    double total = 0.0;
    for (int y = box.y0; y < box.y1; ++y) {
      for (int x = box.x0; x < box.x1; ++x) total += v_[size_t(y) * width_ + x];
    }
    return total;
  }

 private:
  void put(int x, int y, double coverage) {
    if (coverage <= 0.0) return;
    float& v = v_[size_t(y) * width_ + x];
    v = std::max(v, float(std::min(coverage, 1.0)));
  }
  void touch(const Box& box) {
    if (box.empty()) return;
    touched_ = touched_.empty() ? box
                                : Box{std::min(touched_.x0, box.x0), std::min(touched_.y0, box.y0),
                                      std::max(touched_.x1, box.x1), std::max(touched_.y1, box.y1)};
  }

  int width_, height_;
  std::vector<float> v_;
  Box touched_;
};

// --- text -------------------------------------------------------------------------------------

constexpr int kCapHeight = 7;  // stb_easy_font: capitals and digits span rows 0-6
constexpr int kDescent = 2;    // descenders reach row 8

// A line of text as filled rectangles in font units (x0, y0, x1, y1), origin at the top left
// of the capitals.
struct Text {
  std::vector<std::array<float, 4>> rects;
  int width = 0;  // ink width in font units
};

// stb_easy_font covers ASCII 32-126 and reads out of bounds on anything else: control
// characters become spaces; common UTF-8 characters get an ASCII stand-in ("µs" reads "us",
// "é" reads "e"), any other UTF-8 sequence becomes one '?'.
std::string printable(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) {
      out += (c >= 32 && c < 127) ? char(c) : ' ';
      ++i;
      continue;
    }
    // A UTF-8 sequence: decode it, tolerating malformed input (a stray byte is one char).
    const int length = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC0 ? 2 : 1;
    unsigned code = length == 1 ? 0 : c & (0x7Fu >> length);
    int used = 1;
    for (; used < length && i + size_t(used) < text.size(); ++used) {
      const unsigned char next = static_cast<unsigned char>(text[i + size_t(used)]);
      if ((next & 0xC0) != 0x80) break;
      code = (code << 6) | (next & 0x3Fu);
    }
    i += size_t(used);
    switch (code) {
      case 0xB5:
      case 0x3BC:
        out += 'u';
        break;  // micro sign, mu
      case 0xD7:
        out += 'x';
        break;  // multiplication sign
      case 0xB7:
      case 0x22C5:
        out += '.';
        break;  // middle dot, dot operator
      case 0xB1:
        out += "+-";
        break;
      case 0xB2:
        out += '2';
        break;
      case 0xB3:
        out += '3';
        break;
      case 0x2010:
      case 0x2011:
      case 0x2012:
      case 0x2013:
      case 0x2014:
      case 0x2212:
        out += '-';
        break;
      case 0x2018:
      case 0x2019:
        out += '\'';
        break;
      case 0x201C:
      case 0x201D:
        out += '"';
        break;
      case 0x2264:
        out += "<=";
        break;
      case 0x2265:
        out += ">=";
        break;
      case 0xA0:
      case 0x2009:
      case 0x202F:
        out += ' ';
        break;  // no-break, thin spaces
      default:
        if (code >= 0xC0 && code <= 0xFF) {
          // Latin-1 letters without their accents ("café" reads "cafe").
          static constexpr char kLatin1[] =
              "AAAAAAACEEEEIIIIDNOOOOOxOUUUUYPsaaaaaaaceeeeiiiidnooooo/ouuuuypy";
          out += kLatin1[code - 0xC0];
        } else {
          out += '?';
        }
    }
  }
  return out;
}

Text layout_text(const std::string& raw) {
  Text text;
  std::string s = printable(raw);
  if (s.empty()) return text;
  // Exact upper bound of the quads: every segment of every character, 64 bytes a quad.
  size_t segments = 0;
  for (unsigned char c : s) {
    const int i = c - 32;
    segments += size_t(stb_easy_font_charinfo[i + 1].h_seg - stb_easy_font_charinfo[i].h_seg) +
                size_t(stb_easy_font_charinfo[i + 1].v_seg - stb_easy_font_charinfo[i].v_seg);
  }
  std::vector<char> buffer(segments * 64 + 64);
  const int quads = stb_easy_font_print(0.0f, 0.0f, s.data(), nullptr, buffer.data(),
                                        int(std::min<size_t>(buffer.size(), 1u << 30)));
  text.rects.reserve(size_t(std::max(quads, 0)));
  float right = 0.0f;
  for (int q = 0; q < quads; ++q) {
    // Vertices 0 and 2 of a quad are opposite corners; each vertex is x, y, z, colour.
    float v0[2], v2[2];
    std::memcpy(v0, buffer.data() + size_t(q) * 64, sizeof v0);
    std::memcpy(v2, buffer.data() + size_t(q) * 64 + 32, sizeof v2);
    text.rects.push_back({std::min(v0[0], v2[0]), std::min(v0[1], v2[1]), std::max(v0[0], v2[0]),
                          std::max(v0[1], v2[1])});
    right = std::max(right, text.rects.back()[2]);
  }
  text.width = int(std::ceil(right));
  return text;
}

// Draws text with its cap-box top-left corner at (x, y) — or, when `vertical`, rotated a
// quarter turn anticlockwise (reading upwards) with the start of the line at (x, y): the cap
// tops face left, towards x, and the line runs up from y.
void draw_text(Canvas& canvas, const Text& text, int x, int y, int scale, Rgb colour,
               bool vertical = false) {
  for (const auto& r : text.rects) {
    const int rx0 = int(std::lround(r[0])) * scale, ry0 = int(std::lround(r[1])) * scale;
    const int rx1 = int(std::lround(r[2])) * scale, ry1 = int(std::lround(r[3])) * scale;
    if (vertical) {
      canvas.fill({x + ry0, y - rx1, x + ry1, y - rx0}, colour);
    } else {
      canvas.fill({x + rx0, y + ry0, x + rx1, y + ry1}, colour);
    }
  }
}

// Horizontal text anchored at (x, y): ax, ay are the fractions (0, 0.5, 1) of the ink width
// and of the cap height that land on the anchor.
void draw_text_at(Canvas& canvas, const Text& text, double x, double y, double ax, double ay,
                  int scale, Rgb colour) {
  draw_text(canvas, text, int(std::lround(x - ax * text.width * scale)),
            int(std::lround(y - ay * kCapHeight * scale)), scale, colour);
}

// --- axes -------------------------------------------------------------------------------------

struct Tick {
  double value;
  std::string label;
};

struct Axis {
  bool log = false;
  double lo = 0.0, hi = 1.0;  // the axis range in data units; lo < hi (and lo > 0 if log)
  std::vector<Tick> major;
  std::vector<double> minor;  // unlabelled ticks (log decades' 2..9)

  // 0 at lo, 1 at hi.
  double unit(double v) const {
    if (log) return (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo));
    return (v - lo) / (hi - lo);
  }
};

// Digits after the point needed to write `v` exactly, up to 12.
int decimals_for(double v) {
  v = std::abs(v);
  for (int d = 0; d < 12; ++d) {
    const double scaled = v * std::pow(10.0, d);
    if (std::abs(scaled - std::round(scaled)) <= 1e-6 * std::max(1.0, scaled)) return d;
  }
  return 12;
}

// "1.5e6", "2e-5": %g without the '+' and the exponent's leading zeros.
std::string format_scientific(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  std::string s = buf;
  const size_t e = s.find('e');
  if (e == std::string::npos) return s;
  std::string mantissa = s.substr(0, e), exponent = s.substr(e + 1);
  bool negative = false;
  if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) {
    negative = exponent[0] == '-';
    exponent.erase(0, 1);
  }
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  return mantissa + "e" + (negative ? "-" : "") + exponent;
}

std::string format_fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

// Labels for ticks `step` apart (step 0: each value written as briefly as it can be).
void label_ticks(std::vector<Tick>& ticks, double step) {
  double largest = 0.0, smallest = std::numeric_limits<double>::infinity();
  for (const Tick& t : ticks) {
    largest = std::max(largest, std::abs(t.value));
    if (t.value != 0.0) smallest = std::min(smallest, std::abs(t.value));
  }
  const double resolution = step > 0.0 ? step : smallest;
  const bool scientific = largest >= 1e6 || (resolution < 1e-4 && std::isfinite(resolution));
  int decimals = 0;
  if (step > 0.0) decimals = decimals_for(step);
  for (Tick& t : ticks) {
    if (scientific) {
      t.label = format_scientific(t.value);
    } else {
      t.label = format_fixed(t.value, step > 0.0 ? decimals : decimals_for(t.value));
    }
  }
}

// Widens an empty or tiny range so that it has a usable width.
void widen_degenerate(double& lo, double& hi, bool log) {
  if (log) {
    if (!(hi > lo * (1.0 + 1e-9))) {
      lo /= 1.25;
      hi *= 1.25;
    }
    return;
  }
  const double magnitude = std::max(std::abs(lo), std::abs(hi));
  if (!(hi - lo > magnitude * 1e-9)) {
    const double mid = 0.5 * (lo + hi);
    const double d = mid != 0.0 ? std::abs(mid) * 0.1 : 1.0;
    lo = mid - d;
    hi = mid + d;
  }
}

// Linear ticks: a 1, 2, 2.5 or 5 times power-of-ten step giving 5-8 ticks that enclose the
// data as tightly as possible; the axis runs from the first to the last tick.
Axis linear_axis(double lo, double hi) {
  widen_degenerate(lo, hi, false);
  const double range = hi - lo;
  const int e0 = int(std::floor(std::log10(range)));
  double best_score = std::numeric_limits<double>::infinity();
  double best_step = range / 5.0, best_first = lo / best_step, best_last = hi / best_step;
  for (int e = e0 - 2; e <= e0 + 1; ++e) {
    for (double m : {1.0, 2.0, 2.5, 5.0}) {
      const double step = m * std::pow(10.0, e);
      const double first = std::floor(lo / step + 1e-9), last = std::ceil(hi / step - 1e-9);
      const double n = last - first + 1.0;
      const double waste = ((last - first) * step - range) / range;
      double score = waste * 3.0 + 0.1 * std::abs(n - 6.0) + (m == 2.5 ? 0.5 : 0.0);
      if (n < 5.0 || n > 8.0) score += 100.0 + std::abs(n - 6.5);
      if (score < best_score) {
        best_score = score;
        best_step = step;
        best_first = first;
        best_last = last;
      }
    }
  }
  Axis axis;
  axis.lo = best_first * best_step;
  axis.hi = best_last * best_step;
  for (double i = best_first; i <= best_last + 0.5 && axis.major.size() < 100; i += 1.0) {
    double v = i * best_step;
    if (std::abs(v) < best_step * 1e-9) v = 0.0;  // no "-0"
    axis.major.push_back({v, ""});
  }
  label_ticks(axis.major, best_step);
  return axis;
}

// Ticks on a log axis from the sequence m * 10^k, m in `mantissas`: the axis runs from the
// last value <= lo to the first >= hi. Empty if that gives fewer than min_count or more than
// max_count ticks.
std::vector<Tick> sequence_ticks(double lo, double hi, const std::vector<double>& mantissas,
                                 size_t min_count, size_t max_count) {
  const int a = int(std::floor(std::log10(lo))), b = int(std::ceil(std::log10(hi)));
  std::vector<double> candidates;
  for (int k = a - 1; k <= b + 1; ++k) {
    for (double m : mantissas) candidates.push_back(m * std::pow(10.0, k));
  }
  double axis_lo = 0.0, axis_hi = 0.0;
  for (double c : candidates) {
    if (c <= lo * (1.0 + 1e-9)) axis_lo = c;
    if (axis_hi == 0.0 && c >= hi * (1.0 - 1e-9)) axis_hi = c;
  }
  std::vector<Tick> ticks;
  if (!(axis_lo > 0.0) || !(axis_hi > axis_lo)) return ticks;
  for (double c : candidates) {
    if (c >= axis_lo * (1.0 - 1e-9) && c <= axis_hi * (1.0 + 1e-9)) ticks.push_back({c, ""});
  }
  if (ticks.size() < min_count || ticks.size() > max_count) ticks.clear();
  return ticks;
}

// Logarithmic ticks: a 1-2-5 sequence when that gives 4-8 ticks; else whole decades when the
// data spans two or more (every n-th when there would be more than 8, with unlabelled 2..9 in
// between); else 1-2-3-5; else — for less than about half a decade — linear ticks placed on
// the log scale.
Axis log_axis(double lo, double hi) {
  widen_degenerate(lo, hi, true);
  Axis axis;
  axis.log = true;
  auto use = [&axis](std::vector<Tick> ticks) {
    axis.lo = ticks.front().value;
    axis.hi = ticks.back().value;
    axis.major = std::move(ticks);
    label_ticks(axis.major, 0.0);
    return axis;
  };
  if (auto ticks = sequence_ticks(lo, hi, {1, 2, 5}, 4, 8); !ticks.empty()) return use(ticks);
  const int a = int(std::floor(std::log10(lo) + 1e-9));
  int b = int(std::ceil(std::log10(hi) - 1e-9));
  if (b - a >= 2) {
    const int stride = std::max(1, int(std::ceil((b - a + 1) / 8.0)));
    b = a + stride * int(std::ceil(double(b - a) / stride));
    std::vector<Tick> ticks;
    for (int k = a; k <= b; k += stride) ticks.push_back({std::pow(10.0, k), ""});
    if (stride == 1) {
      for (int k = a; k < b; ++k) {
        for (int m = 2; m <= 9; ++m) axis.minor.push_back(m * std::pow(10.0, k));
      }
    }
    return use(std::move(ticks));
  }
  if (auto ticks = sequence_ticks(lo, hi, {1, 2, 3, 5}, 4, 9); !ticks.empty()) return use(ticks);
  Axis linear = linear_axis(lo, hi);
  linear.log = true;
  if (!(linear.lo > 0.0)) {
    linear.lo = lo;
    std::erase_if(linear.major, [&](const Tick& t) { return t.value < lo; });
  }
  return linear;
}

Axis make_axis(double lo, double hi, bool have_data, bool log) {
  if (!have_data) {
    lo = log ? 1.0 : 0.0;
    hi = log ? 10.0 : 1.0;
  }
  // Keeps the range, its width and its ticks finite and normal (data beyond is clipped).
  const double limit = 1e300;
  lo = std::clamp(lo, log ? 1.0 / limit : -limit, limit);
  hi = std::clamp(hi, log ? 1.0 / limit : -limit, limit);
  return log ? log_axis(lo, hi) : linear_axis(lo, hi);
}

// --- the chart ----------------------------------------------------------------------------------

constexpr int kTextScale = 2;
constexpr int kPad = 14;
constexpr int kTickLength = 5;
constexpr int kMinorTickLength = 3;
constexpr int kTickLabelGap = 5;
constexpr int kInset = 10;  // between the frame and the extreme ticks
constexpr double kLineHalfWidth = 1.15;
constexpr double kMarkerRadius = 4.2;

std::string describe(const PlotSpec& spec) {
  return spec.title.empty() ? std::string("plot") : "plot '" + spec.title + "'";
}

void validate(const PlotSpec& spec) {
  if (spec.width < kMinSize || spec.width > kMaxSize || spec.height < kMinSize ||
      spec.height > kMaxSize) {
    throw InputError(describe(spec) + ": size " + std::to_string(spec.width) + "x" +
                     std::to_string(spec.height) + ": width and height must be in [" +
                     std::to_string(kMinSize) + ", " + std::to_string(kMaxSize) + "]");
  }
  for (const PlotSeries& s : spec.series) {
    if (s.x.size() != s.y.size()) {
      throw InputError(describe(spec) + ": series '" + s.label + "' has " +
                       std::to_string(s.x.size()) + " x values and " + std::to_string(s.y.size()) +
                       " y values: they must match");
    }
  }
}

bool usable(double v, bool log) {
  return std::isfinite(v) && (!log || v > 0.0);
}

// Where the chart's parts go, in pixels.
struct Layout {
  Box frame;                              // the frame's outer box; its 1-px border lies inside it
  Box inside;                             // inside the border: where the series are drawn
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;  // pixel positions of the axis ends (y0: top)
};

Layout make_layout(int width, int height, int left, int top, int right, int bottom) {
  Layout l;
  l.frame = {left, top, width - right, height - bottom};
  l.frame.x1 = std::max(l.frame.x1, l.frame.x0 + 8);
  l.frame.y1 = std::max(l.frame.y1, l.frame.y0 + 8);
  l.inside = {l.frame.x0 + 1, l.frame.y0 + 1, l.frame.x1 - 1, l.frame.y1 - 1};
  const int inset_x = std::min(kInset, (l.frame.x1 - l.frame.x0) / 8);
  const int inset_y = std::min(kInset, (l.frame.y1 - l.frame.y0) / 8);
  l.x0 = l.frame.x0 + inset_x + 0.5;
  l.x1 = l.frame.x1 - inset_x - 0.5;
  l.y0 = l.frame.y0 + inset_y + 0.5;
  l.y1 = l.frame.y1 - inset_y - 0.5;
  return l;
}

struct Mapping {
  const Axis& x_axis;
  const Axis& y_axis;
  const Layout& layout;
  double px(double v) const { return layout.x0 + x_axis.unit(v) * (layout.x1 - layout.x0); }
  double py(double v) const { return layout.y1 - y_axis.unit(v) * (layout.y1 - layout.y0); }
};

// Series `index` as coverage in `mask`: lines between consecutive usable points (a point
// that cannot be drawn breaks the line), and a marker on each.
void paint_series(Mask& mask, const PlotSpec& spec, size_t index, const Mapping& map) {
  const PlotSeries& series = spec.series[index];
  mask.clear();
  bool previous = false;
  Point last{0.0, 0.0};
  for (size_t i = 0; i < series.x.size(); ++i) {
    if (!usable(series.x[i], spec.log_x) || !usable(series.y[i], spec.log_y)) {
      previous = false;
      continue;
    }
    const Point p{map.px(series.x[i]), map.py(series.y[i])};
    if (previous) mask.stroke(last, p, kLineHalfWidth, map.layout.inside);
    last = p;
    previous = true;
  }
  for (size_t i = 0; i < series.x.size(); ++i) {
    if (!usable(series.x[i], spec.log_x) || !usable(series.y[i], spec.log_y)) continue;
    mask.marker({map.px(series.x[i]), map.py(series.y[i])}, kMarkers[index % kMarkers.size()],
                kMarkerRadius, map.layout.inside);
  }
}

void draw_chart(Canvas& canvas, const PlotSpec& spec) {
  const int s = kTextScale;
  const int width = canvas.width(), height = canvas.height();

  // Data ranges over the points that can be drawn.
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  double y_lo = x_lo, y_hi = -x_lo;
  bool have_data = false;
  for (const PlotSeries& series : spec.series) {
    for (size_t i = 0; i < series.x.size(); ++i) {
      if (!usable(series.x[i], spec.log_x) || !usable(series.y[i], spec.log_y)) continue;
      have_data = true;
      x_lo = std::min(x_lo, series.x[i]);
      x_hi = std::max(x_hi, series.x[i]);
      y_lo = std::min(y_lo, series.y[i]);
      y_hi = std::max(y_hi, series.y[i]);
    }
  }
  const Axis x_axis = make_axis(x_lo, x_hi, have_data, spec.log_x);
  const Axis y_axis = make_axis(y_lo, y_hi, have_data, spec.log_y);

  // Margins sized to what they hold.
  std::vector<Text> x_labels, y_labels;
  int y_label_width = 0;
  for (const Tick& t : x_axis.major) x_labels.push_back(layout_text(t.label));
  for (const Tick& t : y_axis.major) {
    y_labels.push_back(layout_text(t.label));
    y_label_width = std::max(y_label_width, y_labels.back().width * s);
  }
  const Text title = layout_text(spec.title);
  const int title_scale = title.width * 3 <= width - 2 * kPad ? 3 : 2;  // larger where it fits
  const Text x_title = layout_text(spec.x_label);
  const Text y_title = layout_text(spec.y_label);

  const int top = kPad + (title.rects.empty() ? 6 : kCapHeight * title_scale + 14);
  const int left = kPad + (y_title.rects.empty() ? 0 : (kCapHeight + kDescent) * s + 10) +
                   y_label_width + kTickLabelGap + kTickLength;
  const int bottom = kPad + (x_title.rects.empty() ? 0 : (kCapHeight + kDescent) * s + 10) +
                     kCapHeight * s + kTickLabelGap + kTickLength;
  const int last_x_label = x_labels.empty() ? 0 : x_labels.back().width * s;
  const int right = std::max(kPad + 6, last_x_label / 2 + 6 - kInset);
  Layout layout = make_layout(width, height, left, top, right, bottom);

  // The legend: one row per labelled series, in the frame corner where it hides the least of
  // the data; to the right of the frame if every corner would hide much and there is room.
  std::vector<size_t> entries;
  std::vector<Text> entry_text;
  int entry_width = 0;
  for (size_t si = 0; si < spec.series.size(); ++si) {
    if (spec.series[si].label.empty()) continue;
    entries.push_back(si);
    entry_text.push_back(layout_text(spec.series[si].label));
    entry_width = std::max(entry_width, entry_text.back().width * s);
  }
  constexpr int kBoxPad = 9, kSample = 30, kSampleGap = 8, kRowGap = 9, kMargin = 8;
  const int rows = int(entries.size());
  const int box_w = 2 * kBoxPad + kSample + kSampleGap + entry_width;
  const int box_h = 2 * kBoxPad + rows * kCapHeight * s + std::max(rows - 1, 0) * kRowGap;
  Mask mask(width, height);
  Box legend;
  if (rows > 0) {
    auto place_inside = [&](const Layout& l, const Mask& data, double& covered) {
      const Box& in = l.inside;
      const std::array<Box, 4> corners{{
          {in.x1 - kMargin - box_w, in.y0 + kMargin, in.x1 - kMargin, in.y0 + kMargin + box_h},
          {in.x0 + kMargin, in.y0 + kMargin, in.x0 + kMargin + box_w, in.y0 + kMargin + box_h},
          {in.x1 - kMargin - box_w, in.y1 - kMargin - box_h, in.x1 - kMargin, in.y1 - kMargin},
          {in.x0 + kMargin, in.y1 - kMargin - box_h, in.x0 + kMargin + box_w, in.y1 - kMargin},
      }};
      Box best = corners[0];
      covered = std::numeric_limits<double>::infinity();
      for (const Box& c : corners) {
        const double here = data.sum({c.x0 - 3, c.y0 - 3, c.x1 + 3, c.y1 + 3});
        if (here < covered - 1e-6) {
          covered = here;
          best = c;
        }
      }
      return best;
    };
    Mask data(width, height);
    const Mapping map{x_axis, y_axis, layout};
    for (size_t si = 0; si < spec.series.size(); ++si) {
      paint_series(mask, spec, si, map);
      mask.merge_into(data);
    }
    double covered = 0.0;
    legend = place_inside(layout, data, covered);
    const int outside_right = kPad + box_w + 12;
    const bool room = box_w <= width / 3 && box_h <= layout.frame.y1 - layout.frame.y0;
    if (covered > 0.01 * box_w * box_h && room) {
      layout = make_layout(width, height, left, top, std::max(right, outside_right), bottom);
      legend = {layout.frame.x1 + 12, layout.frame.y0, layout.frame.x1 + 12 + box_w,
                layout.frame.y0 + box_h};
    }
  }
  const Mapping map{x_axis, y_axis, layout};
  const Box& frame = layout.frame;
  const Box& inside = layout.inside;

  // Grid and ticks.
  for (double v : x_axis.minor) {
    if (v < x_axis.lo || v > x_axis.hi) continue;
    const int px = clamp_to_int(std::floor(map.px(v)), -1, width);
    canvas.fill({px, inside.y0, px + 1, inside.y1}, kMinorGridColour);
    canvas.fill({px, frame.y1, px + 1, frame.y1 + kMinorTickLength}, kFrameColour);
  }
  for (double v : y_axis.minor) {
    if (v < y_axis.lo || v > y_axis.hi) continue;
    const int py = clamp_to_int(std::floor(map.py(v)), -1, height);
    canvas.fill({inside.x0, py, inside.x1, py + 1}, kMinorGridColour);
    canvas.fill({frame.x0 - kMinorTickLength, py, frame.x0, py + 1}, kFrameColour);
  }
  for (size_t i = 0; i < x_axis.major.size(); ++i) {
    const int px = clamp_to_int(std::floor(map.px(x_axis.major[i].value)), -1, width);
    canvas.fill({px, inside.y0, px + 1, inside.y1}, kGridColour);
    canvas.fill({px, frame.y1, px + 1, frame.y1 + kTickLength}, kFrameColour);
    draw_text_at(canvas, x_labels[i], px + 0.5, frame.y1 + kTickLength + kTickLabelGap, 0.5, 0.0, s,
                 kTextColour);
  }
  for (size_t i = 0; i < y_axis.major.size(); ++i) {
    const int py = clamp_to_int(std::floor(map.py(y_axis.major[i].value)), -1, height);
    canvas.fill({inside.x0, py, inside.x1, py + 1}, kGridColour);
    canvas.fill({frame.x0 - kTickLength, py, frame.x0, py + 1}, kFrameColour);
    draw_text_at(canvas, y_labels[i], frame.x0 - kTickLength - kTickLabelGap, py + 0.5, 1.0, 0.5, s,
                 kTextColour);
  }

  // Series, later ones over earlier ones.
  for (size_t si = 0; si < spec.series.size(); ++si) {
    paint_series(mask, spec, si, map);
    mask.composite(canvas, kPalette[si % kPalette.size()]);
  }
  canvas.outline(frame, kFrameColour);

  // Titles.
  const double centre_x = 0.5 * (frame.x0 + frame.x1);
  if (!title.rects.empty()) {
    // Centred over the frame, but kept inside the image where it fits.
    const double half = 0.5 * title.width * title_scale;
    const double x = std::max(std::min(centre_x, width - kPad - half), kPad + half);
    draw_text_at(canvas, title, x, kPad, 0.5, 0.0, title_scale, kTextColour);
  }
  if (!x_title.rects.empty()) {
    draw_text_at(canvas, x_title, centre_x,
                 frame.y1 + kTickLength + kTickLabelGap + kCapHeight * s + 10, 0.5, 0.0, s,
                 kTextColour);
  }
  if (!y_title.rects.empty()) {
    const double centre_y = 0.5 * (frame.y0 + frame.y1);
    draw_text(canvas, y_title, kPad, int(std::lround(centre_y + 0.5 * y_title.width * s)), s,
              kTextColour, /*vertical=*/true);
  }

  // Legend.
  if (rows == 0) return;
  canvas.fill(legend, kWhite, 0.92f);
  canvas.outline(legend, kLegendBorder);
  const Box legend_inside{legend.x0 + 1, legend.y0 + 1, legend.x1 - 1, legend.y1 - 1};
  for (int row = 0; row < rows; ++row) {
    const size_t si = entries[size_t(row)];
    const double cy = legend.y0 + kBoxPad + row * (kCapHeight * s + kRowGap) + 0.5 * kCapHeight * s;
    const double sx0 = legend.x0 + kBoxPad, sx1 = sx0 + kSample;
    mask.clear();
    mask.stroke({sx0, cy}, {sx1, cy}, kLineHalfWidth, legend_inside);
    mask.marker({0.5 * (sx0 + sx1), cy}, kMarkers[si % kMarkers.size()], kMarkerRadius,
                legend_inside);
    mask.composite(canvas, kPalette[si % kPalette.size()]);
    draw_text_at(canvas, entry_text[size_t(row)], sx1 + kSampleGap, cy, 0.0, 0.5, s, kTextColour);
  }
}

// --- PNG output -------------------------------------------------------------------------------

// Encodes in memory, writes a temporary file beside `path` with every I/O call checked, and
// renames it over `path`; on failure nothing is left behind.
void write_png(const std::string& path, int width, int height,
               const std::vector<unsigned char>& rgba) {
  std::vector<unsigned char> png;
  auto append = [](void* context, void* data, int size) {
    auto* sink = static_cast<std::vector<unsigned char>*>(context);
    auto* bytes = static_cast<unsigned char*>(data);
    sink->insert(sink->end(), bytes, bytes + size);
  };
  if (!stbi_write_png_to_func(append, &png, width, height, 4, rgba.data(), width * 4) ||
      png.empty()) {
    throw RuntimeError("plot '" + path + "': PNG encoding failed");
  }
  static std::atomic<unsigned> counter{0};
  const std::string temporary =
      path + ".tmp-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  if (!file) {
    throw RuntimeError("plot '" + path + "': cannot create file: " + std::strerror(errno));
  }
  bool ok = std::fwrite(png.data(), 1, png.size(), file) == png.size();
  int error = ok ? 0 : errno;
  if (std::fflush(file) != 0 && ok) {
    ok = false;
    error = errno;
  }
  if (std::fclose(file) != 0 && ok) {
    ok = false;
    error = errno;
  }
  std::error_code ec;
  if (ok) {
    fs::rename(temporary, path, ec);
    if (!ec) return;
  }
  fs::remove(temporary, ec);
  throw RuntimeError("plot '" + path + "': cannot write file: " +
                     (ok ? std::string("rename failed") : std::string(std::strerror(error))));
}

}  // namespace

std::vector<unsigned char> render_plot(const PlotSpec& spec) {
  validate(spec);
  Canvas canvas(spec.width, spec.height);
  draw_chart(canvas, spec);
  return canvas.take();
}

void write_plot_png(const PlotSpec& spec, const std::string& path) {
  const std::vector<unsigned char> rgba = render_plot(spec);
  write_png(path, spec.width, spec.height, rgba);
}

void write_plot_grid_png(const std::vector<PlotSpec>& specs, int columns, const std::string& path) {
  if (specs.empty()) throw InputError("plot grid '" + path + "': no charts to draw");
  if (columns < 1) {
    throw InputError("plot grid '" + path + "': columns = " + std::to_string(columns) +
                     ": must be at least 1");
  }
  for (const PlotSpec& spec : specs) validate(spec);
  const int n = int(specs.size());
  columns = std::min(columns, n);
  const int rows = (n + columns - 1) / columns;
  int cell_w = 0, cell_h = 0;
  for (const PlotSpec& spec : specs) {
    cell_w = std::max(cell_w, spec.width);
    cell_h = std::max(cell_h, spec.height);
  }
  if (int64_t(cell_w) * columns > kMaxGridSize || int64_t(cell_h) * rows > kMaxGridSize) {
    throw InputError("plot grid '" + path + "': " + std::to_string(columns) + "x" +
                     std::to_string(rows) + " charts of " + std::to_string(cell_w) + "x" +
                     std::to_string(cell_h) + " exceed " + std::to_string(kMaxGridSize) +
                     " pixels a side");
  }
  const int width = cell_w * columns, height = cell_h * rows;
  std::vector<unsigned char> grid(size_t(width) * size_t(height) * 4, 255);
  for (int i = 0; i < n; ++i) {
    const PlotSpec& spec = specs[size_t(i)];
    const std::vector<unsigned char> chart = render_plot(spec);
    const int ox = (i % columns) * cell_w + (cell_w - spec.width) / 2;
    const int oy = (i / columns) * cell_h + (cell_h - spec.height) / 2;
    for (int y = 0; y < spec.height; ++y) {
      std::memcpy(&grid[(size_t(oy + y) * size_t(width) + size_t(ox)) * 4],
                  &chart[size_t(y) * size_t(spec.width) * 4], size_t(spec.width) * 4);
    }
  }
  write_png(path, width, height, grid);
}

}  // namespace nephele::cli

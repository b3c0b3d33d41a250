// nephele — golden-image comparison and its tolerance files.
#include "nephele/image_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <glm/common.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "nephele/error.h"

namespace nephele {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// |a - b|, with equal values (infinities included) 0 and anything non-finite infinite.
float channel_diff(float a, float b) {
  if (a == b) return 0.0f;
  const float d = std::fabs(a - b);
  return std::isfinite(d) ? d : kInf;
}

std::string format(const char* fmt, double a, double b = 0.0) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, a, b);
  return buf;
}

std::string size_string(const Image& image) {
  return std::to_string(image.width) + "x" + std::to_string(image.height);
}

// One line: the verdict, then each measure against its limit, '>' marking what failed, e.g.
// "FAIL: max diff 0.2000 > limit 0.1000; 1 of 2048 pixels (0.049%) over 0.0100, <= limit
// 0.100%; mean abs diff 0.000024".
std::string summarize(const CompareResult& r, const CompareTolerance& tol, size_t failing,
                      size_t total) {
  const char* diff_op = r.max_diff > tol.max_pixel_diff ? " > limit " : " <= limit ";
  const char* fraction_op =
      r.failing_fraction > tol.max_failing_fraction ? " > limit " : " <= limit ";
  std::string s = r.pass ? "PASS: " : "FAIL: ";
  s += "max diff " + format("%.4f", r.max_diff) + diff_op + format("%.4f", tol.max_pixel_diff);
  s += "; " + std::to_string(failing) + " of " + std::to_string(total) + " pixels (" +
       format("%.3f%%", 100.0 * r.failing_fraction) + ") over " +
       format("%.4f", tol.pixel_threshold) + "," + fraction_op +
       format("%.3f%%", 100.0 * tol.max_failing_fraction);
  s += "; mean abs diff " + format("%.6f", r.mean_abs_diff);
  return s;
}

CompareResult size_mismatch(const Image& actual, const Image& reference) {
  CompareResult r;
  r.pass = false;
  r.max_diff = kInf;
  r.failing_fraction = 1.0f;
  r.mean_abs_diff = kInf;
  r.summary = "FAIL: size mismatch: actual " + size_string(actual) + ", reference " +
              size_string(reference);
  return r;
}

// --- tolerance file ----------------------------------------------------------------------

[[noreturn]] void throw_tolerance_error(const std::string& path, const std::string& what) {
  throw InputError("tolerance file '" + path + "': " + what);
}

float read_limit(const nlohmann::json& doc, const char* key, float max, const std::string& path) {
  const auto it = doc.find(key);
  if (it == doc.end()) throw_tolerance_error(path, std::string("missing key \"") + key + "\"");
  const std::string where = std::string(key) + " = " + it->dump();
  if (!it->is_number()) throw_tolerance_error(path, where + ": must be a number");
  const double v = it->get<double>();
  if (!(v >= 0.0 && v <= max)) {
    throw_tolerance_error(
        path, where + (std::isinf(max) ? ": must be >= 0"
                                       : ": must be in [0, " + format("%g", max) + "]"));
  }
  return static_cast<float>(v);
}

}  // namespace

CompareResult compare_images(const Image& actual, const Image& reference,
                             const CompareTolerance& tol) {
  if (actual.width != reference.width || actual.height != reference.height ||
      actual.pixels.size() != reference.pixels.size()) {
    return size_mismatch(actual, reference);
  }
  CompareResult r;
  r.diff = Image(actual.width, actual.height);
  size_t failing = 0;
  double sum = 0.0;
  for (size_t i = 0; i < actual.pixels.size(); ++i) {
    const glm::vec4& a = actual.pixels[i];
    const glm::vec4& b = reference.pixels[i];
    const glm::vec4 d(channel_diff(a.r, b.r), channel_diff(a.g, b.g), channel_diff(a.b, b.b),
                      channel_diff(a.a, b.a));
    const float pixel_max = std::max({d.r, d.g, d.b, d.a});
    r.max_diff = std::max(r.max_diff, pixel_max);
    if (pixel_max > tol.pixel_threshold) ++failing;
    sum += double(d.r) + double(d.g) + double(d.b) + double(d.a);
    // Alpha has no colour of its own: show its difference in all three channels.
    const glm::vec4 shown = glm::max(d, glm::vec4(d.a));
    r.diff.pixels[i] = glm::min(shown * kDiffGain, glm::vec4(1.0f));
    r.diff.pixels[i].a = 1.0f;
  }
  const size_t total = actual.pixels.size();
  r.failing_fraction = total ? float(double(failing) / double(total)) : 0.0f;
  r.mean_abs_diff = total ? float(sum / (4.0 * double(total))) : 0.0f;
  r.pass = r.max_diff <= tol.max_pixel_diff && r.failing_fraction <= tol.max_failing_fraction;
  r.summary = summarize(r, tol, failing, total);
  return r;
}

CompareTolerance load_tolerance_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw_tolerance_error(path, "cannot open");
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw_tolerance_error(path, std::string("invalid JSON: ") + e.what());
  }
  if (!doc.is_object()) throw_tolerance_error(path, "must be a JSON object");
  for (const auto& item : doc.items()) {
    const std::string& key = item.key();
    if (key != "pixel_threshold" && key != "max_failing_fraction" && key != "max_pixel_diff") {
      throw_tolerance_error(path, "unknown key \"" + key +
                                      "\" (allowed: pixel_threshold, max_failing_fraction, "
                                      "max_pixel_diff)");
    }
  }
  CompareTolerance tol;
  tol.pixel_threshold = read_limit(doc, "pixel_threshold", kInf, path);
  tol.max_failing_fraction = read_limit(doc, "max_failing_fraction", 1.0f, path);
  tol.max_pixel_diff = read_limit(doc, "max_pixel_diff", kInf, path);
  return tol;
}

}  // namespace nephele

namespace nephele {

double luminance_error(const Image& image, const Image& reference) {
  if (image.width != reference.width || image.height != reference.height)
    throw InputError("luminance_error: image " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + " and reference " +
                     std::to_string(reference.width) + "x" + std::to_string(reference.height) +
                     " differ in size");
  double diff = 0.0, sum = 0.0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const double l_ref = luminance(reference.pixels[i]);
    diff += std::abs(luminance(image.pixels[i]) - l_ref);
    sum += l_ref;
  }
  return sum > 0.0 ? diff / sum : diff / double(std::max<size_t>(image.pixels.size(), 1));
}

BlockLuminanceError block_luminance_error(const Image& image, const Image& reference,
                                          const Image& reference_variance, int block) {
  if (image.width != reference.width || image.height != reference.height)
    throw InputError("block_luminance_error: image " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + " and reference " +
                     std::to_string(reference.width) + "x" + std::to_string(reference.height) +
                     " differ in size");
  const bool with_variance = !reference_variance.pixels.empty();
  if (with_variance && (reference_variance.width != reference.width ||
                        reference_variance.height != reference.height))
    throw InputError("block_luminance_error: the reference's variance differs from it in size");
  if (block < 1) throw InputError("block_luminance_error: block " + std::to_string(block) + ": must be >= 1");
  const int bw = (image.width + block - 1) / block, bh = (image.height + block - 1) / block;
  BlockLuminanceError out;
  out.map = Image(bw, bh);
  std::vector<double> relative, reference_blocks;
  double sum_image = 0.0, sum_reference = 0.0, sum_abs = 0.0, sum_noise = 0.0;
  for (int by = 0; by < bh; ++by)
    for (int bx = 0; bx < bw; ++bx) {
      double l_image = 0.0, l_reference = 0.0, variance = 0.0;
      int n = 0;
      for (int y = by * block; y < std::min((by + 1) * block, image.height); ++y)
        for (int x = bx * block; x < std::min((bx + 1) * block, image.width); ++x, ++n) {
          l_image += luminance(image.at(x, y));
          l_reference += luminance(reference.at(x, y));
          if (with_variance) {
            // The channels' estimates are independent (one channel per path): the luminance's
            // variance is the weighted sum of theirs.
            const glm::vec4& v = reference_variance.at(x, y);
            variance += 0.2126 * 0.2126 * v.r + 0.7152 * 0.7152 * v.g + 0.0722 * 0.0722 * v.b;
          }
        }
      l_image /= n;
      l_reference /= n;
      sum_image += l_image;
      sum_reference += l_reference;
      sum_abs += std::abs(l_image - l_reference);
      sum_noise += std::sqrt(variance) / n;
      const double r = l_reference > 0.0 ? std::abs(l_image / l_reference - 1.0) : (l_image > 0.0 ? 1.0 : 0.0);
      relative.push_back(r);
      reference_blocks.push_back(l_reference);
      out.map.at(bx, by) = glm::vec4(float(r), float(r), float(r), 1.0f);
    }
  out.mean_bias = sum_reference > 0.0 ? sum_image / sum_reference - 1.0 : 0.0;
  out.mean_error = sum_reference > 0.0 ? sum_abs / sum_reference : (sum_abs > 0.0 ? 1.0 : 0.0);
  out.reference_noise = sum_reference > 0.0 ? sum_noise / sum_reference : 0.0;
  const double lit = 0.01 * sum_reference / double(reference_blocks.size());
  std::vector<double> lit_relative;
  for (size_t i = 0; i < relative.size(); ++i) {
    if (reference_blocks[i] > 0.0 && reference_blocks[i] >= lit)
      lit_relative.push_back(relative[i]);
    else
      out.map.pixels[i].a = 0.0f;
  }
  if (!lit_relative.empty()) {
    std::sort(lit_relative.begin(), lit_relative.end());
    out.max_lit_error = lit_relative.back();
    out.p95_error =
        lit_relative[std::min(lit_relative.size() - 1, size_t(0.95 * double(lit_relative.size())))];
  }
  out.max_error = *std::max_element(relative.begin(), relative.end());
  return out;
}

}  // namespace nephele

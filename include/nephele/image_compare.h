// nephele — golden-image comparison, in the manner of Filament's renderdiff.
#pragma once

#include <string>

#include "nephele/image.h"

namespace nephele {

// How far an image may stray from its reference. Differences are per channel (RGBA) in
// the images' own units; for images read from 8-bit PNG that is [0, 1] with 1/255 per code
// value. The defaults demand an exact match.
struct CompareTolerance {
  // A pixel fails when any of its channels differs by more than this.
  float pixel_threshold = 0.0f;
  // The image fails when more than this fraction of its pixels fail, in [0, 1].
  float max_failing_fraction = 0.0f;
  // The image fails when any channel of any pixel differs by more than this.
  float max_pixel_diff = 0.0f;
};

struct CompareResult {
  bool pass = false;
  float max_diff = 0.0f;          // largest channel difference (inf for NaN or a size mismatch)
  float failing_fraction = 0.0f;  // fraction of pixels over pixel_threshold
  float mean_abs_diff = 0.0f;     // mean over all channels of all pixels
  // For viewing: RGB = min(1, kDiffGain * |actual - reference|), each channel also raised to
  // the pixel's alpha difference; alpha 1. Empty on a size mismatch.
  Image diff;
  std::string summary;  // one line, starting "PASS" or "FAIL"
};

// Amplification of the differences in CompareResult::diff.
inline constexpr float kDiffGain = 10.0f;

// Compares `actual` with `reference`. Images of different sizes fail.
// A non-finite channel (NaN, or inf where the other is not the same inf) counts as an
// infinite difference.
CompareResult compare_images(const Image& actual, const Image& reference,
                             const CompareTolerance& tol);

// Reads {"pixel_threshold": t, "max_failing_fraction": f, "max_pixel_diff": d}: all three
// keys, numbers >= 0, f <= 1, no other keys. Throws InputError naming the file and the
// offending key if the file cannot be read, is not such an object, or a value is out of range.
CompareTolerance load_tolerance_json(const std::string& path);

}  // namespace nephele

namespace nephele {

// Mean absolute difference of relative luminance, divided by the reference's mean luminance:
// 0.01 = images differ by 1% of the reference's brightness on average. Same sizes required
// (throws InputError otherwise); a zero-luminance reference gives the mean absolute difference.
double luminance_error(const Image& image, const Image& reference);

}  // namespace nephele

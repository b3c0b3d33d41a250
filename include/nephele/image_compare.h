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

// An image against a reference at the scale of blocks of pixels (the reference path
// tracer's comparisons, issue 21): the relative luminance of each block's mean, which averages
// the reference's noise and the images' sub-pixel differences away.
struct BlockLuminanceError {
  double mean_bias = 0.0;   // mean luminance of the image over the reference's, minus 1
  double mean_error = 0.0;  // sum over blocks of |L_image - L_reference| / sum of L_reference
  // The 95th percentile of |L_image / L_reference - 1| over the blocks with light (below).
  double p95_error = 0.0;
  double max_error = 0.0;   // the largest block's
  // The largest among the blocks with light: those whose reference is at least 1% of the mean
  // block's (a black background, where any light counts as 100%, left out).
  double max_lit_error = 0.0;
  // The reference's own noise in the same measure (its standard error summed over blocks, over
  // the sum of its luminance) when the variance of its pixels' means is given, else 0.
  double reference_noise = 0.0;
  // One pixel per block: |L_image / L_reference - 1| in r, g and b; a 1 for a block with light,
  // 0 for one without.
  Image map;
};

// Blocks of block x block pixels (the last row and column of blocks may be smaller). Same
// sizes required (throws InputError otherwise); `reference_variance` empty, or the variance of
// each reference pixel's mean per channel (ReferenceImage::variance). A block whose reference
// is black counts its relative error as 0 when the image is black too, else 1.
BlockLuminanceError block_luminance_error(const Image& image, const Image& reference,
                                          const Image& reference_variance, int block = 8);

}  // namespace nephele

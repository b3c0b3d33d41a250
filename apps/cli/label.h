// Text drawn into an image (the gallery's and the validation's labels).
#pragma once

#include <string>

#include "nephele/image.h"

namespace nephele::cli {

// Draws `text` at (x, y), `scale` pixels per font unit, white on a darkened box, in HDR values
// (white after any tone mapping with an exposure of at least 0.02).
void draw_label(Image& image, int x, int y, const std::string& text, int scale);
// The width in pixels of draw_label's box for `text` (its height is 12 x scale).
int label_width(const std::string& text, int scale);

}  // namespace nephele::cli

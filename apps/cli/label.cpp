#include "label.h"

#include <algorithm>
#include <glm/glm.hpp>

#define STB_EASY_FONT_IMPLEMENTATION
#include <stb/stb_easy_font.h>

namespace nephele::cli {

int label_width(const std::string& text, int scale) {
  return (stb_easy_font_width(const_cast<char*>(text.c_str())) + 4) * scale;
}

// stb_easy_font's quads, filled.
void draw_label(Image& image, int x, int y, const std::string& text, int scale) {
  static char quads[64 * 1024];
  const int n = stb_easy_font_print(0.0f, 0.0f, const_cast<char*>(text.c_str()), nullptr, quads,
                                    sizeof quads);
  const int box_w = label_width(text, scale);
  const int box_h = 12 * scale;
  for (int py = y; py < std::min(y + box_h, image.height); ++py)
    for (int px = x; px < std::min(x + box_w, image.width); ++px)
      image.at(px, py) = glm::vec4(glm::vec3(image.at(px, py)) * 0.25f, 1.0f);
  // Each quad: four vertices of x, y, z (floats) and a colour (4 bytes), 16 bytes each.
  const auto* v = reinterpret_cast<const float*>(quads);
  for (int q = 0; q < n; ++q, v += 16) {
    const int x0 = x + (2 + int(v[0])) * scale, y0 = y + (2 + int(v[1])) * scale;
    const int x1 = x + (2 + int(v[8])) * scale, y1 = y + (2 + int(v[9])) * scale;
    for (int py = std::max(y0, 0); py < std::min(y1, image.height); ++py)
      for (int px = std::max(x0, 0); px < std::min(x1, image.width); ++px)
        image.at(px, py) = glm::vec4(50.0f, 50.0f, 50.0f, 1.0f);  // white after tone mapping
  }
}

}  // namespace nephele::cli

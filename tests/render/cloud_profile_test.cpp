// Each cloud type's vertical profile (seed 002, "Cloud Modeling 改进"): the rendered density
// field, averaged over a weather-map tile per altitude (Renderer::cloud_profile), peaks and
// ends where the genus should; a second, high layer keeps its own altitude range.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "nephele/renderer.h"
#include "nephele/scene_io.h"
#include "render_fixture.h"

using nephele::CloudProfile;
using nephele::Scene;

namespace {

struct Shape {
  float peak;    // height fraction of the densest bin
  float bottom;  // lowest height fraction with at least 5% of the peak's density
  float top;     // highest such
};

// The profile of the layer `bottom_m` ... `top_m` as height fractions of that layer.
Shape shape_of(const CloudProfile& p, float bottom_m, float top_m) {
  const auto peak = std::max_element(p.density.begin(), p.density.end());
  const float max_density = *peak;
  const auto fraction = [&](size_t i) { return (p.altitude_m[i] - bottom_m) / (top_m - bottom_m); };
  Shape s{fraction(size_t(peak - p.density.begin())), 2.0f, -1.0f};
  for (size_t i = 0; i < p.density.size(); ++i)
    if (p.density[i] >= 0.05f * max_density) {
      s.bottom = std::min(s.bottom, fraction(i));
      s.top = std::max(s.top, fraction(i));
    }
  return s;
}

void print(const char* name, const CloudProfile& p) {
  std::printf("%s:", name);
  for (size_t i = 0; i < p.density.size(); i += 4) std::printf(" %.3f", p.density[i]);
  std::printf("\n");
}

class CloudProfileTest : public RenderTest {};

Scene genus(float type) {
  Scene s = nephele::load_preset("default");
  s.clouds.type = type;
  s.clouds.coverage = 0.6f;
  return s;
}

}  // namespace

// The weather map varies the type by +-0.1 around the layer's, so each genus is mixed a
// little with its neighbours: the bounds allow for that, and each excludes its neighbours'
// heights (stratus ends below where stratocumulus does, altocumulus starts where stratus ends).
TEST_F(CloudProfileTest, EachCloudTypePeaksAndEndsWhereItShould) {
  struct Expected {
    const char* name;
    float type;
    float peak_lo, peak_hi;  // the densest height
    float bottom_max;        // starts at or below
    float top_lo, top_hi;    // ends between
  };
  const Expected genera[] = {
      {"stratus", 0.0f, 0.0f, 0.2f, 0.12f, 0.1f, 0.32f},
      {"stratocumulus", 0.25f, 0.1f, 0.42f, 0.12f, 0.25f, 0.45f},
      {"altocumulus", 0.5f, 0.35f, 0.7f, 0.65f, 0.5f, 0.8f},
      {"cumulus", 0.75f, 0.15f, 0.6f, 0.12f, 0.35f, 0.85f},
      {"cumulonimbus", 1.0f, 0.5f, 1.0f, 0.12f, 0.9f, 1.0f},
  };
  std::vector<float> tops;
  for (const Expected& e : genera) {
    SCOPED_TRACE(e.name);
    const Scene s = genus(e.type);
    const CloudProfile p = shared_renderer().cloud_profile(s);
    ASSERT_EQ(p.density.size(), 64u);
    print(e.name, p);
    const Shape shape = shape_of(p, s.clouds.bottom_altitude_m, s.clouds.top_altitude_m);
    std::printf("  peak %.2f, from %.2f to %.2f\n", shape.peak, shape.bottom, shape.top);
    EXPECT_GE(shape.peak, e.peak_lo);
    EXPECT_LE(shape.peak, e.peak_hi);
    EXPECT_LE(shape.bottom, e.bottom_max);
    EXPECT_GE(shape.top, e.top_lo);
    EXPECT_LE(shape.top, e.top_hi);
    tops.push_back(shape.top);
  }
  // The genera that grow from the base reach higher in turn: stratus, stratocumulus, cumulus,
  // cumulonimbus.
  EXPECT_GT(tops[1], tops[0] + 0.08f);
  EXPECT_GT(tops[3], tops[1] + 0.08f);
  EXPECT_GT(tops[4], tops[3] + 0.08f);
  // Altocumulus floats: nothing in the lowest quarter of the layer.
  const Scene alto = genus(0.5f);
  const Shape a = shape_of(shared_renderer().cloud_profile(alto), alto.clouds.bottom_altitude_m,
                           alto.clouds.top_altitude_m);
  EXPECT_GE(a.bottom, 0.25f);
}

// Two volumetric layers: each keeps its own range, coverage and type; the gap between them is
// empty.
TEST_F(CloudProfileTest, TheHighLayerKeepsItsOwnRange) {
  Scene s = genus(0.25f);  // stratocumulus low
  s.high_clouds.coverage = 0.55f;
  s.high_clouds.bottom_altitude_m = 6000.0f;
  s.high_clouds.top_altitude_m = 7500.0f;
  s.high_clouds.type = 0.5f;
  const CloudProfile p = shared_renderer().cloud_profile(s);
  print("two layers", p);
  ASSERT_EQ(p.altitude_m.size(), 64u);
  EXPECT_NEAR(p.altitude_m.front(), 1500.0f, 100.0f);
  EXPECT_NEAR(p.altitude_m.back(), 7500.0f, 100.0f);
  float low = 0.0f, gap = 0.0f, high = 0.0f;
  for (size_t i = 0; i < p.density.size(); ++i) {
    const float z = p.altitude_m[i];
    float& band = z < 4000.0f ? low : z < 6000.0f ? gap : high;
    band = std::max(band, p.density[i]);
  }
  std::printf("max density: low %.4f, gap %.4f, high %.4f\n", low, gap, high);
  EXPECT_GT(low, 0.01f);
  EXPECT_GT(high, 0.01f);
  EXPECT_EQ(gap, 0.0f);
  // The high altocumulus sits in the middle of its own layer, not at its bottom.
  const Shape h = shape_of(CloudProfile{{p.altitude_m.begin() + 43, p.altitude_m.end()},
                                        {p.density.begin() + 43, p.density.end()},
                                        {}},
                           6000.0f, 7500.0f);
  EXPECT_GE(h.peak, 0.3f);
  EXPECT_LE(h.peak, 0.75f);
  // Without coverage the high layer is gone and the profile spans the low layer alone.
  s.high_clouds.coverage = 0.0f;
  EXPECT_NEAR(shared_renderer().cloud_profile(s).altitude_m.back(), 4000.0f, 100.0f);
}

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

// Four volumetric layers, three of them given as a report gives them ([[cloud_layers]]: genus,
// where the clouds' bases and tops are, oktas): each draws its clouds between its base and top,
// the gaps between them stay empty, and a layer without oktas is gone.
TEST_F(CloudProfileTest, ReportLayersDrawTheirCloudsBetweenTheirBasesAndTops) {
  Scene s = genus(0.25f);  // stratocumulus, 1500-4000 m
  s.clouds.bottom_altitude_m = 500.0f;
  s.clouds.top_altitude_m = 1500.0f;
  const auto layer = [](const char* genus, float base_m, float top_m, float oktas) {
    nephele::CloudLayerParams l;
    l.genus = genus;
    l.base_m = base_m;
    l.top_m = top_m;
    l.oktas = oktas;
    return l;
  };
  s.cloud_layers = {layer("altocumulus", 2500.0f, 3200.0f, 5.0f),
                    layer("cumulus", 4200.0f, 5600.0f, 3.0f),
                    layer("stratocumulus", 6500.0f, 7200.0f, 6.0f)};
  const CloudProfile p = shared_renderer().cloud_profile(s);
  print("four layers", p);
  ASSERT_EQ(p.altitude_m.size(), 64u);
  const float bin_m = p.altitude_m[1] - p.altitude_m[0];
  // Each given layer's clouds, where a tenth as much of the area is cloud as at the layer's
  // cloudiest height: from within 10% of its depth (or a bin) of its base to within that of
  // its top.
  for (const nephele::CloudLayerParams& l : s.cloud_layers) {
    SCOPED_TRACE(l.genus);
    const float slack_m = std::max(0.1f * (l.top_m - l.base_m), bin_m);
    float lowest = 1e9f, highest = -1e9f, most = 0.0f, densest = 0.0f;
    const auto near = [&](size_t i) {
      return p.altitude_m[i] > l.base_m - 600.0f && p.altitude_m[i] < l.top_m + 600.0f;
    };
    for (size_t i = 0; i < p.density.size(); ++i)
      if (near(i)) {
        most = std::max(most, p.cloud_fraction[i]);
        densest = std::max(densest, p.density[i]);
      }
    for (size_t i = 0; i < p.density.size(); ++i)
      if (near(i) && p.cloud_fraction[i] >= 0.1f * most) {
        lowest = std::min(lowest, p.altitude_m[i]);
        highest = std::max(highest, p.altitude_m[i]);
      }
    std::printf("%s: clouds %.0f-%.0f m, given %.0f-%.0f\n", l.genus.c_str(), lowest, highest,
                l.base_m, l.top_m);
    EXPECT_GT(densest, 0.001f);
    EXPECT_NEAR(lowest, l.base_m, slack_m);
    EXPECT_NEAR(highest, l.top_m, slack_m);
  }
  // Between the layers' clouds there is none: between the low layer's and the altocumulus',
  // the altocumulus' and the cumulus', and the cumulus' (whose last towers fade out by 6 km)
  // and the stratocumulus'.
  const float gaps[][2] = {{1000.0f, 2400.0f}, {3350.0f, 4050.0f}, {6100.0f, 6400.0f}};
  for (const auto& gap : gaps)
    for (size_t i = 0; i < p.density.size(); ++i)
      if (p.altitude_m[i] > gap[0] && p.altitude_m[i] < gap[1])
        EXPECT_EQ(p.density[i], 0.0f) << "at " << p.altitude_m[i] << " m";
  // A layer without oktas is gone: where the stratocumulus was, under 1% of its density (the
  // cumulus' shell, now up to its own top, holds its faintest towers).
  const auto sum_between = [](const CloudProfile& q, float lo_m, float hi_m) {
    float sum = 0.0f;
    for (size_t i = 0; i < q.density.size(); ++i)
      if (q.altitude_m[i] > lo_m && q.altitude_m[i] < hi_m) sum += q.density[i];
    return sum;
  };
  s.cloud_layers[2].oktas = 0.0f;
  EXPECT_LT(sum_between(shared_renderer().cloud_profile(s), 6500.0f, 7200.0f),
            0.01f * sum_between(p, 6500.0f, 7200.0f));
}

// Tests of the photometric units and the camera's exposure (nephele/exposure.h): EV100 against
// Lagarde and de Rousiers' relations, the meter, auto exposure's limits and adaptation, the old
// keys' mapping, and the field of view's three forms (scene.h).
#include "nephele/exposure.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "nephele/error.h"
#include "nephele/image.h"
#include "nephele/scene_io.h"

namespace nephele {
namespace {

Image uniform(float luminance_cd_m2) {
  Image image(4, 3);
  for (glm::vec4& p : image.pixels) p = glm::vec4(glm::vec3(luminance_cd_m2), 1.0f);
  return image;
}

TEST(Exposure, Ev100FollowsTheSaturationBasedRelation) {
  // L_max = 1.2 x 2^EV100: EV100 0 saturates at 1.2 cd/m^2, sunny 16 (EV100 15) at 39322.
  EXPECT_DOUBLE_EQ(exposure_from_ev100(0.0), 1.0 / 1.2);
  EXPECT_NEAR(1.0 / exposure_from_ev100(15.0), 39321.6, 1e-6);
  for (double ev : {-6.0, -2.5, 0.0, 9.0, 15.0, 24.0})
    EXPECT_NEAR(ev100_from_exposure(exposure_from_ev100(ev)), ev, 1e-12);
  // One stop more halves the exposure.
  EXPECT_DOUBLE_EQ(exposure_from_ev100(10.0) / exposure_from_ev100(11.0), 2.0);
}

TEST(Exposure, MeterReadsLog2OfEightTimesTheLuminance) {
  // K = 12.5, S = 100: EV100 = log2(L S / K). 1 cd/m^2 reads EV100 3; 4096 cd/m^2 reads 15.
  EXPECT_DOUBLE_EQ(ev100_from_luminance(1.0), 3.0);
  EXPECT_DOUBLE_EQ(ev100_from_luminance(4096.0), 15.0);
  // A metered grey lands at L / L_max = K / (S x 1.2) = 0.104 of saturation, whatever L.
  for (double l : {1e-3, 1.0, 5000.0})
    EXPECT_NEAR(l * exposure_from_ev100(ev100_from_luminance(l)), 12.5 / 120.0, 1e-12);
  EXPECT_TRUE(std::isfinite(ev100_from_luminance(0.0)));
}

TEST(Exposure, MeterIsTheLogAverage) {
  Image image = uniform(100.0f);
  EXPECT_NEAR(metered_luminance(image), 100.0, 1e-3);
  // Half the pixels at 1, half at 10000: the log-average is 100, not the mean 5000.5.
  for (size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = glm::vec4(glm::vec3(i % 2 ? 1.0f : 10000.0f), 1.0f);
  EXPECT_NEAR(metered_luminance(image), 100.0, 1e-3);
  // A sun's disk of 1e9 cd/m^2 in one pixel of 12 moves the meter by a factor 1e9^(1/12) / 1.
  image = uniform(1000.0f);
  image.pixels[0] = glm::vec4(glm::vec3(1.0e9f), 1.0f);
  EXPECT_NEAR(metered_luminance(image), 1000.0 * std::pow(1.0e6, 1.0 / 12.0), 1e-2);
  // NaN and black pixels do not make it NaN or 0.
  image.pixels[1] = glm::vec4(NAN);
  image.pixels[2] = glm::vec4(0.0f);
  EXPECT_GT(metered_luminance(image), 0.0);
  EXPECT_TRUE(std::isfinite(metered_luminance(image)));
}

TEST(Exposure, SolarConstantAndTheOldScale) {
  EXPECT_EQ(kSolarConstantLux, 128000.0f);
  EXPECT_EQ(Scene().sun.illuminance_lux, kSolarConstantLux);
  EXPECT_EQ(kLegacyLuxPerUnit * 20.0f, kSolarConstantLux);  // the old sun, 20
  // The old exposure e showed old radiance L / 6400 as (L / 6400) e; the EV100 it maps to shows
  // L the same: L x exposure_from_ev100(ev100_from_legacy_exposure(e)) = (L / 6400) e.
  for (double e : {0.5, 1.0, 12000.0, 5e-6, 1e6})
    EXPECT_NEAR(exposure_from_ev100(ev100_from_legacy_exposure(e)), e / 6400.0, 1e-9 * e);
  EXPECT_NEAR(ev100_from_legacy_exposure(0.5), 13.3808, 1e-4);     // the old default
  EXPECT_NEAR(ev100_from_legacy_exposure(12000.0), -1.1699, 1e-4);  // the old moonlit example
}

TEST(AutoExposure, TargetsTheMeterWithinItsLimits) {
  OutputParams out;
  out.ev100_min = -4.0f;
  out.ev100_max = 17.0f;
  EXPECT_DOUBLE_EQ(auto_ev100_target(out, 4096.0), 15.0);
  EXPECT_DOUBLE_EQ(auto_ev100_target(out, 1e-6), -4.0);  // a dark night stays dark
  EXPECT_DOUBLE_EQ(auto_ev100_target(out, 1e9), 17.0);
  out.exposure_compensation_ev = 1.0f;  // one stop brighter: one EV less
  EXPECT_DOUBLE_EQ(auto_ev100_target(out, 4096.0), 14.0);
}

TEST(AutoExposure, AdaptsAtItsRate) {
  EXPECT_DOUBLE_EQ(adapt_ev100(15.0, 5.0, 2.0, 1.0), 13.0);   // 2 EV in a second
  EXPECT_DOUBLE_EQ(adapt_ev100(15.0, 5.0, 2.0, 10.0), 5.0);   // no overshoot
  EXPECT_DOUBLE_EQ(adapt_ev100(5.0, 15.0, 2.0, 0.25), 5.5);   // upwards too
  EXPECT_DOUBLE_EQ(adapt_ev100(15.0, 5.0, 0.0, 0.0), 5.0);    // rate 0: at once
  EXPECT_DOUBLE_EQ(adapt_ev100(15.0, 5.0, 2.0, -1.0), 15.0);  // time running back: stay

  OutputParams out;
  out.adaptation_ev_per_s = 2.0f;
  const Image day = uniform(4096.0f), dusk = uniform(16.0f);  // metered 15 and 7
  EXPECT_DOUBLE_EQ(frame_ev100(out, day, nullptr, 0.0), 15.0);  // the first frame: at once
  const double previous = 15.0;
  EXPECT_DOUBLE_EQ(frame_ev100(out, dusk, &previous, 1.0), 13.0);
  out.auto_exposure = false;
  out.ev100 = 9.5f;
  EXPECT_DOUBLE_EQ(frame_ev100(out, dusk, &previous, 1.0), 9.5);  // manual: output.ev100
  EXPECT_FLOAT_EQ(still_exposure(out, dusk), float(exposure_from_ev100(9.5)));
}

// A live display exposes from the meter's reading of a frame already drawn.
TEST(AutoExposure, LiveDisplayExposesFromTheMetersReading) {
  OutputParams out;
  out.adaptation_ev_per_s = 2.0f;
  out.ev100 = 11.0f;
  EXPECT_DOUBLE_EQ(live_ev100(out, 0.0, nullptr, 0.1), 11.0);     // nothing metered yet
  EXPECT_DOUBLE_EQ(live_ev100(out, 4096.0, nullptr, 0.1), 15.0);  // the first reading: at once
  const double shown = 15.0;
  EXPECT_DOUBLE_EQ(live_ev100(out, 16.0, &shown, 0.5), 14.0);     // towards 7, 2 EV/s
  EXPECT_DOUBLE_EQ(live_ev100(out, 0.0, &shown, 0.5), 15.0);      // no reading: stay
  out.auto_exposure = false;
  EXPECT_DOUBLE_EQ(live_ev100(out, 16.0, &shown, 0.5), 11.0);     // manual
}

// The old keys keep old scenes rendering as they did.
TEST(OldKeys, IlluminanceAndExposureAreMapped) {
  const Scene s = parse_scene_toml(
      "[sun]\nilluminance = 20.0\n[output]\nexposure = 0.5\n", "old.toml");
  EXPECT_EQ(s.sun.illuminance_lux, 128000.0f);
  EXPECT_NEAR(s.output.ev100, 13.3808f, 1e-4f);
  EXPECT_FALSE(s.output.auto_exposure);
  // With auto_exposure in the same table, the meter decides.
  EXPECT_TRUE(parse_scene_toml("[output]\nexposure = 0.5\nauto_exposure = true\n", "old.toml")
                  .output.auto_exposure);
}

TEST(OldKeys, GiveOneLineWhenWrongOrMixedWithTheNew) {
  const auto error = [](const std::string& text) {
    try {
      parse_scene_toml(text, "s.toml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error("[output]\nexposure = 0.5\nev100 = 12.0\n"),
            "s.toml:2:12: output.exposure and output.ev100 are both given; give ev100 (the old "
            "exposure e is ev100 = log2(5333 / e))");
  EXPECT_EQ(error("[sun]\nilluminance = 20.0\nilluminance_lux = 1.0\n"),
            "s.toml:2:15: sun.illuminance and sun.illuminance_lux are both given; give "
            "illuminance_lux (the old illuminance is illuminance_lux / 6400)");
  EXPECT_EQ(error("[output]\nexposure = 0\n"),
            "s.toml:2:12: output.exposure = 0: must be in [5e-06, 1e+06] (the old linear "
            "exposure, read as output.ev100 = log2(5333 / exposure) in [-7.55, 30])");
  EXPECT_EQ(error("[sun]\nilluminance = -1\n"),
            "s.toml:2:15: sun.illuminance = -1: must be in [0, 1e+06] (the old radiance scale, "
            "read as x 6400 lux; sun.illuminance_lux replaces it)");
}

TEST(FieldOfView, ThreeFormsGiveTheVerticalForTheAspect) {
  CameraParams c;
  c.fov_deg = 50.0f;
  EXPECT_FLOAT_EQ(vertical_fov_deg(c, 1.5f), 50.0f);  // the vertical as given
  c.horizontal_fov_deg = 90.0f;
  // tan(v / 2) = tan(45 deg) / 1.5: v = 67.38 deg.
  EXPECT_NEAR(vertical_fov_deg(c, 1.5f), 2.0 * std::atan(1.0 / 1.5) * 180.0 / M_PI, 1e-4);
  EXPECT_NEAR(vertical_fov_deg(c, 1.0f), 90.0, 1e-4);  // square: the same
  c.horizontal_fov_deg = 0.0f;
  c.focal_length_mm = 50.0f;  // a 50 mm lens on full frame (36 x 24): 39.6 x 27.0 deg
  EXPECT_NEAR(horizontal_fov_from_focal_deg(50.0f, 36.0f), 39.5978, 1e-3);
  EXPECT_NEAR(vertical_fov_deg(c, 1.5f), 26.9915, 1e-3);
  c.sensor_width_mm = 24.0f;  // the same lens on a narrower sensor: narrower
  EXPECT_NEAR(vertical_fov_deg(c, 1.5f), 2.0 * std::atan(12.0 / 50.0 / 1.5) * 180.0 / M_PI, 1e-3);
  Scene s;
  s.camera = c;
  s.output.width = 300;
  s.output.height = 200;
  EXPECT_FLOAT_EQ(vertical_fov_deg(s), vertical_fov_deg(c, 1.5f));
}

TEST(FieldOfView, SceneFilesTakeOneForm) {
  const Scene lens = parse_scene_toml("[camera]\nfocal_length_mm = 35.0\n", "s.toml");
  EXPECT_EQ(lens.camera.focal_length_mm, 35.0f);
  // A file's form replaces its preset's.
  const std::string text =
      "[camera]\nhorizontal_fov_deg = 80.0\nsensor_width_mm = 24.0\n";
  const Scene h = parse_scene_toml(text, "s.toml");
  EXPECT_EQ(h.camera.horizontal_fov_deg, 80.0f);
  EXPECT_EQ(h.camera.focal_length_mm, 0.0f);
  // The writer writes the form given, and it reads back.
  Scene s;
  s.camera.focal_length_mm = 85.0f;
  s.camera.sensor_width_mm = 23.5f;
  const Scene back = parse_scene_toml(scene_to_toml(s), "dump.toml");
  EXPECT_EQ(back.camera.focal_length_mm, 85.0f);
  EXPECT_EQ(back.camera.sensor_width_mm, 23.5f);
  EXPECT_FLOAT_EQ(vertical_fov_deg(back), vertical_fov_deg(s));
  s.camera.focal_length_mm = 0.0f;
  s.camera.horizontal_fov_deg = 100.0f;
  EXPECT_EQ(parse_scene_toml(scene_to_toml(s), "dump.toml").camera.horizontal_fov_deg, 100.0f);
  try {
    parse_scene_toml("[camera]\nfov_deg = 40.0\nfocal_length_mm = 35.0\n", "s.toml");
    FAIL() << "two forms accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "s.toml:3:19: camera.fov_deg and camera.focal_length_mm are both given; give one "
              "of fov_deg, horizontal_fov_deg, focal_length_mm");
  }
}

}  // namespace
}  // namespace nephele

namespace nephele {

// Issue 41: the obvious call, write_image(frame.color, "x.png"), meters the image as a camera
// would: a daylit sky's cd/m^2 give a mid-grey PNG, not the all-white one an exposure of 1 did.
TEST(Exposure, WriteImageMetersAFramesLuminanceByDefault) {
  Image sky(16, 8);
  for (int y = 0; y < sky.height; ++y)
    for (int x = 0; x < sky.width; ++x)  // 2,000 to 9,000 cd/m^2: a clear day's sky
      sky.at(x, y) = glm::vec4(glm::vec3(2000.0f + 500.0f * float(x + y)), 1.0f);
  const std::string dir = std::string(NEPHELE_TEST_OUTPUT_DIR);
  std::filesystem::create_directories(dir);
  const std::string metered = dir + "/exposure_metered.png", raw = dir + "/exposure_raw.png";
  write_image(sky, metered);
  write_image(sky, raw, 1.0f);
  const auto mean_srgb8 = [](const Image& image) {  // read_image gives sRGB values / 255
    double sum = 0.0;
    for (const glm::vec4& p : image.pixels) sum += p.g;
    return 255.0 * sum / double(image.pixels.size());
  };
  const double metered_mean = mean_srgb8(read_image(metered));
  EXPECT_GT(metered_mean, 60.0);
  EXPECT_LT(metered_mean, 200.0);
  EXPECT_GT(mean_srgb8(read_image(raw)), 250.0);  // what the old default wrote
  // As the CLI exposes a still: the same bytes as still_exposure with the default output.
  write_image(sky, raw, still_exposure(OutputParams{}, sky));
  EXPECT_NEAR(mean_srgb8(read_image(raw)), metered_mean, 1e-9);
}

}  // namespace nephele

// Film output (render --layers, nephele/film.h): the multi-layer EXR read back with OpenEXR has
// its layers and header, and composites back to the image: R, G, B = clouds.RGB + (1 -
// clouds.A) sky.RGB within float precision; the holdout cuts the clouds out of the sky.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include <glm/geometric.hpp>

#include "nephele/error.h"

#include "nephele/exposure.h"
#include "nephele/film.h"
#include "nephele/scene_io.h"
#include "render_fixture.h"
#include "support/process_run.h"

namespace fs = std::filesystem;

namespace {

class FilmOutputTest : public RenderTest {
 protected:
  void SetUp() override {
    RenderTest::SetUp();
    dir_ = fs::temp_directory_path() / ("nephele_film_" + std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    fs::remove_all(dir_);
    RenderTest::TearDown();
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  static nephele::Scene scene() {
    nephele::Scene s = nephele::load_preset("default");
    s.output.width = 96;
    s.output.height = 64;
    s.location = {48.85f, 2.35f, 35.0f};
    s.camera.roll_deg = 10.0f;
    return s;
  }

  fs::path dir_;
};

glm::vec3 rgb(const std::string& file, const std::string& layer, size_t i) {
  const std::string prefix = layer.empty() ? "" : layer + ".";
  return {nephele::read_exr_channel(file, prefix + "R").pixels[i].r,
          nephele::read_exr_channel(file, prefix + "G").pixels[i].r,
          nephele::read_exr_channel(file, prefix + "B").pixels[i].r};
}

TEST_F(FilmOutputTest, LayersCompositeBackToTheImage) {
  const nephele::Scene s = scene();
  const nephele::FilmLayers layers = shared_renderer().render_layers(s);
  const std::string file = path("film.exr");
  nephele::write_film_exr(layers, s, file, {nephele::ExrPixels::kFloat, false, 14.5});

  // Every channel, read back by OpenEXR.
  std::map<std::string, nephele::Image> ch;
  for (const char* name : {"R", "G", "B", "A", "sky.R", "sky.G", "sky.B", "clouds.R", "clouds.G",
                           "clouds.B", "clouds.A", "clouds.depth_m"})
    ch[name] = nephele::read_exr_channel(file, name);
  EXPECT_THROW(nephele::read_exr_channel(file, "sky.A"), nephele::InputError);

  size_t cloudy = 0, clear = 0;
  double worst = 0.0;
  for (size_t i = 0; i < ch["R"].pixels.size(); ++i) {
    const float a = ch["clouds.A"].pixels[i].r;
    ASSERT_GE(a, 0.0f);
    ASSERT_LE(a, 1.0f);
    EXPECT_EQ(ch["A"].pixels[i].r, 1.0f);
    const char* const c[3] = {"R", "G", "B"};
    for (int k = 0; k < 3; ++k) {
      const float image = ch[c[k]].pixels[i].r;
      const float over = ch[std::string("clouds.") + c[k]].pixels[i].r +
                         (1.0f - a) * ch[std::string("sky.") + c[k]].pixels[i].r;
      worst = std::max(worst, double(std::abs(image - over)) / (std::abs(image) + 1e-3));
    }
    // The image is the frame render() made; the sky behind the clouds is never black.
    EXPECT_EQ(ch["R"].pixels[i].r, layers.frame.color.pixels[i].r);
    EXPECT_GT(ch["sky.G"].pixels[i].r, 0.0f);
    const float depth = ch["clouds.depth_m"].pixels[i].r;
    if (a > 0.5f) {
      ++cloudy;  // from the ground, the cloud base is 1500 m up at least
      EXPECT_GT(depth, 1500.0f);
      EXPECT_LT(depth, 3.0e5f);
    }
    if (a < 1e-4f) {
      ++clear;
      EXPECT_EQ(depth, 0.0f);
    }
  }
  std::printf("%zu cloudy, %zu clear pixels; worst relative error of the over: %.3g\n", cloudy,
              clear, worst);
  EXPECT_GT(cloudy, 100u);
  EXPECT_GT(clear, 100u);
  EXPECT_LT(worst, 1e-5);
}

TEST_F(FilmOutputTest, HeaderHoldsCameraPlaceTimeAndExposure) {
  nephele::Scene s = scene();
  s.camera.focal_length_mm = 35.0f;
  const nephele::FilmLayers layers = shared_renderer().render_layers(s);
  const std::string file = path("half.exr");
  nephele::write_film_exr(layers, s, file, {nephele::ExrPixels::kHalf, false, 14.5});
  std::map<std::string, std::string> h;
  for (const auto& [name, value] : nephele::read_exr_attributes(file)) h[name] = value;
  EXPECT_EQ(h["software"], "nephele 0.1.0");
  EXPECT_EQ(h["nephele.ev100"], "14.5");
  EXPECT_EQ(h["nephele.camera.position_m"], "0 0 2");
  EXPECT_EQ(h["nephele.camera.roll_deg"], "10");
  EXPECT_EQ(h["nephele.camera.focal_length_mm"], "35");
  EXPECT_EQ(h["nephele.camera.sensor_width_mm"], "36");
  EXPECT_EQ(h["latitude"], "48.85");
  EXPECT_EQ(h["longitude"], "2.35");
  EXPECT_EQ(h["altitude"], "37");
  EXPECT_EQ(h["nephele.time"], "none");
  EXPECT_EQ(h["nephele.holdout"], "false");
  // A 35 mm lens on full frame: 54.4 deg across; the vertical for 96 x 64 pixels.
  EXPECT_NEAR(std::stof(h["nephele.fov_horizontal_deg"]), 54.432f, 1e-3f);
  EXPECT_NEAR(std::stof(h["nephele.fov_vertical_deg"]), nephele::vertical_fov_deg(s), 1e-4f);
  EXPECT_NEAR(std::stof(h["nephele.exposure"]), nephele::exposure_from_ev100(14.5), 1e-9);
  ASSERT_TRUE(h.count("worldToCamera"));
  // worldToCamera (row vectors): the camera's position goes to the origin, the point 1 km
  // along the view direction to z = 1000 on the camera's axis.
  std::vector<float> m;
  for (std::string rest = h["worldToCamera"]; !rest.empty();) {
    const size_t space = rest.find(' ');
    m.push_back(std::stof(rest.substr(0, space)));
    rest = space == std::string::npos ? "" : rest.substr(space + 1);
  }
  ASSERT_EQ(m.size(), 16u);
  const auto apply = [&](glm::vec3 p) {
    glm::vec3 q;
    for (int c = 0; c < 3; ++c) q[c] = p.x * m[size_t(c)] + p.y * m[size_t(4 + c)] + p.z * m[size_t(8 + c)] + m[size_t(12 + c)];
    return q;
  };
  const glm::vec3 origin = apply(s.camera.position_m);
  EXPECT_NEAR(glm::length(origin), 0.0f, 1e-3f);
  const glm::vec3 ahead = apply(s.camera.position_m + 1000.0f * glm::normalize(s.camera.view_dir));
  EXPECT_NEAR(ahead.z, 1000.0f, 1e-2f);
  EXPECT_NEAR(glm::length(glm::vec2(ahead)), 0.0f, 1e-2f);
}

TEST_F(FilmOutputTest, HoldoutCutsTheCloudsOutOfTheSky) {
  const nephele::Scene s = scene();
  const nephele::FilmLayers layers = shared_renderer().render_layers(s);
  const nephele::Image held = nephele::film_beauty(layers, true);
  for (size_t i = 0; i < held.pixels.size(); ++i) {
    const float a = layers.clouds.pixels[i].a;
    EXPECT_FLOAT_EQ(held.pixels[i].a, 1.0f - a);
    EXPECT_FLOAT_EQ(held.pixels[i].g, (1.0f - a) * layers.sky.pixels[i].g);
    // The holdout and the clouds add up to the image.
    EXPECT_NEAR(held.pixels[i].g + layers.clouds.pixels[i].g, layers.frame.color.pixels[i].g,
                1e-5f * layers.frame.color.pixels[i].g + 1e-3f);
  }
}

TEST_F(FilmOutputTest, CliWritesLayersAndRefusesMisuse) {
  using nephele::test::run_cli;
  const std::string out = path("cli.exr");
  const auto r = run_cli("render --width 32 --height 24 --layers --holdout --ev100 12 -o " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  std::map<std::string, std::string> h;
  for (const auto& [name, value] : nephele::read_exr_attributes(out)) h[name] = value;
  EXPECT_EQ(h["nephele.holdout"], "true");
  EXPECT_EQ(h["nephele.ev100"], "12");
  EXPECT_NO_THROW(nephele::read_exr_channel(out, "clouds.depth_m"));
  const std::pair<std::string, std::string> bad[] = {
      {"--layers -o " + path("x.png"), "nephele: error: --layers '" + path("x.png") +
                                           "': needs an .exr output (-o name.exr)\n"},
      {"--holdout -o " + path("x.exr"),
       "nephele: error: --holdout needs --layers (it shapes the multi-layer EXR's image)\n"},
  };
  for (const auto& [args, message] : bad) {
    const auto refused = run_cli("render --width 8 --height 8 " + args);
    EXPECT_EQ(refused.status, 2) << args;
    EXPECT_EQ(refused.output, message);
    EXPECT_FALSE(fs::exists(path("x.png")) || fs::exists(path("x.exr")));
  }
}

}  // namespace

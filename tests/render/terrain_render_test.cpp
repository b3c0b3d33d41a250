// The terrain on the device (terrain.comp, compose.comp): a cloud's shadow lands where the cloud
// projects along the sun onto the terrain; a GeoTIFF's peak appears at the pixel its latitude,
// longitude and height project to; a mountain hides the sun and the clouds behind it while the
// clouds in front of it stay; the far terrain fades into the sky's haze at the horizon.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <glm/glm.hpp>

#include "nephele/camera_path.h"
#include "nephele/image.h"
#include "nephele/scene_io.h"
#include "render/frame_params.h"
#include "render/glsl.h"
#include "render_fixture.h"
#include "support/terrain_files.h"

namespace nephele {
namespace {

namespace fs = std::filesystem;

class TerrainRenderTest : public RenderTest {
 protected:
  void SetUp() override {
    RenderTest::SetUp();
    dir_ = fs::path(NEPHELE_TEST_OUTPUT_DIR) /
           ("terrain_render_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  // An EXR heightfield of w x h points (row 0 the north edge), heights in R.
  std::string write_heights(const std::string& name, int w, int h, const std::vector<float>& heights) const {
    Image image(w, h);
    for (size_t i = 0; i < heights.size(); ++i) image.pixels[i] = glm::vec4(heights[i], 0.0f, 0.0f, 1.0f);
    const std::string path = (dir_ / name).string();
    write_image(image, path, 1.0f, ExrPixels::kFloat);
    return path;
  }
  fs::path dir_;
};

Scene base_scene(int w, int h) {
  Scene s = load_preset("default");
  s.output.width = w;
  s.output.height = h;
  s.output.auto_exposure = false;
  s.quality.cloud_downsample = 1;
  return s;
}

// The direction of pixel (x, y) of the scene's camera (planet frame = ENU axes).
glm::vec3 pixel_ray(const Scene& s, float x, float y) {
  const CameraBasis b = camera_basis(s.camera);
  const float tan_half = std::tan(glm::radians(vertical_fov_deg(s)) * 0.5f);
  return glsl::camera_ray(b.forward, b.right, b.up, tan_half, float(s.output.width) / float(s.output.height), x,
                          y, float(s.output.width), float(s.output.height));
}

glm::vec2 project(const Scene& s, const glm::vec3& dir) {
  const CameraBasis b = camera_basis(s.camera);
  const float tan_half = std::tan(glm::radians(vertical_fov_deg(s)) * 0.5f);
  return glsl::camera_pixel(b.forward, b.right, b.up, tan_half, float(s.output.width) / float(s.output.height),
                            dir, float(s.output.width), float(s.output.height));
}

// Bilinear lookup of channel c of an image at continuous pixel coordinates; NaN outside.
float lookup(const Image& image, glm::vec2 p, int c) {
  if (!(p.x >= 0.0f && p.y >= 0.0f && p.x <= float(image.width - 1) && p.y <= float(image.height - 1)))
    return std::nanf("");
  const int x0 = std::min(int(p.x), image.width - 2), y0 = std::min(int(p.y), image.height - 2);
  const float fx = p.x - float(x0), fy = p.y - float(y0);
  const auto v = [&](int x, int y) { return image.at(x, y)[c]; };
  return (v(x0, y0) * (1 - fx) + v(x0 + 1, y0) * fx) * (1 - fy) + (v(x0, y0 + 1) * (1 - fx) + v(x0 + 1, y0 + 1) * fx) * fy;
}

TEST_F(TerrainRenderTest, CloudShadowLandsWhereTheCloudProjectsAlongTheSun) {
  // A flat terrain 500 m high, a thin cloud layer at 2000-2100 m, the sun 45 deg up in the
  // east; the camera 6 km up looking straight down. The shadow of the cloud at (x, y, 2050)
  // falls at (x - 1550, y, 500).
  Scene s = base_scene(128, 128);
  s.terrain.file = write_heights("flat.exr", 2, 2, {1.0f, 1.0f, 1.0f, 1.0f});
  s.terrain.extent_m = glm::vec2(40000.0f);
  s.terrain.height_m = 500.0f;
  s.clouds.bottom_altitude_m = 2000.0f;
  s.clouds.top_altitude_m = 2100.0f;
  s.clouds.coverage = 0.5f;
  s.clouds.type = 0.0f;
  s.clouds.density = 1.0f;
  s.sun.direction = glm::normalize(glm::vec3(1.0f, 0.0f, 1.0f));
  s.camera.position_m = glm::vec3(0.0f, 0.0f, 6000.0f);
  s.camera.view_dir = glm::vec3(0.0f, 1e-4f, -1.0f);
  s.camera.fov_deg = 60.0f;
  const FilmLayers layers = shared_renderer().render_layers(s);
  const glm::vec3 eye = s.camera.position_m;
  // Terrain points and their darkness (1 - luminance / the lit ground's).
  std::vector<float> lum;
  for (const glm::vec4& p : layers.sky.pixels) lum.push_back(float(luminance(p)));
  std::vector<float> sorted = lum;
  std::sort(sorted.begin(), sorted.end());
  const float lit = sorted[sorted.size() * 95 / 100];
  struct Point {
    glm::vec2 xy;
    float dark;
  };
  std::vector<Point> ground;
  for (int y = 0; y < s.output.height; ++y)
    for (int x = 0; x < s.output.width; ++x) {
      const glm::vec3 d = pixel_ray(s, float(x), float(y));
      ground.push_back({glm::vec2(eye + d * ((eye.z - 500.0f) / -d.z)), 1.0f - lum[size_t(y * s.output.width + x)] / lit});
    }
  // The cloud's opacity at (x, y, 2050), from the clouds layer.
  const auto opacity = [&](glm::vec2 xy) {
    return lookup(layers.clouds, project(s, glm::normalize(glm::vec3(xy, 2050.0f) - eye)), 3);
  };
  // The correlation of the shadow with the cloud shifted by v, over the points both cover.
  const auto correlation = [&](glm::vec2 v) {
    double n = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    for (const Point& p : ground) {
      const float c = opacity(p.xy + v);
      if (std::isnan(c)) continue;
      n += 1;
      sa += p.dark;
      sb += c;
      saa += double(p.dark) * p.dark;
      sbb += double(c) * c;
      sab += double(p.dark) * c;
    }
    const double cov = sab / n - sa / n * sb / n;
    return cov / std::sqrt(std::max((saa / n - sa * sa / (n * n)) * (sbb / n - sb * sb / (n * n)), 1e-20));
  };
  glm::vec2 best(0.0f);
  double best_r = -2.0;
  for (float vx = 500.0f; vx <= 2600.0f; vx += 25.0f)
    for (float vy = -400.0f; vy <= 400.0f; vy += 50.0f)
      if (const double r = correlation({vx, vy}); r > best_r) {
        best_r = r;
        best = {vx, vy};
      }
  std::printf("the shadow matches the cloud %.0f m east, %.0f m north of it (r = %.2f; expected 1550, 0)\n",
              best.x, best.y, best_r);
  // The layer seen from above glints in a grid of dots where it is thin (the march's sampling
  // of a 100 m layer), which keeps the correlation from 1; no shadow at all gives about 0.
  EXPECT_GT(best_r, 0.3);
  // Within a ground pixel and a half (about 50 m each).
  EXPECT_NEAR(best.x, 1550.0f, 75.0f);
  EXPECT_NEAR(best.y, 0.0f, 75.0f);
}

TEST_F(TerrainRenderTest, GeoTiffPeakAppearsWhereItsCoordinatesProject) {
  // A Gaussian peak 1800 m above a 500 m plain (sigma 400 m) on 161 x 161 cells of 0.0005 deg;
  // the scene 10 km south of it at the plain's height, the camera 100 m up.
  const int n = 161;
  const double north = 46.60, west = 8.00, cell = 0.0005;
  const double peak_lat = north - 80.5 * cell, peak_lon = west + 80.5 * cell;
  Scene s = base_scene(96, 64);
  s.location.lat_deg = float(peak_lat - 0.09);
  s.location.lon_deg = float(peak_lon);
  s.location.altitude_m = 500.0f;
  std::vector<float> h(size_t(n * n));
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double dn = (y - 80) * cell * 111195.0, de = (x - 80) * cell * 111195.0 * std::cos(glm::radians(peak_lat));
      h[size_t(y * n + x)] = float(500.0 + 1800.0 * std::exp(-(dn * dn + de * de) / (2.0 * 400.0 * 400.0)));
    }
  s.terrain.file = (dir_ / "peak.tif").string();
  test::write_geotiff(s.terrain.file, n, n, h, north, west, cell);
  s.clouds.coverage = 0.0f;
  s.camera.position_m = glm::vec3(0.0f, 0.0f, 100.0f);
  const glm::dvec3 peak = enu_from_lat_lon(s, peak_lat, peak_lon, 1800.0);
  s.camera.view_dir = glm::vec3(glm::normalize(peak - glm::dvec3(s.camera.position_m)));
  s.camera.fov_deg = 10.0f;
  // Terrain pixels: those that change with its albedo.
  s.terrain.albedo = glm::vec3(0.0f);
  const Frame dark = render(s);
  s.terrain.albedo = glm::vec3(1.0f);
  const Frame bright = render(s);
  int top = -1;
  double sum_x = 0.0;
  int count = 0;
  for (int y = 0; y < s.output.height && top < 0; ++y)
    for (int x = 0; x < s.output.width; ++x) {
      const size_t i = size_t(y * s.output.width + x);
      if (luminance(bright.color.pixels[i]) > 1.02 * luminance(dark.color.pixels[i]) + 1e-3) {
        top = y;
        sum_x += x;
        ++count;
      }
    }
  ASSERT_GE(top, 0) << "no terrain in view";
  // The peak's place in the planet frame: its east and north, |p| = R + 1800 m.
  const double r = double(s.atmosphere.planet_radius_km) * 1000.0;
  const glm::dvec3 p(peak.x, peak.y, std::sqrt((r + 1800.0) * (r + 1800.0) - peak.x * peak.x - peak.y * peak.y));
  const glm::dvec3 eye(0.0, 0.0, r + 100.0);
  const glm::vec2 expected = project(s, glm::vec3(glm::normalize(p - eye)));
  std::printf("the peak's top pixel (%.1f, %d), its coordinates project to (%.2f, %.2f)\n", sum_x / count, top,
              expected.x, expected.y);
  EXPECT_NEAR(sum_x / count, expected.x, 1.5);
  EXPECT_NEAR(float(top), expected.y, 1.5);
}

TEST_F(TerrainRenderTest, MountainHidesTheSunAndTheCloudsBehindItButNotThoseInFront) {
  // A plateau 2000 m high from 20 to 24 km north, 40 km wide; the sun 5 deg up behind it; clouds
  // at 1200-3000 m. The camera on the ground looks north.
  Scene s = base_scene(96, 64);
  s.terrain.file = write_heights("wall.exr", 2, 2, {1.0f, 1.0f, 1.0f, 1.0f});
  s.terrain.extent_m = glm::vec2(40000.0f, 4000.0f);
  s.terrain.center_m = glm::vec2(0.0f, 22000.0f);
  s.terrain.height_m = 2000.0f;
  s.sun.direction = glm::vec3(0.0f, std::cos(glm::radians(5.0f)), std::sin(glm::radians(5.0f)));
  s.clouds.bottom_altitude_m = 1200.0f;
  s.clouds.top_altitude_m = 3000.0f;
  s.clouds.coverage = 0.6f;
  s.camera.view_dir = glm::vec3(0.0f, 1.0f, std::tan(glm::radians(5.0f)));
  s.camera.fov_deg = 20.0f;
  Scene bare = s;
  bare.terrain.file.clear();
  // The sun, in a clear sky.
  const auto brightest = [](Scene scene) {
    scene.clouds.coverage = 0.0f;
    double most = 0.0;
    for (const glm::vec4& p : render(scene).color.pixels) most = std::max(most, double(luminance(p)));
    return most;
  };
  const double sun_with = brightest(s), sun_without = brightest(bare);
  std::printf("the brightest pixel: %.3g cd/m^2 with the mountain, %.3g without (the sun)\n", sun_with, sun_without);
  EXPECT_GT(sun_without, 1e6);
  EXPECT_LT(sun_with, 1e-3 * sun_without);
  const FilmLayers with = shared_renderer().render_layers(s);
  const FilmLayers without = shared_renderer().render_layers(bare);
  // Rays below 3 deg enter the cloud layer beyond the plateau (1200 m / sin 3 deg = 23 km);
  // rays between 4.3 and 5.2 deg pass through it in front of the plateau's face.
  double hidden_with = 0.0, hidden_without = 0.0, front_with = 0.0;
  for (int y = 0; y < s.output.height; ++y)
    for (int x = 0; x < s.output.width; ++x) {
      const glm::vec3 d = pixel_ray(s, float(x), float(y));
      const float elevation = glm::degrees(std::asin(d.z)), azimuth = glm::degrees(std::atan2(d.x, d.y));
      if (std::abs(azimuth) > 15.0f) continue;
      const size_t i = size_t(y * s.output.width + x);
      if (elevation > 0.5f && elevation < 3.0f) {
        hidden_with = std::max(hidden_with, double(with.clouds.pixels[i].a));
        hidden_without = std::max(hidden_without, double(without.clouds.pixels[i].a));
      }
      if (elevation > 4.3f && elevation < 5.2f) front_with = std::max(front_with, double(with.clouds.pixels[i].a));
    }
  std::printf("cloud opacity behind the plateau: %.3f (%.3f without it); in front of it %.3f\n", hidden_with,
              hidden_without, front_with);
  EXPECT_GT(hidden_without, 0.3);  // there are clouds there to hide
  EXPECT_LT(hidden_with, 0.01);
  EXPECT_GT(front_with, 0.3);
}

TEST_F(TerrainRenderTest, PeakThroughACloudDeckIsSunlitAboveItAndHiddenInIt) {
  // A cone 3000 m high through a closed deck at 1000-2500 m (its cumulus tops reach about
  // 1800 m), seen from 3.2 km up, 8 km south, the sun behind the camera: its top stands clear
  // in the sun, its lower flanks are in the cloud.
  const int n = 65;
  std::vector<float> cone(size_t(n * n));
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      cone[size_t(y * n + x)] = std::max(0.0f, 1.0f - glm::length(glm::vec2(x - 32, y - 32)) / 32.0f);
  Scene s = base_scene(64, 64);
  s.terrain.file = write_heights("cone.exr", n, n, cone);
  s.terrain.extent_m = glm::vec2(6400.0f);
  s.terrain.height_m = 3000.0f;
  s.clouds.bottom_altitude_m = 1000.0f;
  s.clouds.top_altitude_m = 2500.0f;
  s.clouds.coverage = 1.0f;
  s.sun.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.8f));
  s.camera.position_m = glm::vec3(0.0f, -8000.0f, 3200.0f);
  s.camera.view_dir = glm::normalize(glm::vec3(0.0f, 8000.0f, 2600.0f - 3200.0f));
  s.camera.fov_deg = 30.0f;
  const FilmLayers layers = shared_renderer().render_layers(s);
  // Along the image's middle column: the summit's pixels (rays that meet the cone above the
  // deck's top) and the lower flank's (rays that meet it deep in the deck).
  const glm::vec3 eye = s.camera.position_m;
  double top_opacity = 0.0, top_luminance = 1e30, flank_opacity = 1.0;
  int tops = 0, flanks = 0;
  for (int y = 0; y < s.output.height; ++y) {
    const glm::vec3 d = pixel_ray(s, 32.0f, float(y));
    // Where the ray meets the cone (flat earth is close enough over 8 km): march it.
    float hit_z = -1.0f;
    for (float t = 0.0f; t < 12000.0f; t += 2.0f) {
      const glm::vec3 p = eye + d * t;
      if (p.z <= 3000.0f * std::max(0.0f, 1.0f - glm::length(glm::vec2(p)) / 3200.0f)) {
        hit_z = p.z;
        break;
      }
    }
    const size_t i = size_t(y * s.output.width + 32);
    if (hit_z > 2650.0f) {
      top_opacity = std::max(top_opacity, double(layers.clouds.pixels[i].a));
      top_luminance = std::min(top_luminance, double(luminance(layers.frame.color.pixels[i])));
      ++tops;
    } else if (hit_z > 1000.0f && hit_z < 1500.0f) {
      flank_opacity = std::min(flank_opacity, double(layers.clouds.pixels[i].a));
      ++flanks;
    }
  }
  std::printf("summit: %d pixels, cloud opacity at most %.3f, luminance at least %.0f cd/m^2; flank in "
              "the deck: %d pixels, cloud opacity at least %.3f\n", tops, top_opacity, top_luminance, flanks,
              flank_opacity);
  ASSERT_GE(tops, 3);
  ASSERT_GE(flanks, 3);
  EXPECT_LT(top_opacity, 0.05);   // no cloud drawn over the summit
  EXPECT_GT(flank_opacity, 0.9);  // the deck hides the flank
  // Sunlit as under a clear sky (the deck takes only some of its sky light), not shadowed.
  Scene clear = s;
  clear.clouds.coverage = 0.0f;
  const Frame bare = render(clear);
  double clear_luminance = 1e30;
  for (int y = 0; y < s.output.height; ++y)
    if (layers.clouds.pixels[size_t(y * s.output.width + 32)].a < 0.05f && pixel_ray(s, 32.0f, float(y)).z < -0.02f)
      clear_luminance = std::min(clear_luminance, double(luminance(bare.color.pixels[size_t(y * s.output.width + 32)])));
  std::printf("the summit's darkest pixel: %.0f cd/m^2 over the deck, %.0f under a clear sky\n", top_luminance,
              clear_luminance);
  EXPECT_GT(top_luminance, 0.7 * clear_luminance);
}

TEST_F(TerrainRenderTest, FarTerrainFadesIntoTheHazeAtTheHorizon) {
  // A plain 200 m high, 600 km across, in hazy air; the camera 1 km up looking at the horizon.
  Scene s = base_scene(32, 96);
  s.terrain.file = write_heights("plain.exr", 2, 2, {1.0f, 1.0f, 1.0f, 1.0f});
  s.terrain.extent_m = glm::vec2(600000.0f);
  s.terrain.height_m = 200.0f;
  s.clouds.coverage = 0.0f;
  s.atmosphere.mie_extinction_per_m *= 4.0f;
  s.atmosphere.mie_scattering_per_m *= 4.0f;
  s.camera.position_m = glm::vec3(0.0f, 0.0f, 1000.0f);
  s.camera.view_dir = glm::vec3(0.0f, 1.0f, -std::tan(glm::radians(4.0f)));
  s.camera.fov_deg = 16.0f;
  const Frame f = render(s);
  // The horizon is 0.9 deg below the level (the plain 800 m below the camera, curved away).
  int horizon = -1;  // the first row of terrain from the top
  for (int y = 0; y < s.output.height && horizon < 0; ++y)
    if (pixel_ray(s, 16.0f, float(y)).z < -std::sin(glm::radians(0.9f))) horizon = y;
  ASSERT_GT(horizon, 2);
  ASSERT_LT(horizon, s.output.height - 10);
  const auto difference = [&](int y) {  // relative to the sky just above the horizon
    const glm::vec3 sky(f.color.at(16, horizon - 2)), here(f.color.at(16, y));
    return glm::length(here - sky) / glm::length(sky);
  };
  const double far = difference(horizon + 1), near = difference(s.output.height - 1);
  std::printf("terrain against the horizon's sky: %.3f just below the horizon, %.3f at the bottom row\n", far, near);
  // Without the air in front the plain would differ from the sky as much far as near.
  EXPECT_LT(far, 0.3);
  EXPECT_LT(far, 0.5 * near);
}

TEST_F(TerrainRenderTest, AlbedoMapColoursTheGroundAndPngsAreDecodedFromSrgb) {
  // A plain seen from straight above, its west half under a red albedo, its east half green.
  Scene s = base_scene(32, 32);
  s.terrain.file = write_heights("plain.exr", 2, 2, {1.0f, 1.0f, 1.0f, 1.0f});
  s.terrain.extent_m = glm::vec2(4000.0f);
  s.terrain.height_m = 100.0f;
  s.clouds.coverage = 0.0f;
  s.camera.position_m = glm::vec3(0.0f, 0.0f, 2000.0f);
  s.camera.view_dir = glm::vec3(0.0f, 1e-4f, -1.0f);
  s.camera.fov_deg = 40.0f;
  Image halves(8, 1);  // texels of 500 m; filtered bilinearly, pure within the halves' middles
  for (int x = 0; x < 8; ++x)
    halves.pixels[size_t(x)] = x < 4 ? glm::vec4(0.5f, 0.0f, 0.0f, 1.0f) : glm::vec4(0.0f, 0.5f, 0.0f, 1.0f);
  s.terrain.albedo_map = (dir_ / "halves.exr").string();
  write_image(halves, s.terrain.albedo_map, 1.0f, ExrPixels::kFloat);
  const Frame split = render(s);
  const glm::vec4 west = split.color.at(4, 16), east = split.color.at(27, 16);
  EXPECT_GT(west.r, 5.0f * west.g);
  EXPECT_GT(east.g, 5.0f * east.r);
  // A grey of linear 0.5 three ways: the colour, an EXR, an 8-bit sRGB PNG (188 = 0.503).
  const auto centre = [&](Scene scene) { return double(luminance(render(scene).color.at(16, 16))); };
  Scene grey = s;
  grey.terrain.albedo_map.clear();
  grey.terrain.albedo = glm::vec3(0.5f);
  const double plain = centre(grey);
  Image flat(1, 1);
  flat.pixels = {glm::vec4(0.5f, 0.5f, 0.5f, 1.0f)};
  grey.terrain.albedo_map = (dir_ / "grey.exr").string();
  write_image(flat, grey.terrain.albedo_map, 1.0f, ExrPixels::kFloat);
  const double exr = centre(grey);
  grey.terrain.albedo_map = (dir_ / "grey.png").string();  // the writer encodes 0.5 as sRGB 188
  write_image(flat, grey.terrain.albedo_map, 1.0f, ExrPixels::kHalf, ToneMap::None);
  ASSERT_EQ(int(std::lround(read_image(grey.terrain.albedo_map).pixels[0].r * 255.0f)), 188);
  const double png = centre(grey);
  std::printf("a grey plain: %.1f (colour), %.1f (EXR map), %.1f (sRGB PNG map) cd/m^2\n", plain, exr, png);
  EXPECT_NEAR(exr / plain, 1.0, 0.01);
  EXPECT_NEAR(png / plain, 1.0, 0.02);  // read as linear, 188 would give 1.47 times
}

TEST_F(TerrainRenderTest, MeshDrawnWithDepthSeesWhatTheRayCastSees) {
  // Seed 002's way (the heightfield as a mesh, rasterised with depth) against the ray cast.
  Scene s = load_preset("mountains");
  s.output.width = 160;
  s.output.height = 100;
  s.output.auto_exposure = false;
  s.quality.cloud_downsample = 1;
  s.terrain.resolution = 256;
  const Frame cast = render(s);
  s.terrain.method = "raster";
  const Frame mesh = render(s);
  double sum = 0.0, total = 0.0;
  int differing = 0;
  for (size_t i = 0; i < cast.color.pixels.size(); ++i) {
    const double a = luminance(cast.color.pixels[i]), b = luminance(mesh.color.pixels[i]);
    sum += std::abs(a - b);
    total += a;
    differing += std::abs(a - b) > 0.05 * a;
  }
  std::printf("mesh against ray cast: mean |difference| %.4f of the mean luminance, %d of %zu pixels "
              "differ by more than 5%%\n", sum / total, differing, cast.color.pixels.size());
  EXPECT_LT(sum / total, 0.01);
  EXPECT_LT(differing, int(cast.color.pixels.size() / 100));  // silhouettes' pixels
}

}  // namespace
}  // namespace nephele

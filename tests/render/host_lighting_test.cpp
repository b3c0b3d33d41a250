// The lighting the frame gives a host (nephele::HostLighting, the cloud shadow map; issue 25),
// against the tables and the image it was made with.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "nephele/error.h"
#include "nephele/frame.h"
#include "nephele/scene_io.h"
#include "render/frame_renderer_impl.h"
#include "render/glsl.h"
#include "render/passes.h"
#include "render_fixture.h"

namespace nephele {
namespace {

// One still frame of `scene` with the host's lighting, completed and collected.
FrameImages lit_frame(FrameRenderer::Impl& impl, const Scene& scene,
                      HostLightingOptions lighting = {}) {
  FrameOptions options;
  options.still = true;
  options.lighting = lighting;
  options.lighting.enabled = true;
  FrameImages images;
  impl.ctx.submit_and_wait(
      [&](VkCommandBuffer cmd) { images = impl.record_frame(cmd, scene, options); });
  impl.collect(images.slot);
  return images;
}

// The sky-view table's radiance from direction d (per unit key-light illuminance), as
// sky_light_inc.glsl's sky_radiance reads it.
glm::vec3 table_radiance(const Image& lut, const gpu::FrameParams& params, const glm::vec3& d) {
  const glsl::sampler2D table{lut.pixels.data(), lut.width, lut.height};
  const glsl::SkyViewFrame f =
      glsl::sky_view_frame_from(params.sky_view_up, params.sky_view_forward);
  const glm::vec2 uv = glsl::sky_view_uv(f, d);
  const float rows = float(lut.height / 2);
  glm::vec3 l = glm::vec3(glsl::textureLod(table, glsl::sky_view_texcoord(uv, rows, 0.0f), 0.0f));
  if (uv.y < 0.5f)
    l += glm::vec3(glsl::textureLod(table, glsl::sky_view_texcoord(uv, rows, 1.0f), 0.0f));
  return l;
}

// The sum of f(d, radiance from d) dw over the sphere, 256 x 512 cells of equal solid angle.
template <typename T, typename F>
T over_sphere(const Image& lut, const gpu::FrameParams& params, F f) {
  const int rows = 256, columns = 512;
  T sum{};
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      const float z = 1.0f - 2.0f * (float(r) + 0.5f) / float(rows);
      const float phi = (float(c) + 0.5f) / float(columns) * 2.0f * 3.14159265f;
      const float s = std::sqrt(std::max(1.0f - z * z, 0.0f));
      const glm::vec3 d(s * std::cos(phi), s * std::sin(phi), z);
      f(sum, d,
        glm::dvec3(table_radiance(lut, params, d)) *
            (4.0 * 3.14159265358979 / double(rows * columns)));
    }
  return sum;
}

// The irradiance on a surface facing n: the table's radiance times the cosine.
glm::dvec3 table_irradiance(const Image& lut, const gpu::FrameParams& params, const glm::vec3& n) {
  return over_sphere<glm::dvec3>(lut, params,
                                 [&](glm::dvec3& sum, const glm::vec3& d, const glm::dvec3& l_dw) {
                                   sum += l_dw * double(std::max(glm::dot(d, n), 0.0f));
                                 });
}

// The table's radiance projected on the nine real spherical harmonics (HostLighting's order).
std::array<glm::dvec3, 9> table_sh(const Image& lut, const gpu::FrameParams& params) {
  using Sh = std::array<glm::dvec3, 9>;
  return over_sphere<Sh>(lut, params, [](Sh& sum, const glm::vec3& d, const glm::dvec3& l_dw) {
    const glsl::Sh9 y = glsl::sh9_basis(d);
    for (int k = 0; k < 9; ++k) sum[k] += l_dw * double(y.y[k]);
  });
}

TEST(HostLighting, SkyIrradianceMatchesAnIntegralOfTheSkyViewTable) {
  FrameRenderer::Impl impl(validated());
  for (const char* preset : {"clear", "sunset"}) {
    Scene scene = load_preset(preset);
    scene.output.width = 32;
    scene.output.height = 24;
    lit_frame(impl, scene);
    ASSERT_TRUE(impl.completed_lighting.has_value());
    const HostLighting& lighting = *impl.completed_lighting;
    const Image lut = download(impl.ctx, impl.sky_view.lut(), true);  // rgba16f
    // The coefficients: the device's projection (64 x 128 cells) against the CPU's (256 x 512).
    const std::array<glm::dvec3, 9> sh = table_sh(lut, impl.last_params);
    const double lux = scene.sun.illuminance_lux * lighting.sky_cloud_share;
    for (int k = 0; k < 9; ++k)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(lighting.sky_radiance_sh[k][c], sh[k][c] * lux, 0.01 * sh[0][c] * lux)
            << preset << " coefficient " << k << " channel " << c;
    const glm::vec3 sun = lighting.sun_direction;
    const glm::vec3 towards_sun = glm::normalize(glm::vec3(sun.x, sun.y, 0.0f));
    const glm::vec3 normals[] = {{0, 0, 1}, towards_sun, -towards_sun, {0, 0, -1}};
    glm::dvec3 expected[4];
    glm::dvec3 brightest(0.0);
    for (int i = 0; i < 4; ++i) {
      expected[i] = table_irradiance(lut, impl.last_params, normals[i]) * lux;
      brightest = glm::max(brightest, expected[i]);
    }
    // The irradiance against the exact integral: nine coefficients cannot hold the step at the
    // horizon, and ring by up to 6% of the brightest irradiance (5.3% at sunset, facing up and
    // down, in red).
    for (int i = 0; i < 4; ++i) {
      const glm::vec3& n = normals[i];
      const glm::vec3 got = lighting.sky_irradiance_lux(n);
      std::printf(
          "%s, normal (%.2f, %.2f, %.2f): SH %.1f lux, the table's integral %.1f lux (green)\n",
          preset, n.x, n.y, n.z, got.g, expected[i].g);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], expected[i][c], 0.06 * brightest[c])
            << preset << " channel " << c << " normal " << n.x << "," << n.y << "," << n.z;
    }
    std::printf("%s: the clouds pass %.3f of the sky's light, %.3f of the sun's\n", preset,
                lighting.sky_cloud_share, lighting.sun_cloud_transmittance);
    if (std::string(preset) == "clear") {  // no cloud dims the light
      EXPECT_NEAR(lighting.sun_cloud_transmittance, 1.0f, 1e-3f);
      EXPECT_NEAR(lighting.sky_cloud_share, 1.0f, 1e-3f);
    }
    EXPECT_GT(lighting.sun_illuminance_lux.g, 0.0f);
    EXPECT_LT(lighting.sun_illuminance_lux.g, scene.sun.illuminance_lux);
    EXPECT_FALSE(lighting.inside_cloud);
  }
  EXPECT_EQ(impl.ctx.validation_messages(), 0);
}

// A single-channel float texture's texels, in the red channel.
Image download_r32f(gpu::Context& ctx, const gpu::Texture& texture) {
  Image image(int(texture.width()), int(texture.height()));
  gpu::Buffer staging(ctx, VkDeviceSize(image.pixels.size() * 4), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { texture.record_download(cmd, staging); });
  const auto* texels = static_cast<const float*>(staging.data());
  for (size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = glm::vec4(texels[i], 0.0f, 0.0f, 1.0f);
  return image;
}

// The map's value at ENU point p through `matrix`, bilinear with the edges clamped (as a
// host's sampler reads it).
float shadow_at(const Image& map, const glm::mat4& matrix, const glm::vec3& p) {
  const glm::vec4 uv = matrix * glm::vec4(p, 1.0f);
  const glsl::sampler2D texture{map.pixels.data(), map.width, map.height};
  return glsl::textureLod(texture, glm::vec2(uv), 0.0f).r;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double ma = 0, mb = 0;
  for (size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
  ma /= double(a.size()), mb /= double(b.size());
  double ab = 0, aa = 0, bb = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    ab += (a[i] - ma) * (b[i] - mb);
    aa += (a[i] - ma) * (a[i] - ma);
    bb += (b[i] - mb) * (b[i] - mb);
  }
  return ab / std::sqrt(aa * bb);
}

// Spearman's: the correlation of the values' ranks, 1 for any increasing relation.
double rank_correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const auto ranks = [](const std::vector<double>& v) {
    std::vector<size_t> order(v.size());
    for (size_t i = 0; i < v.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t i, size_t j) { return v[i] < v[j]; });
    std::vector<double> r(v.size());
    for (size_t k = 0; k < order.size(); ++k) r[order[k]] = double(k);
    return r;
  };
  return correlation(ranks(a), ranks(b));
}

// Looking straight down from under broken clouds at the sunlit ground: its brightness follows
// the clouds' shadows, and the map through its matrix must hold the same shadows at the same
// ground points (in rank: the ground's light grows with the map's transmittance, but not in
// proportion, the clouds' own light on the ground being shared with it). Looked up straight above
// each point instead (the light's slant ignored, 1.2 km at this sun), the shadows land elsewhere.
TEST(HostLighting, TheShadowMapsMatrixPutsTheCloudsGroundShadowsWhereTheImageHasThem) {
  FrameRenderer::Impl impl(validated());
  Scene scene = load_preset("broken");
  scene.output.width = 64;
  scene.output.height = 64;
  scene.camera.position_m = glm::vec3(0.0f, 0.0f, 800.0f);
  scene.camera.view_dir = glm::vec3(0.0f, 0.001f, -1.0f);
  scene.camera.fov_deg = 90.0f;
  scene.sun.direction = glm::normalize(glm::vec3(0.3f, -0.6f, 0.75f));
  HostLightingOptions options;
  options.shadow_map_extent_m = 6000.0f;
  options.shadow_map_size = 512;
  const FrameImages images = lit_frame(impl, scene, options);
  const Image map = download_r32f(impl.ctx, impl.host_lighting.shadow_map());
  const Frame frame = impl.download_last(scene);
  // Where the light through a ground point crosses the clouds' bottom, less the ground point:
  // undone, a point reads the map straight above itself.
  const float base_m = impl.last_params.radii_m.z - impl.last_params.radii_m.x;
  const glm::vec3 slant = glm::vec3(scene.sun.direction.x, scene.sun.direction.y, 0.0f) /
                          scene.sun.direction.z * base_m;
  const CameraBasis basis = camera_basis(scene.camera);
  const float tan_half = std::tan(glm::radians(scene.camera.fov_deg) * 0.5f);
  std::vector<double> brightness, slanted, straight;
  double lo = 1.0, hi = 0.0;
  for (int y = 0; y < frame.color.height; ++y)
    for (int x = 0; x < frame.color.width; ++x) {
      const glm::vec3 dir =
          glsl::camera_ray(basis.forward, basis.right, basis.up, tan_half, 1.0f, float(x), float(y),
                           float(frame.color.width), float(frame.color.height));
      const glm::vec3 ground = scene.camera.position_m + dir * (scene.camera.position_m.z / -dir.z);
      brightness.push_back(luminance(frame.color.at(x, y)));
      slanted.push_back(shadow_at(map, images.world_to_cloud_shadow, ground));
      straight.push_back(shadow_at(map, images.world_to_cloud_shadow, ground - slant));
      lo = std::min(lo, slanted.back()), hi = std::max(hi, slanted.back());
    }
  const double along_light = rank_correlation(brightness, slanted),
               straight_above = rank_correlation(brightness, straight);
  std::printf(
      "the ground's brightness against the map: correlation %.3f along the light, %.3f straight "
      "above; "
      "the map's shadows from %.2f to %.2f\n",
      along_light, straight_above, lo, hi);
  EXPECT_LT(lo, 0.3) << "the view should hold cloud shadows";
  EXPECT_GT(hi - lo, 0.5) << "and sunlit ground";
  // Measured: 0.88 along the light, -0.12 straight above (Pearson's before the clouds' own
  // light on the ground: over 0.9).
  EXPECT_GT(along_light, 0.8);
  EXPECT_LT(straight_above, 0.5);
  EXPECT_EQ(impl.ctx.validation_messages(), 0);
}

// A Vulkan cube map's texel direction (environment.comp's cube_direction), ENU.
glm::vec3 cube_direction(int face, glm::vec2 st) {
  const glm::vec3 d = face == 0   ? glm::vec3(1.0f, -st.y, -st.x)
                      : face == 1 ? glm::vec3(-1.0f, -st.y, st.x)
                      : face == 2 ? glm::vec3(st.x, 1.0f, st.y)
                      : face == 3 ? glm::vec3(st.x, -1.0f, -st.y)
                      : face == 4 ? glm::vec3(st.x, -st.y, 1.0f)
                                  : glm::vec3(-st.x, -st.y, -1.0f);
  return glm::normalize(d);
}

// Without clouds the environment is the sky-view table's sky and ground; under an overcast
// deck its zenith is the deck's light as the view renders it looking up.
TEST(HostLighting, TheEnvironmentHoldsTheSkyAndTheClouds) {
  FrameRenderer::Impl impl(validated());
  Scene scene = load_preset("clear");
  scene.output.width = 32;
  scene.output.height = 32;
  HostLightingOptions options;
  options.environment_size = 16;
  FrameImages images = lit_frame(impl, scene, options);
  ASSERT_NE(images.environment, VK_NULL_HANDLE);
  const Image clear = download(impl.ctx, impl.host_lighting.environment(), true);
  ASSERT_EQ(clear.width, 6 * 16);
  ASSERT_EQ(clear.height, 16);
  const Image lut = download(impl.ctx, impl.sky_view.lut(), true);
  double worst = 0.0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 96; ++x) {
      const int face = x / 16;
      const glm::vec2 st = (glm::vec2(x - 16 * face, y) + 0.5f) / 16.0f * 2.0f - 1.0f;
      const glm::vec3 expected = table_radiance(lut, impl.last_params, cube_direction(face, st)) *
                                 glm::vec3(impl.last_params.sun_illuminance);
      const glm::vec3 got(clear.at(x, y));
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, std::abs(double(got[c]) / double(expected[c]) - 1.0));
        EXPECT_NEAR(got[c], expected[c], 0.01f * expected[c] + 1e-3f)
            << "face " << face << " texel " << x << "," << y;
      }
    }
  std::printf("clear environment against the sky-view table: largest difference %.3f%%\n",
              100.0 * worst);

  // Looking straight up under the deck: the environment's zenith and the view's centre.
  scene = load_preset("overcast");
  scene.output.width = 32;
  scene.output.height = 32;
  scene.camera.view_dir = glm::vec3(0.0f, 0.001f, 1.0f);
  scene.camera.fov_deg = 20.0f;
  images = lit_frame(impl, scene, options);
  const Image deck = download(impl.ctx, impl.host_lighting.environment(), true);
  const Frame view = impl.download_last(scene);
  glm::vec3 zenith(0.0f), seen(0.0f);
  for (int y = 6; y < 10; ++y)
    for (int x = 4 * 16 + 6; x < 4 * 16 + 10; ++x) zenith += glm::vec3(deck.at(x, y)) / 16.0f;
  for (int y = 12; y < 20; ++y)
    for (int x = 12; x < 20; ++x) seen += glm::vec3(view.color.at(x, y)) / 64.0f;
  const glm::vec3 clear_zenith(clear.at(4 * 16 + 8, 8));
  std::printf(
      "zenith: clear sky %.0f cd/m^2 (blue/red %.2f); under the deck the environment %.0f, the "
      "view %.0f cd/m^2 "
      "(blue/red %.2f and %.2f)\n",
      luminance(glm::vec4(clear_zenith, 1.0f)), clear_zenith.b / clear_zenith.r,
      luminance(glm::vec4(zenith, 1.0f)), luminance(glm::vec4(seen, 1.0f)), zenith.b / zenith.r,
      seen.b / seen.r);
  EXPECT_NEAR(luminance(glm::vec4(zenith, 1.0f)), luminance(glm::vec4(seen, 1.0f)),
              0.2f * luminance(glm::vec4(seen, 1.0f)));
  EXPECT_LT(zenith.b / zenith.r, 0.8f * clear_zenith.b / clear_zenith.r)
      << "the deck is grey, not blue";
  EXPECT_EQ(impl.ctx.validation_messages(), 0);
}

TEST(HostLighting, TheShadowMapMatrixCarriesPointsAlongTheLightOntoTheCloudsBottom) {
  const glm::vec3 light = glm::normalize(glm::vec3(0.4f, 0.2f, 0.5f));
  const glm::mat4 m = shadow_map_matrix(light, 1500.0f, glm::vec2(-1000.0f, 3000.0f), 4000.0f);
  const auto uv = [&](const glm::vec3& p) { return glm::vec3(m * glm::vec4(p, 1.0f)); };
  // The plane's north-west corner and its south-east one.
  EXPECT_NEAR(glm::distance(uv({-1000.0f, 3000.0f, 1500.0f}), glm::vec3(0.0f)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::distance(uv({3000.0f, -1000.0f, 1500.0f}), glm::vec3(1.0f, 1.0f, 0.0f)), 0.0f,
              1e-5f);
  // Points on one ray of light share their texel; z is the height above the plane.
  const glm::vec3 on_plane(500.0f, 1200.0f, 1500.0f);
  for (float t : {300.0f, 1500.0f / light.z}) {
    const glm::vec3 below = on_plane - light * t;
    EXPECT_NEAR(uv(below).x, uv(on_plane).x, 1e-5f);
    EXPECT_NEAR(uv(below).y, uv(on_plane).y, 1e-5f);
    EXPECT_NEAR(uv(below).z, below.z - 1500.0f, 1e-2f);
  }
}

TEST(HostLighting, InsideACloudTheVisibilityIsTheClouds) {
  FrameRenderer::Impl impl(validated());
  Scene scene = load_preset("inside-cloud");
  scene.output.width = 16;
  scene.output.height = 16;
  lit_frame(impl, scene);
  ASSERT_TRUE(impl.completed_lighting.has_value());
  const HostLighting inside = *impl.completed_lighting;
  scene = load_preset("clear");
  scene.output.width = 16;
  scene.output.height = 16;
  lit_frame(impl, scene);
  const HostLighting clear = *impl.completed_lighting;
  std::printf("visibility: %.0f m inside the cloud (sigma_t %.4f /m), %.0f m in clear air\n",
              inside.visibility_m, inside.cloud_sigma_t_per_m, clear.visibility_m);
  EXPECT_TRUE(inside.inside_cloud);
  EXPECT_FALSE(clear.inside_cloud);
  EXPECT_NEAR(inside.visibility_m, 3.912f / inside.cloud_sigma_t_per_m,
              0.01f * inside.visibility_m);
  EXPECT_LT(inside.visibility_m, 1000.0f);  // fog, by the meteorologists' definition
  EXPECT_GT(clear.visibility_m, 50000.0f);
  EXPECT_LT(inside.sun_cloud_transmittance, 0.9f);  // the cloud around dims the sun
  EXPECT_EQ(impl.ctx.validation_messages(), 0);
}

TEST(HostLighting, BadOptionsAreRefusedNamingTheField) {
  FrameRenderer::Impl impl(validated());
  Scene scene = load_preset("clear");
  scene.output.width = 16;
  scene.output.height = 16;
  for (const auto& [extent, size, field] :
       {std::tuple{50.0f, 256u, "shadow_map_extent_m"}, std::tuple{20000.0f, 4u, "shadow_map_size"},
        std::tuple{std::nanf(""), 256u, "shadow_map_extent_m"}}) {
    HostLightingOptions options;
    options.shadow_map_extent_m = extent;
    options.shadow_map_size = size;
    try {
      lit_frame(impl, scene, options);
      ADD_FAILURE() << field << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace nephele

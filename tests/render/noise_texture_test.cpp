// Device test: the noise textures generated on the GPU tile seamlessly (opposite faces match)
// and their channels carry noise, not constants.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>

#include "gpu/context.h"
#include "nephele/scene.h"
#include "render/frame_params.h"
#include "render/glsl.h"
#include "render/modules/atmosphere/atmosphere.h"
#include "render/modules/clouds/clouds.h"
#include "render/modules/host_lighting/host_lighting.h"
#include "render/modules/host_scene/host_scene.h"
#include "render/modules/light_shafts/light_shafts.h"
#include "render/modules/light_volume/light_volume.h"
#include "render/modules/metaball_clouds/metaball_clouds.h"
#include "render/modules/noise/noise.h"
#include "render/modules/particle_clouds/particle_clouds.h"
#include "render/modules/particle_light_gpu/particle_light_gpu.h"
#include "render/modules/path_tracer/path_tracer.h"
#include "render/modules/post/post.h"
#include "render/modules/sky_view/sky_view.h"
#include "render/modules/terrain/terrain.h"
#include "render/modules/voxel_clouds/voxel_clouds.h"
#include "render/modules/weather/weather.h"
#include "render/passes.h"
#include "support/scoped_env.h"

namespace {

struct Volume {
  uint32_t size;
  std::vector<unsigned char> texels;  // RGBA8
  float at(uint32_t x, uint32_t y, uint32_t z, int c) const {
    return texels[4 * ((size_t(z) * size + y) * size + x) + c] / 255.0f;
  }
};

Volume download(nephele::gpu::Context& ctx, const nephele::gpu::Texture& texture) {
  Volume v{texture.width(), {}};
  const size_t bytes = size_t(v.size) * v.size * v.size * 4;
  nephele::gpu::Buffer staging(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { texture.record_download(cmd, staging); });
  v.texels.resize(bytes);
  std::memcpy(v.texels.data(), staging.data(), bytes);
  return v;
}

// Mean |difference| across the wrap-around seam along x (texel N-1 next to texel 0), and mean
// |difference| between interior neighbours. A tiling texture has similar values for both; one
// that does not tile has a seam as different as two random texels.
void seam_and_interior(const Volume& v, int c, double& seam, double& interior) {
  seam = interior = 0.0;
  size_t n_seam = 0, n_interior = 0;
  const uint32_t n = v.size;
  for (uint32_t z = 0; z < n; z += 3)
    for (uint32_t y = 0; y < n; y += 3) {
      seam += std::abs(v.at(n - 1, y, z, c) - v.at(0, y, z, c));
      seam += std::abs(v.at(y, n - 1, z, c) - v.at(y, 0, z, c));
      seam += std::abs(v.at(y, z, n - 1, c) - v.at(y, z, 0, c));
      n_seam += 3;
      const uint32_t x = n / 2;
      interior += std::abs(v.at(x, y, z, c) - v.at(x + 1, y, z, c));
      interior += std::abs(v.at(y, x, z, c) - v.at(y, x + 1, z, c));
      interior += std::abs(v.at(y, z, x, c) - v.at(y, z, x + 1, c));
      n_interior += 3;
    }
  seam /= double(n_seam);
  interior /= double(n_interior);
}

double random_pair_difference(const Volume& v, int c) {
  double sum = 0.0;
  const uint32_t n = v.size;
  for (uint32_t i = 0; i < 1000; ++i)
    sum += std::abs(v.at((i * 7) % n, (i * 13) % n, (i * 29) % n, c) -
                    v.at((i * 17 + n / 2) % n, (i * 3 + 5) % n, (i * 11 + 1) % n, c));
  return sum / 1000.0;
}

// The modules that own the other bindings of the shared set (a set with unwritten bindings
// must not be bound).
struct Modules {
  Modules(nephele::gpu::Context& ctx, nephele::GpuState& s)
      : noise(ctx, s.set),
        atmosphere(ctx, s.set),
        weather(ctx, s.set),
        light_volume(ctx, s.set),
        voxel_clouds(ctx, s.set),
        sky_view(ctx, s.set),
        clouds(ctx, s.set),
        particles(ctx, s.set, s.layers),
        particle_light(ctx, s.set),
        path_tracer(ctx, s.set),
        metaballs(ctx, s.set),
        post(ctx, s.set),
        light_shafts(ctx, s.set),
        terrain(ctx, s.set, s.layers),
        host_scene(ctx, s.set),
        host_lighting(ctx, s.set) {}
  nephele::NoiseModule noise;
  nephele::AtmosphereModule atmosphere;
  nephele::WeatherModule weather;
  nephele::LightVolumeModule light_volume;
  nephele::VoxelCloudsModule voxel_clouds;
  nephele::SkyViewModule sky_view;
  nephele::CloudsModule clouds;
  nephele::ParticleCloudsModule particles;
  nephele::ParticleLightGpuModule particle_light;
  nephele::PathTracerModule path_tracer;
  nephele::MetaballCloudsModule metaballs;
  nephele::PostModule post;
  nephele::LightShaftsModule light_shafts;
  nephele::TerrainModule terrain;
  nephele::HostSceneModule host_scene;
  nephele::HostLightingModule host_lighting;
};

// Runs `passes` with the default scene's parameters.
template <typename Passes>
void run_passes(nephele::gpu::Context&, nephele::GpuState& state, Passes passes) {
  state.run_once(nephele::make_frame_params(nephele::Scene{}, 0), passes);
}

}  // namespace

TEST(NoiseTextures, TileSeamlesslyAndCarryNoise) {
  nephele::gpu::Context ctx({"", true, false});
  nephele::GpuState state(ctx);
  Modules modules(ctx, state);  // every binding of the set filled
  run_passes(ctx, state, [&](VkCommandBuffer cmd) {
    modules.noise.record(cmd, *state.timer, 0);
    modules.noise.record(cmd, *state.timer, 1);
  });
  const Volume base = download(ctx, modules.noise.base());
  const Volume detail = download(ctx, modules.noise.detail());
  ASSERT_EQ(base.size, 128u);
  ASSERT_EQ(detail.size, 32u);

  for (const auto& [volume, channels, label] :
       {std::tuple{&base, 4, "base"}, std::tuple{&detail, 3, "detail"}}) {
    for (int c = 0; c < channels; ++c) {
      double seam, interior;
      seam_and_interior(*volume, c, seam, interior);
      const double random = random_pair_difference(*volume, c);
      EXPECT_GT(random, 0.03) << label << " channel " << c << " looks constant";
      EXPECT_LT(seam, 1.5 * interior + 0.01) << label << " channel " << c << " has a seam";
      EXPECT_LT(interior, 0.5 * random) << label << " channel " << c << " is not smooth";
    }
  }
  EXPECT_EQ(ctx.validation_messages(), 0);
}

// The base noise texture holds noise_inc.glsl's functions (as C++) at each texel's centre, for
// the default seed, within the RGBA8 rounding: what the device made is what the CPU's tests of
// those functions test (and a faster noise_base.comp must not change a value).
TEST(NoiseTextures, BaseNoiseIsTheNoiseFunctionsAtEachTexel) {
  nephele::gpu::Context ctx({"", true, false});
  nephele::GpuState state(ctx);
  Modules modules(ctx, state);
  const auto params = nephele::make_frame_params(nephele::Scene{}, 0);
  state.run_once(params, [&](VkCommandBuffer cmd) { modules.noise.record(cmd, *state.timer, 0); });
  const Volume base = download(ctx, modules.noise.base());
  namespace g = nephele::glsl;
  const uint32_t seed = uint32_t(params.size.w) * 101u;  // as noise_base.comp
  const uint32_t n = base.size;
  int checked = 0, off = 0;
  float worst = 0.0f;
  // Every texel of a few rows in each axis' direction, across workgroups' borders.
  for (uint32_t z = 0; z < n; z += 37)
    for (uint32_t y = 0; y < n; y += 5)
      for (uint32_t x = 0; x < n; ++x) {
        const glm::vec3 uvw = (glm::vec3(x, y, z) + 0.5f) / float(n);
        const float expected[4] = {
            g::perlin_worley(uvw, 4, seed), g::worley_fbm(uvw, 4, seed + 31u),
            g::worley_fbm(uvw, 8, seed + 41u), g::worley_fbm(uvw, 16, seed + 53u)};
        for (int c = 0; c < 4; ++c) {
          const float d = std::abs(base.at(x, y, z, c) - expected[c]);
          worst = std::max(worst, d);
          off += d > 0.5f / 255.0f + 1e-6f;
          ++checked;
        }
      }
  EXPECT_LE(worst, 1.0f / 255.0f + 1e-6f);
  EXPECT_LE(off, checked / 1000) << off << " of " << checked << " values off by a code";
  EXPECT_EQ(ctx.validation_messages(), 0);
}

// The curl noise (noise_curl.comp) is a swirl field that displaces the detail noise and is the
// flow map: divergence-free (so the flow neither piles cloud up nor thins it out), of unit
// root-mean-square magnitude (so curl_distortion_m and flow_speed_mps mean what they say),
// seamless across the tile's edges, and not constant.
TEST(NoiseTextures, CurlNoiseIsDivergenceFreeUnitAndTiles) {
  nephele::gpu::Context ctx({"", true, false});
  nephele::GpuState state(ctx);
  Modules modules(ctx, state);  // every binding of the set filled
  run_passes(ctx, state, [&](VkCommandBuffer cmd) { modules.noise.record(cmd, *state.timer, 2); });
  const nephele::gpu::Texture& curl = modules.noise.curl();
  const int n = int(curl.width());
  ASSERT_EQ(n, 128);
  std::vector<glm::vec4> texels(size_t(n) * n);
  nephele::gpu::Buffer staging(ctx, texels.size() * sizeof(glm::vec4),
                               VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { curl.record_download(cmd, staging); });
  std::memcpy(texels.data(), staging.data(), texels.size() * sizeof(glm::vec4));
  const auto at = [&](int x, int y) {
    return glm::vec2(texels[size_t((y + n) % n) * n + size_t((x + n) % n)]);
  };
  double sum_sq = 0.0, divergence = 0.0, gradient = 0.0, seam = 0.0, interior = 0.0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const glm::vec2 v = at(x, y);
      sum_sq += glm::dot(v, v);
      // Central differences (per texel): du/dx + dv/dy against the size of du/dx alone.
      const float du_dx = 0.5f * (at(x + 1, y).x - at(x - 1, y).x);
      const float dv_dy = 0.5f * (at(x, y + 1).y - at(x, y - 1).y);
      divergence += std::abs(du_dx + dv_dy);
      gradient += std::abs(du_dx) + std::abs(dv_dy);
      if (x == n - 1) seam += glm::length(at(0, y) - v);
      if (x == n / 2) interior += glm::length(at(x + 1, y) - v);
    }
  const double rms = std::sqrt(sum_sq / (double(n) * n));
  std::printf("curl noise: rms %.3f, |div| / |gradient| %.4f, seam %.4f, interior %.4f\n", rms,
              divergence / gradient, seam / n, interior / n);
  EXPECT_NEAR(rms, 1.0, 0.1);
  EXPECT_LT(divergence, 0.1 * gradient);  // a random field has |div| about 0.7 of this
  EXPECT_LT(seam, 1.5 * interior);
  EXPECT_GT(interior / n, 0.01);
  EXPECT_EQ(ctx.validation_messages(), 0);
}

// The base noise kept in the disk cache (render/disk_cache.h) comes back texel for texel, into a
// texture that held something else; a damaged file is not read.
TEST(NoiseTextures, TheBaseNoiseComesBackFromTheDiskCacheAsItWasMade) {
  const std::filesystem::path dir =
      std::filesystem::path(NEPHELE_TEST_OUTPUT_DIR) / "noise_texture_cache";
  std::filesystem::remove_all(dir);
  ScopedEnv cache("NEPHELE_CACHE_DIR", dir.string());
  {
    nephele::gpu::Context ctx({"", true, false});
    nephele::GpuState state(ctx);
    Modules modules(ctx, state);
    nephele::Scene scene;
    scene.noise_seed = 7;
    const auto params = nephele::make_frame_params(scene, 0);
    EXPECT_FALSE(modules.noise.load_base(7));  // nothing there yet
    state.run_once(params,
                   [&](VkCommandBuffer cmd) { modules.noise.record(cmd, *state.timer, 0); });
    const Volume made = download(ctx, modules.noise.base());
    modules.noise.store_base(7);
    EXPECT_FALSE(modules.noise.load_base(8));  // another seed's is another file
    ctx.submit_and_wait([&](VkCommandBuffer cmd) { modules.noise.base().record_clear(cmd); });
    ASSERT_NE(download(ctx, modules.noise.base()).texels, made.texels);
    const std::optional<std::filesystem::path> file = modules.noise.load_base(7);
    ASSERT_TRUE(file);
    EXPECT_EQ(file->parent_path(), dir);
    EXPECT_TRUE(download(ctx, modules.noise.base()).texels == made.texels);
    {
      std::fstream f(*file, std::ios::binary | std::ios::in | std::ios::out);
      f.seekp(1000);
      f.put('\x5a');
    }
    EXPECT_FALSE(modules.noise.load_base(7));
    EXPECT_EQ(ctx.validation_messages(), 0);
  }
}

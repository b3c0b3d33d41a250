#include "render/modules/metaball_clouds/metaball_clouds.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "render/glsl.h"

namespace nephele {

std::vector<Metaball> make_cumulus_metaballs(const Scene& scene, uint32_t seed) {
  const ClassicCloudParams& c = scene.classic;
  const int clouds = std::clamp(c.nishita_clouds, 1, std::max(c.nishita_metaballs, 1));
  const float bottom_m = scene.clouds.bottom_altitude_m;
  const float layer_m = scene.clouds.top_altitude_m - bottom_m;
  const int side = int(std::ceil(std::sqrt(float(clouds))));
  const float cell_m = c.nishita_extent_m / float(side);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const auto uniform = [&](float lo, float hi) { return lo + (hi - lo) * u01(rng); };
  std::vector<Metaball> balls;
  balls.reserve(size_t(c.nishita_metaballs));
  for (int k = 0; k < clouds; ++k) {
    const int count = c.nishita_metaballs / clouds + (k < c.nishita_metaballs % clouds ? 1 : 0);
    // The cloud's axis: its cell's centre, jittered by a fifth of the cell.
    const glm::vec2 cell(float(k % side), float(k / side));
    const glm::vec2 axis =
        c.nishita_center_m - 0.5f * c.nishita_extent_m +
        (cell + 0.5f + glm::vec2(uniform(-0.2f, 0.2f), uniform(-0.2f, 0.2f))) * cell_m;
    const float reach_m = 0.38f * cell_m * uniform(0.75f, 1.0f);  // its base's half width
    const float height_m = std::min(layer_m, 1.3f * reach_m) * uniform(0.7f, 1.0f);
    const float base_r = std::min(0.45f * reach_m, 0.5f * height_m);
    const size_t first = balls.size();
    // The base: wide balls in a disc, their centres a little above the layer's bottom, so the
    // cloud's underside is flat.
    const int base = std::max(1, int(std::round(0.35f * float(count))));
    for (int i = 0; i < count; ++i) {
      Metaball b;
      b.density = uniform(0.6f, 1.0f);
      if (i < base) {
        b.radius_m = base_r * uniform(0.7f, 1.0f);
        const float a = uniform(0.0f, 2.0f * glsl::PI);
        const float r = (reach_m - b.radius_m) * std::sqrt(u01(rng));
        b.centre_m =
            glm::vec3(axis + r * glm::vec2(std::cos(a), std::sin(a)), bottom_m + 0.5f * b.radius_m);
      } else {
        // A tower: a smaller ball on the upper side of one already placed.
        const Metaball& parent = balls[first + size_t(u01(rng) * float(i)) % size_t(i)];
        b.radius_m = std::max(parent.radius_m * uniform(0.65f, 0.9f), 0.2f * base_r);
        const float a = uniform(0.0f, 2.0f * glsl::PI);
        const float up = uniform(0.35f, 1.0f);  // the sine of its elevation from the parent
        const glm::vec3 d(std::sqrt(1.0f - up * up) * std::cos(a),
                          std::sqrt(1.0f - up * up) * std::sin(a), up);
        b.centre_m = parent.centre_m + d * (0.75f * parent.radius_m);
        // Narrowing upwards: the further up, the closer to the axis.
        const float rise = std::clamp((b.centre_m.z - bottom_m) / height_m, 0.0f, 1.0f);
        const float limit = std::max((reach_m - b.radius_m) * (1.0f - 0.6f * rise), 0.0f);
        glm::vec2 off = glm::vec2(b.centre_m) - axis;
        if (glm::length(off) > limit) off *= limit / glm::length(off);
        b.centre_m = glm::vec3(axis + off, std::clamp(b.centre_m.z, bottom_m + 0.5f * b.radius_m,
                                                      std::max(bottom_m + height_m - b.radius_m,
                                                               bottom_m + 0.5f * b.radius_m)));
      }
      balls.push_back(b);
    }
  }
  return balls;
}

float metaball_field(const std::vector<Metaball>& balls, const glm::vec3& p) {
  float sum = 0.0f;
  for (const Metaball& b : balls)
    sum += glsl::metaball(p, glm::vec4(b.centre_m, b.radius_m), b.density).x;
  return sum;
}

MetaballGrid voxelize_metaballs(const std::vector<Metaball>& balls, int longest) {
  MetaballGrid g;
  if (balls.empty()) return g;
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const Metaball& b : balls) {
    lo = glm::min(lo, b.centre_m - b.radius_m);
    hi = glm::max(hi, b.centre_m + b.radius_m);
  }
  const glm::vec3 size = hi - lo;
  g.voxel_m = std::max(std::max(size.x, size.y), size.z) / float(longest);
  g.dims = glm::max(glm::ivec3(glm::ceil(size / g.voxel_m)), glm::ivec3(1));
  g.corner_m = lo;
  g.density.assign(size_t(g.dims.x) * size_t(g.dims.y) * size_t(g.dims.z), 0.0f);
  for (const Metaball& b : balls) {
    // The voxels whose centres lie within the ball's box.
    const glm::ivec3 v0 = glm::max(
        glm::ivec3(glm::floor((b.centre_m - b.radius_m - lo) / g.voxel_m - 0.5f)), glm::ivec3(0));
    const glm::ivec3 v1 = glm::min(
        glm::ivec3(glm::ceil((b.centre_m + b.radius_m - lo) / g.voxel_m - 0.5f)), g.dims - 1);
    const glm::vec4 centre_radius(b.centre_m, b.radius_m);
    for (int z = v0.z; z <= v1.z; ++z)
      for (int y = v0.y; y <= v1.y; ++y)
        for (int x = v0.x; x <= v1.x; ++x) {
          const glm::vec3 p = lo + (glm::vec3(x, y, z) + 0.5f) * g.voxel_m;
          g.density[(size_t(z) * g.dims.y + y) * g.dims.x + x] +=
              glsl::metaball(p, centre_radius, b.density).x;
        }
  }
  return g;
}

MetaballCloudsModule::MetaballCloudsModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx),
      set_(set),
      // A placeholder until a scene draws metaballs (only Nishita's passes read it): the
      // passes that declare the volume bind it.
      volume_(ctx, 1, 1, glsl::NISHITA_SLABS, VK_FORMAT_R32G32B32A32_SFLOAT,
              VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE) {
  set_.bind_image(gpu::kNishitaVolumeOut, gpu::kNishitaVolume, volume_);
}

void MetaballCloudsModule::upload() {
  const glm::ivec3 d = grid_.dims;
  ctx_.wait_queue_idle();  // the frames in flight read the volume replaced
  volume_ = gpu::Texture(ctx_, uint32_t(d.x), uint32_t(d.y), uint32_t(d.z * glsl::NISHITA_SLABS),
                         VK_FORMAT_R32G32B32A32_SFLOAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  const size_t voxels = grid_.density.size();
  gpu::Buffer staging(ctx_, voxels * glsl::NISHITA_SLABS * 4 * sizeof(float),
                      VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  auto* texels = static_cast<float*>(staging.data());
  std::memset(texels, 0, staging.size());
  for (size_t i = 0; i < voxels; ++i) texels[4 * i] = grid_.density[i];  // slab 0, r
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) { volume_.record_upload(cmd, staging); });
  set_.bind_image(gpu::kNishitaVolumeOut, gpu::kNishitaVolume, volume_);
}

void MetaballCloudsModule::prepare(const Scene& scene, gpu::FrameParams& params) {
  const ClassicCloudParams& c = scene.classic;
  const Key key{c.nishita_metaballs,
                c.nishita_clouds,
                c.nishita_voxels,
                c.nishita_extent_m,
                scene.clouds.bottom_altitude_m,
                scene.clouds.top_altitude_m,
                c.nishita_center_m,
                scene.noise_seed};
  if (key_ != key) {
    grid_ = voxelize_metaballs(make_cumulus_metaballs(scene, scene.noise_seed), c.nishita_voxels);
    upload();
    key_ = key;
    lit_key_.reset();
  }
  params.classic_nishita = glm::vec4(grid_.corner_m, grid_.voxel_m);
  params.classic_nishita_grid = glm::vec4(glm::vec3(grid_.dims), 0.0f);
  params.classic_nishita_light =
      glm::vec4(c.nishita_sigma_t_per_m, c.nishita_albedo, float(c.nishita_order),
                c.nishita_sky_light ? 1.0f : 0.0f);
  // What the light passes read: the balls, the light's direction, the medium, the phase and
  // the sky (its colour by the sky-view table's frame and the ground's light).
  want_ = LightKey{key, glm::vec3(params.sun_dir), params.classic_nishita_light, params.cloud_phase,
                   c.nishita_sky_light ? params.ambient_below_clouds /
                                             glm::max(params.sun_illuminance, glm::vec4(1e-20f))
                                       : glm::vec4(0.0f)};
}

bool MetaballCloudsModule::LightKey::close_to(const LightKey& other) const {
  // The sun moves 0.25 deg a minute: relit once it has moved 0.25 deg, or the sky's colour by
  // 2%, not every frame of a flight.
  const float cos_quarter_deg = 0.99999048f;
  const glm::vec4 sky_change =
      glm::abs(sky - other.sky) / glm::max(glm::abs(other.sky), glm::vec4(1e-12f));
  return shape == other.shape && nishita_light == other.nishita_light && phase == other.phase &&
         glm::dot(light, other.light) >= cos_quarter_deg &&
         std::max(std::max(sky_change.x, sky_change.y), sky_change.z) <= 0.02f;
}

void MetaballCloudsModule::record_light(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  if (lit_key_ && lit_key_->close_to(want_)) return;
  if (!light_) {
    light_ = std::make_unique<gpu::Kernel>(ctx_, set_, "nishita_light.comp.spv");
    scatter_ = std::make_unique<gpu::Kernel>(ctx_, set_, "nishita_scatter.comp.spv");
  }
  const glm::uvec3 d(grid_.dims);
  gpu::dispatch(cmd, *light_, timer, "nishita_light", d.x, d.y, d.z, 4, 4, 4);
  if (want_.nishita_light.z > 1.5f)  // the second order
    gpu::dispatch(cmd, *scatter_, timer, "nishita_scatter", d.x, d.y, d.z, 4, 4, 4);
  lit_key_ = want_;
}

}  // namespace nephele

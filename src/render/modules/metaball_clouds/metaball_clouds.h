// Nishita and Nakamae 1996 (seed 004, issue 23): cumulus made of metaballs, their density on a
// voxel grid, lit by the sun to the second order of scattering and by the sky. The balls and
// the grid's density are made here on the CPU (a ball touches only the voxels within its
// radius); the light is two passes on the device, redone only when the balls or the light
// change (nishita_light.comp, nishita_scatter.comp); classic_clouds.comp marches the eye rays.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <vector>

#include "gpu/kernel.h"
#include "nephele/scene.h"
#include "render/gpu_params.h"

namespace nephele {

struct Metaball {
  glm::vec3 centre_m{0.0f};  // ENU on a flat earth
  float radius_m = 0.0f;
  float density = 1.0f;  // q, the density at its centre
};

// The scene's [classic] nishita_* cumulus: nishita_clouds of them on a jittered grid over the
// square of nishita_extent_m about nishita_center_m, nishita_metaballs balls in all, between
// clouds.bottom_altitude_m and top_altitude_m. Each cloud is a flat-bottomed base of wide balls
// with towers of smaller balls grown on it, narrowing upwards. Deterministic in `seed`.
std::vector<Metaball> make_cumulus_metaballs(const Scene& scene, uint32_t seed);

// The field of the balls at p: sum of q f(|p - c| / R) (classic_inc.glsl, metaball_falloff).
float metaball_field(const std::vector<Metaball>& balls, const glm::vec3& p);

// The balls' field sampled at the centres of a grid of cubic voxels over their bounding box:
// at most `longest` voxels along its longest side.
struct MetaballGrid {
  glm::vec3 corner_m{0.0f};
  float voxel_m = 1.0f;
  glm::ivec3 dims{0};
  std::vector<float> density;  // x fastest
  float at(int x, int y, int z) const { return density[(size_t(z) * dims.y + y) * dims.x + x]; }
};
MetaballGrid voxelize_metaballs(const std::vector<Metaball>& balls, int longest);

class MetaballCloudsModule {
 public:
  MetaballCloudsModule(gpu::Context& ctx, gpu::DescriptorSet& set);

  // Remakes the balls and their grid when their parameters change (a one-off wait for the
  // device) and fills params.classic_nishita*.
  void prepare(const Scene& scene, gpu::FrameParams& params);
  // The light passes, when the balls or the light changed since they last ran.
  void record_light(VkCommandBuffer cmd, gpu::PassTimer& timer);

 private:
  struct Key {
    int metaballs = 0, clouds = 0, voxels = 0;
    float extent_m = 0.0f, bottom_m = 0.0f, top_m = 0.0f;
    glm::vec2 center_m{0.0f};
    uint32_t seed = 0;
    bool operator==(const Key&) const = default;
  };
  struct LightKey {
    Key shape;
    glm::vec3 light{0.0f};
    glm::vec4 nishita_light{0.0f}, phase{0.0f}, sky{0.0f};
    bool close_to(const LightKey& other) const;
  };
  void upload();

  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::Texture volume_;
  MetaballGrid grid_;
  std::optional<Key> key_;
  std::optional<LightKey> lit_key_;
  LightKey want_;
  std::unique_ptr<gpu::Kernel> light_, scatter_;
};

}  // namespace nephele

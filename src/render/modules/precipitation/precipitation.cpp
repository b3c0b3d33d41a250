#include "render/modules/precipitation/precipitation.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <limits>

#include "render/glsl.h"
#include "render/gpu_params.h"
#include "render/image_layers.h"
#include "render/media_light.h"
// The block's one definition and the medium's pure functions, as the shader has them.
#include "render/modules/precipitation/precipitation_gpu_inc.glsl"

namespace nephele {

namespace {
namespace precip = nephele::glsl;

constexpr const char* kBlockName = "PrecipitationBlock";
}  // namespace

int precipitation_kind(std::string_view name) {
  if (name == "rain") return precip::PRECIPITATION_RAIN;
  if (name == "drizzle") return precip::PRECIPITATION_DRIZZLE;
  if (name == "snow") return precip::PRECIPITATION_SNOW;
  if (name == "sleet") return precip::PRECIPITATION_SLEET;
  return -1;
}

float precipitation_sigma_t_per_m(const PrecipitationParams& p) {
  const int kind = precipitation_kind(p.kind);
  return kind < 0 ? 0.0f : precip::precipitation_sigma_t_per_m(kind, p.rate_mm_per_h);
}

float precipitation_visibility_m(const PrecipitationParams& p) {
  const float sigma = precipitation_sigma_t_per_m(p);
  return sigma > 0.0f ? glsl::KOSCHMIEDER / sigma : std::numeric_limits<float>::infinity();
}

namespace {
// The slices: the march's start and each of its samples (precipitation_field_inc.glsl).
constexpr uint32_t kSlices = uint32_t(precip::PRECIPITATION_STEPS) + 1;

// The falling grid's period, in cells: the hash repeats after it (wider than twice the range).
constexpr int kNearPeriodCells = 128;

// The particles near the camera (precipitation_particles_inc.glsl) into `block`: the camera's place
// in a grid that falls with them (at `fall_mps`, carried by the wind at the camera's height), its
// cells' size and how many particles each one drawn stands for. False when the camera is not in
// it.
bool near_particles(const Scene& scene, float fall_mps, gpu::PrecipitationGpu& block) {
  const PrecipitationParams& p = scene.precipitation;
  const glm::vec3 eye_m = scene.camera.position_m;
  const float base_m = scene.clouds.bottom_altitude_m;
  if (eye_m.z < p.bottom_m || eye_m.z > base_m) return false;
  const glm::vec3 velocity_mps(
      precip::precipitation_wind_at(scene.clouds.wind_mps, eye_m.z, base_m), -fall_mps);
  const int kind = precipitation_kind(p.kind);
  const float d_m = precip::precipitation_particle_m(kind, p.rate_mm_per_h);
  const glm::vec3 streak_m = velocity_mps * p.shutter_s;
  const bool flutters = kind == precip::PRECIPITATION_SNOW || kind == precip::PRECIPITATION_SLEET;
  const float flutter_m = flutters ? 0.08f : 0.0f;
  // A cell holds its particle's whole streak and flutter, with room to spare.
  const float cell_m = std::max(0.5f, 2.0f * (glm::length(streak_m) + d_m + 2.0f * flutter_m));
  // The camera in the grid, in double: the planet frame's float cannot hold a centimetre.
  const double period_m = double(kNearPeriodCells) * cell_m;
  glm::dvec3 q = glm::dvec3(eye_m) - glm::dvec3(velocity_mps) * double(scene.time_s);
  q -= period_m * glm::floor(q / period_m);
  block.near = glm::vec4(glm::vec3(q), cell_m);
  block.streak = glm::vec4(streak_m, d_m);
  const float per_cell =
      precip::precipitation_particles_per_m3(kind, p.rate_mm_per_h) * cell_m * cell_m * cell_m;
  // Snow and sleet sway a few centimetres each way, about twice a second.
  const double phase_rad =
      std::fmod(double(scene.time_s) * 2.0 * 3.14159265358979 * 2.0, 2.0 * 3.14159265358979);
  // The range they are drawn to (m), within the cube drawn: beyond, the froxels' medium alone.
  const float range_m = 0.45f * float(gpu::PRECIPITATION_NEAR_SIDE) * cell_m;
  block.particles = glm::vec4(per_cell, range_m, flutter_m, float(phase_rad));
  return per_cell > 0.0f;
}

gpu::Texture froxel_texture(gpu::Context& ctx, uint32_t w, uint32_t h, VkFormat format) {
  return gpu::Texture(ctx, w, h, kSlices, format, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
}
}  // namespace

PrecipitationModule::PrecipitationModule(const ModuleContext& context)
    : ctx_(context.ctx),
      set_(context.set),
      layers_(context.layers),
      froxels_(froxel_texture(ctx_, 1, 1, VK_FORMAT_R16G16B16A16_SFLOAT)),
      depth_(froxel_texture(ctx_, 1, 1, VK_FORMAT_R16_SFLOAT)) {
  for (gpu::Buffer& b : blocks_) {
    b = gpu::Buffer(context.ctx, sizeof(gpu::PrecipitationGpu), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    std::memset(b.data(), 0, sizeof(gpu::PrecipitationGpu));  // none
  }
  // compose.comp and stars.comp declare the block and the froxels whether or not a frame has
  // any: always bound.
  set_.bind_module_buffer(kBlockName, blocks_[0], VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  bind_froxels();
}

void PrecipitationModule::bind_froxels() {
  set_.bind_module_storage_image("precipitation_froxels_out", froxels_);
  set_.bind_module_storage_image("precipitation_depth_out", depth_);
  set_.bind_module_sampled_image("precipitation_froxels", froxels_);
  set_.bind_module_sampled_image("precipitation_depth", depth_);
}

void PrecipitationModule::prepare(const FramePrepare& frame, FramePlan& plan) {
  const PrecipitationParams& p = frame.scene.precipitation;
  const float top_m = frame.scene.clouds.bottom_altitude_m;
  gpu::PrecipitationGpu block{};
  const float sigma = precipitation_sigma_t_per_m(p);
  falls_ = sigma > 0.0f && p.bottom_m < top_m;
  if (falls_) {
    block.fall = glm::vec4(p.bottom_m, top_m, sigma,
                           precip::precipitation_phase_g(precipitation_kind(p.kind)));
    const MediumLight light = medium_light(frame.params);
    block.sun = light.sun;
    block.sky = glm::vec4(light.sky, p.shafts ? 1.0f : 0.0f);
    const int kind = precipitation_kind(p.kind);
    const float fall_mps = precip::precipitation_fall_mps(kind, p.rate_mm_per_h);
    const glm::vec2 drift =
        precip::precipitation_drift_slope(frame.scene.clouds.wind_mps, fall_mps);
    block.drift = glm::vec4(drift, 0.0f, 0.0f);
    // Drawn by a raster pass: not on a queue without graphics.
    near_ = p.particles && ctx_.has_graphics() && near_particles(frame.scene, fall_mps, block);
    if (near_) {
      layers_.require(frame.width, frame.height);
      const gpu::FrameParams& f = frame.params;
      camera_.forward = glm::vec4(glm::vec3(f.camera_forward), f.camera_pos_m.w);
      camera_.right = glm::vec4(glm::vec3(f.camera_right), f.camera_forward.w);
      camera_.up = glm::vec4(glm::vec3(f.camera_up), 0.0f);
    }
    const uint32_t w =
        uint32_t((frame.width + kPrecipitationDownsample - 1) / kPrecipitationDownsample);
    const uint32_t h =
        uint32_t((frame.height + kPrecipitationDownsample - 1) / kPrecipitationDownsample);
    if (froxels_.width() != w || froxels_.height() != h) {
      ctx_.wait_queue_idle();  // a frame in flight may still read the old ones
      froxels_ = froxel_texture(ctx_, w, h, VK_FORMAT_R16G16B16A16_SFLOAT);
      depth_ = froxel_texture(ctx_, w, h, VK_FORMAT_R16_SFLOAT);
      bind_froxels();
    }
  }
  std::memcpy(blocks_[frame.slot].data(), &block, sizeof(block));
  set_.bind_module_buffer(kBlockName, blocks_[frame.slot], VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  plan.media = plan.media || falls_;
}

void PrecipitationModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  graph.import("media");  // read by compose and the stars whether or not it falls
  if (!falls_) return;
  graph.add_pass("precipitation", {"weather_map", FrameGraph::kView}, {"media"},
                 [this, timer = frame.timer](VkCommandBuffer cmd) {
                   if (!kernel_)
                     kernel_ = std::make_unique<gpu::Kernel>(ctx_, set_, "precipitation.comp.spv");
                   gpu::dispatch(cmd, *kernel_, timer(), "precipitation", froxels_.width(),
                                 froxels_.height(), 1, 8, 8, 1);
                 });
  if (!near_) return;
  graph.add_pass(
      "precipitation_particles", {"weather_map", "media", FrameGraph::kView}, {"layers"},
      [this, timer = frame.timer](VkCommandBuffer cmd) {
        if (!particles_)
          particles_ = std::make_unique<gpu::RasterPass>(
              ctx_, set_, std::vector<VkFormat>{ImageLayers::kFormat}, true,
              std::vector<gpu::RasterShaders>{
                  {"precipitation_particles.vert.spv", "precipitation_particles.frag.spv"}});
        gpu::RasterDraw draw;
        constexpr uint32_t side = uint32_t(gpu::PRECIPITATION_NEAR_SIDE);
        draw.vertex_count = 6 * side * side * side;
        draw.constants = camera_;
        const glm::uvec2 size(layers_.texture().width(), layers_.texture().height());
        particles_->record(cmd, timer(), "precipitation_particles",
                           {layers_.target(gpu::LAYER_PRECIPITATION, int(size.x), int(size.y))},
                           {draw});
      });
}

std::unique_ptr<RenderModule> make_precipitation_module(const ModuleContext& context) {
  return std::make_unique<PrecipitationModule>(context);
}

}  // namespace nephele

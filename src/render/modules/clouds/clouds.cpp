#include "render/modules/clouds/clouds.h"

#include "render/glsl.h"

namespace nephele {

namespace {
// The passes that light cloud samples read the diffusion light's field too
// (render/modules/cloud_diffusion), which the frame imports whatever the lighting.
std::vector<std::string> with_diffusion(std::vector<std::string> reads) {
  reads.push_back("cloud_diffusion");
  return reads;
}
}  // namespace

glm::ivec4 entering_region(const gpu::FrameParams& f) {
  const int w = f.cloud_grid.x, h = f.cloud_grid.y;
  if (f.cloud_grid.w != 1 || w < 8 || h < 8) return glm::ivec4(0);
  glm::ivec2 lo(w, h), hi(-1, -1);  // the columns (x) and rows (y) sampled outside
  for (int y = 0; y < h; y += 2)
    for (int x = 0; x < w; x += 2) {
      const glm::vec3 dir = glsl::camera_ray(glm::vec3(f.camera_forward), glm::vec3(f.camera_right),
                                             glm::vec3(f.camera_up), f.camera_pos_m.w,
                                             f.camera_forward.w, float(x), float(y), float(w),
                                             float(h), glm::vec2(f.camera_right.w, f.camera_up.w));
      const glm::vec2 q = glsl::camera_pixel(
          glm::vec3(f.prev_camera_forward), glm::vec3(f.prev_camera_right),
          glm::vec3(f.prev_camera_up), f.prev_camera_pos_m.w, f.prev_camera_forward.w, dir,
          float(w), float(h), glm::vec2(f.prev_camera_right.w, f.prev_camera_up.w));
      // Beyond the previous image's outermost pixel centres: at its sides, or its top or
      // bottom (behind the previous camera counts as both).
      const glm::vec2 last(float(w - 1), float(h - 1));
      const glm::bvec2 out =
          glm::lessThan(q, glm::vec2(-0.01f)) || glm::greaterThan(q, last + 0.01f);
      const glm::ivec2 at(x, y);
      for (int axis = 0; axis < 2; ++axis)
        if (out[axis]) {
          lo[axis] = std::min(lo[axis], at[axis]);
          hi[axis] = std::max(hi[axis], at[axis]);
        }
    }
  // The pixels between the samples too; none where over a quarter.
  glm::ivec4 region(0);
  for (int axis = 0; axis < 2; ++axis) {
    const int size = axis == 0 ? w : h;
    if (hi[axis] < 0) continue;
    const int from = std::max(lo[axis] - 1, 0), to = std::min(hi[axis] + 1, size - 1);
    if (4 * (to - from + 1) > size) continue;
    region[2 * axis] = from;
    region[2 * axis + 1] = to - from + 1;
  }
  return region;
}

CloudsModule::CloudsModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx),
      set_(set),
      march_(ctx, set, "clouds.comp.spv", 1, {1, -1, 1}),
      range_(ctx, set, "march_range.comp.spv"),
      resolve_(ctx, set, "resolve.comp.spv"),
      profile_(ctx, set, "cloud_profile.comp.spv"),
      ground_default_(ctx, set, "ground_light.comp.spv", {0}),
      ground_baseline_(ctx, set, "ground_light.comp.spv", {1}),
      ground_light_(ctx, 2, 1, 1, VK_FORMAT_R32G32B32A32_SFLOAT) {
  for (gpu::Texture* t : {&dome_a_, &dome_b_})
    *t = gpu::Texture(ctx, kSkyDomeSize, kSkyDomeSize, 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                      VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  set_.bind_image(gpu::kGroundLightOut, gpu::kGroundLight, ground_light_);
  resize(1, 1);
}

bool CloudsModule::resize(int w, int h, bool carry_history) {
  if (w == width_ && h == height_) return false;
  // The last frame's buffer (the one written last: current_).
  gpu::Texture last_a = std::move(clouds_a_[current_]), last_b = std::move(clouds_b_[current_]);
  const auto cloud_image = [&] {
    return gpu::Texture(ctx_, uint32_t(w), uint32_t(h), 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                        VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  };
  // Room for a still image's march of every pixel.
  march_a_ = cloud_image();
  march_b_ = cloud_image();
  range_lo_ = cloud_image();
  range_hi_ = cloud_image();
  for (int i = 0; i < 2; ++i) {
    clouds_a_[i] = cloud_image();
    clouds_b_[i] = cloud_image();
  }
  bind_march(false);
  set_.bind_storage_image(gpu::kRangeLo, range_lo_);
  set_.bind_storage_image(gpu::kRangeHi, range_hi_);
  // Defined contents: filters read neighbours of the texels a frame writes.
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) {
    for (const gpu::Texture* t : {&march_a_, &march_b_, &range_lo_, &range_hi_, &clouds_a_[0],
                                  &clouds_a_[1], &clouds_b_[0], &clouds_b_[1]})
      t->record_clear(cmd);
    // The next frame's history is clouds_*[0] (prepare() swaps once more).
    if (carry_history && last_a.width() > 0) {
      last_a.record_blit_to(cmd, clouds_a_[0]);
      last_b.record_blit_to(cmd, clouds_b_[0]);
    }
  });
  current_ = 1;
  swap_history();
  width_ = w;
  height_ = h;
  return true;
}

void CloudsModule::bind_march(bool sky_dome) {
  set_.bind_image(gpu::kMarchAOut, gpu::kMarchA, sky_dome ? dome_a_ : march_a_);
  set_.bind_image(gpu::kMarchBOut, gpu::kMarchB, sky_dome ? dome_b_ : march_b_);
}

void CloudsModule::swap_history() {
  current_ = 1 - current_;
  set_.bind_image(gpu::kCloudsAOut, gpu::kCloudsA, clouds_a_[current_]);
  set_.bind_image(gpu::kCloudsBOut, gpu::kCloudsB, clouds_b_[current_]);
  set_.bind_sampled_image(gpu::kHistoryA, clouds_a_[1 - current_]);
  set_.bind_sampled_image(gpu::kHistoryB, clouds_b_[1 - current_]);
}

std::vector<int32_t> CloudsModule::march_variant(MarchMode mode, const gpu::FrameParams& params) {
  // Each feature where clouds.comp would find it in the parameters, so that a variant draws
  // what the full shader draws. Without a light volume the diffusion light is the two-stream
  // light (its variant, 2, needs the volume).
  int lighting = int(params.cloud_phase.w + 0.5f);
  if (lighting == 2 && params.light_volume.w <= 0.0f) lighting = 1;
  return {mode == MarchMode::Baseline ? 1 : 0, params.voxel_info.x > 0 ? 1 : 0, lighting,
          params.cloud_flow.x > 0.0f ? 1 : 0};
}

void CloudsModule::record_march(VkCommandBuffer cmd, gpu::PassTimer& timer, MarchMode mode,
                                const gpu::FrameParams& params, int rows, int first_row) {
  const auto blocks = [&](int n) { return uint32_t((n + stride_ - 1) / stride_); };
  gpu::dispatch(cmd, march_.get(march_variant(mode, params)), timer, "clouds", blocks(width_),
                rows < 0 ? blocks(height_) : uint32_t(rows), 1, 8, 8, 1,
                gpu::DispatchConstants{glm::ivec4(first_row, 0, 0, 0)});
  // What the previous frame did not see, the columns and the rows: every other pixel, 8
  // samples a row of the dispatch (clouds.comp, entering_inc.glsl).
  const glm::ivec4& e = params.march_entering;
  const glm::ivec2 strips[2] = {{e.y, height_}, {width_, e.w}};
  for (int k = 0; k < 2; ++k) {
    const uint32_t samples = uint32_t((strips[k].x + 1) / 2 * ((strips[k].y + 1) / 2));
    if (rows < 0 && strips[k].x > 0 && strips[k].y > 0)
      gpu::dispatch(cmd, march_.get(march_variant(mode, params)), timer,
                    k == 0 ? "clouds_entering" : "clouds_entering_rows", 8, (samples + 7) / 8, 1, 8,
                    8, 1, gpu::DispatchConstants{glm::ivec4(0, 1 + k, 0, 0)});
  }
}

void CloudsModule::record_reconstruction(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  const auto blocks = [&](int n) { return uint32_t((n + stride_ - 1) / stride_); };
  gpu::dispatch(cmd, range_, timer, "march_range", blocks(width_), blocks(height_), 1, 8, 8, 1);
  gpu::dispatch(cmd, resolve_, timer, "resolve", uint32_t(width_), uint32_t(height_), 1, 8, 8, 1);
}

void CloudsModule::record_clear_sky(VkCommandBuffer cmd) {
  clouds_a_[current_].record_clear(cmd, {{0.0f, 0.0f, 0.0f, 1.0f}});
  clouds_b_[current_].record_clear(cmd, {{0.0f, 1.0f, 0.0f, 1.0f}});
}

void CloudsModule::record_clear_ground_light(VkCommandBuffer cmd) {
  // All the sky, no cloud light; seen from above, all the ground and no cloud light.
  ground_light_.record_clear(cmd, {{1.0f, 0.0f, 0.0f, 0.0f}});
}

void CloudsModule::record_ground_light(VkCommandBuffer cmd, gpu::PassTimer& timer, MarchMode mode) {
  gpu::dispatch(cmd, mode == MarchMode::Baseline ? ground_baseline_ : ground_default_, timer,
                "ground_light", 16, 16, 1, 16, 16, 1);
}

void CloudsModule::record_sky_dome(VkCommandBuffer cmd, gpu::PassTimer& timer, MarchMode mode,
                                   const gpu::FrameParams& params) {
  gpu::dispatch(cmd, march_.get(march_variant(mode, params)), timer, "sky_dome", kSkyDomeSize,
                kSkyDomeSize, 1, 8, 8, 1, gpu::DispatchConstants{glm::ivec4(0)});
}

void CloudsModule::record_profile(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  gpu::dispatch(cmd, profile_, timer, "cloud_profile", kCloudProfileSize, kCloudProfileSize, 1, 8,
                8, 1);
}

void CloudsModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  // Kept: the ground's light, read back by a later frame, and the cloud buffer, the next
  // frame's history.
  graph.import("ground_light", true);
  graph.import("cloud_layer", true);
  // The ground's light changes as slowly as the light volume's (3.9 ms on lavapipe). Without
  // nephele's clouds the gaps pass all the sky's light (a classical model's shadow is its
  // own, in the cloud buffer).
  const MarchMode mode = frame.scene.quality.mode;
  // The measurements: the profile reads only the density field's sources, the dome the march's.
  if (frame.plan.measure == FramePlan::Measure::kCloudProfile) {
    graph.output("cloud_profile");
    graph.add_pass(
        "cloud_profile", {"weather_map", "noise", "voxel_clouds"}, {"cloud_profile"},
        [timer = frame.timer, this](VkCommandBuffer cmd) { record_profile(cmd, timer()); });
  }
  if (frame.plan.measure == FramePlan::Measure::kSkyDome) {
    std::vector<std::string> reads = cloud_field_resources();
    reads.push_back("atmosphere");
    reads = with_diffusion(reads);
    graph.output("sky_dome");
    graph.add_pass("sky_dome", reads, {"sky_dome"},
                   [timer = frame.timer, this, mode, params = &frame.params](VkCommandBuffer cmd) {
                     record_sky_dome(cmd, timer(), mode, *params);
                   });
  }
  if (!frame.plan.volumetric)
    graph.add_pass("ground_light", {}, {"ground_light"},
                   [this](VkCommandBuffer cmd) { record_clear_ground_light(cmd); });
  else if (frame.plan.ground_light)
    graph.add_pass("ground_light", with_diffusion(cloud_field_resources()), {"ground_light"},
                   [timer = frame.timer, this, mode](VkCommandBuffer cmd) {
                     record_ground_light(cmd, timer(), mode);
                   });
  if (frame.plan.classic) return;  // a classical model draws the cloud layer
  if (frame.plan.volumetric) {
    std::vector<std::string> march_reads = cloud_field_resources();
    march_reads.insert(march_reads.end(), {"terrain", "ground_light", FrameGraph::kView});
    march_reads = with_diffusion(march_reads);
    graph.add_pass("march", march_reads, {"cloud_march"},
                   [timer = frame.timer, this, mode, params = &frame.params](VkCommandBuffer cmd) {
                     record_march(cmd, timer(), mode, *params);
                   });
    graph.add_pass(
        "clouds", {"cloud_march", "cloud_layer"}, {"cloud_layer"},
        [timer = frame.timer, this](VkCommandBuffer cmd) { record_reconstruction(cmd, timer()); });
  } else {
    graph.add_pass("clouds", {FrameGraph::kView}, {"cloud_layer"},
                   [this](VkCommandBuffer cmd) { record_clear_sky(cmd); });
  }
}

void CloudsModule::prepare(const FramePrepare& frame, FramePlan&) {
  swap_history();
  frame.params.march_entering = stride_ > 1 ? entering_region(frame.params) : glm::ivec4(0);
}

}  // namespace nephele

#include "render/modules/light_volume/light_volume.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <vector>

#include "render/disk_cache.h"
#include "render/frame_params.h"
#include "render/modules/weather/weather.h"
#include "render/texture_cache.h"

namespace nephele {

namespace {

// What shapes the clouds' density, for the light volume (and the diffusion light, rebuilt with
// it): the history's key less the image's size (the viewer's dynamic resolution changes it
// every few frames, and each change restarted the volume's build, 16 frames of 140 ms bands on
// lavapipe), how the view rays are marched and how their samples are lit, and what neither
// the volume nor the diffusion light reads: the cirrus sheet, the ground fog, the terrain,
// the particle clouds and the light shafts (a still that changes only those, or a viewer's
// edit of them, keeps the lighting: 5 s of a still on lavapipe).
std::string density_key(Scene scene) {
  const QualityParams shipped;
  scene.output = OutputParams{};
  scene.cirrus = CirrusParams{};
  scene.ground_fog = GroundFogParams{};
  scene.terrain = TerrainParams{};
  scene.particle_clouds = ParticleCloudParams{};
  scene.quality.light_shafts = shipped.light_shafts;
  scene.quality.screen_shaft_samples = shipped.screen_shaft_samples;
  scene.quality.screen_shaft_strength = shipped.screen_shaft_strength;
  scene.quality.screen_shaft_decay = shipped.screen_shaft_decay;
  scene.quality.primary_steps = shipped.primary_steps;
  scene.quality.light_steps = shipped.light_steps;
  scene.quality.march_stride = shipped.march_stride;
  scene.quality.cloud_downsample = shipped.cloud_downsample;
  scene.quality.voxel_march = shipped.voxel_march;
  scene.quality.voxel_shadow = shipped.voxel_shadow;
  scene.quality.sdf_light_tangent = shipped.sdf_light_tangent;
  return history_key(scene);
}
constexpr int kRows = gpu::LIGHT_VOLUME_XY * gpu::LIGHT_VOLUME_Z;
// The rows of a group of layers built together (light_volume.comp).
constexpr int kGroupRows = gpu::LIGHT_VOLUME_XY * gpu::LIGHT_VOLUME_LAYERS_UP;
static_assert(gpu::LIGHT_VOLUME_Z % gpu::LIGHT_VOLUME_LAYERS_UP == 0);
constexpr size_t kVolumeBytes = size_t(kRows) * gpu::LIGHT_VOLUME_XY * sizeof(float);
constexpr int rows_per_frame(int frames) {
  return (kRows + frames - 1) / frames;
}
}  // namespace

LightVolumeModule::LightVolumeModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx), set_(set), kernels_(ctx, set, "light_volume.comp.spv", 0, {1, 1}) {
  for (gpu::Texture& v : volumes_)
    v = gpu::Texture(ctx, gpu::LIGHT_VOLUME_XY, gpu::LIGHT_VOLUME_XY, gpu::LIGHT_VOLUME_Z,
                     VK_FORMAT_R32_SFLOAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  set_.bind_image(gpu::kLightVolumeOut, gpu::kLightVolume, volumes_[0]);
}

// Rebuilt when the clouds or the light (by 0.25 deg) change, when the camera has moved 1/20 of
// the half extent from the centre in cloud space (where the voxels are finest), when the
// clouds' features have moved 100 m against the volume's frame (shear, detail wind, the high
// layer's wind, the flow), or when the weather has evolved by 1/360 of its time scale (10 s at
// an hour: its clusters move a 2000th of a tile).
bool LightVolumeModule::stale(const Key& built, const Key& now, float half_m) const {
  return built.clouds != now.clouds ||
         glm::dot(built.light, now.light) < std::cos(glm::radians(0.25f)) ||
         glm::distance(built.centre_m, now.centre_m) > 0.05f * half_m ||
         std::abs(now.drift_m - built.drift_m) > 100.0f ||
         std::abs(now.weather_time - built.weather_time) > 1.0 / 360.0;
}

bool LightVolumeModule::same(const Key& built, const Key& now) {
  return built.clouds == now.clouds && built.light == now.light && built.centre_m == now.centre_m &&
         built.drift_m == now.drift_m && built.weather_time == now.weather_time;
}

std::string LightVolumeModule::disk_key(const Scene& scene, const Key& now) const {
  char values[192];
  std::snprintf(values, sizeof(values), "%a %a %a|%a %a|%a|%a|%a", now.light.x, now.light.y,
                now.light.z, now.centre_m.x, now.centre_m.y, now.drift_m, now.weather_time,
                double(scene.time_s));
  std::string text = code_identity();
  for (const std::string* part : {&ctx_.device_name(), &now.clouds})
    text.append("\n").append(*part);
  text.append("\n").append(values);
  std::vector<std::string> files = {scene.clouds.weather_map, scene.lab.grid};
  for (const VoxelCloudParams& c : scene.voxel_clouds) files.push_back(c.file);
  for (const std::string& file : files)
    if (!file.empty()) text.append("\n").append(file_identity(file));
  char name[24];
  std::snprintf(name, sizeof(name), "%016llx", static_cast<unsigned long long>(fnv1a64(text)));
  return name;
}

void LightVolumeModule::prepare(const Scene& scene, const std::string& clouds_key,
                                double weather_time, bool still, bool needed,
                                gpu::FrameParams& params) {
  completed_ = completed_edit_ = false;
  first_row_ = rows_ = 0;
  cache_key_.clear();
  read_from_.clear();
  with_voxels_ = params.voxel_info.x > 0;  // set by VoxelCloudsModule::prepare, which runs first
  with_flow_ = params.cloud_flow.x > 0.0f;
  const float half_m = float(scene.quality.light_volume_km) * 1000.0f;
  if (!needed || half_m <= 0.0f || scene.quality.mode == MarchMode::Baseline) {
    params.light_volume = glm::vec4(0.0f);
    read_key_.reset();
    build_key_.reset();
    return;
  }
  const Key now{clouds_key, glm::vec3(params.sun_dir),
                glm::vec2(scene.camera.position_m) - glm::vec2(params.wind_offset_m),
                cloud_relative_drift_m(scene), weather_time};
  // A still takes a volume built for exactly its own scene, so that it does not depend on what
  // was rendered before (a still 5 km from the last one would otherwise keep the diffusion
  // light's grids, 4.5 km across, centred on the last).
  const bool read_stale =
      !read_key_ || (still ? !same(*read_key_, now) : stale(*read_key_, now, half_m));
  // A build in progress that this frame does not need is dropped: a still's volume is the one
  // it reads, and an animation's build for other clouds is an edit taken back.
  if (build_key_ && !read_stale && (still || build_key_->clouds != now.clouds)) build_key_.reset();
  bool loaded = false;
  if (read_stale && (still || !read_key_)) {
    // At once: into the volume not read, which becomes the one read in this frame. A still's
    // from the disk cache, where an earlier process built it.
    build_key_ = now;
    next_row_ = 0;
    first_row_ = 0;
    rows_ = kRows;
    if (still) {
      cache_key_ = disk_key(scene, now);
      store_file_ = lighting_cache_file("volume", cache_key_);
      if (store_file_.empty()) cache_key_.clear();  // no cache
    }
    if (!cache_key_.empty()) {
      ctx_.wait_queue_idle();  // a frame in flight may still read the volume filled
      loaded = load_cached_texture(ctx_, volumes_[1 - read_], store_file_, kVolumeBytes);
      if (loaded) {
        read_from_ = store_file_;
        rows_ = 0;
      }
    }
  } else if (read_stale || build_key_) {
    if (!build_key_ || (read_stale && build_key_->clouds != now.clouds)) {
      build_key_ = now;  // a new build (one for other clouds is abandoned)
      next_row_ = 0;
    }
    const bool edit = build_key_->clouds != read_key_->clouds;
    first_row_ = next_row_;
    rows_ = std::min(rows_per_frame(edit ? kLightVolumeEditFrames : kLightVolumeBuildFrames),
                     kRows - next_row_);
  }
  next_row_ = first_row_ + rows_;
  if (loaded ||
      (rows_ > 0 && next_row_ >= kRows)) {  // complete this frame: read after its last band
    completed_edit_ = read_key_ && build_key_->clouds != read_key_->clouds;
    read_ = 1 - read_;
    read_key_ = build_key_;
    build_key_.reset();
    next_row_ = 0;
    completed_ = true;
    // Built whole for a still: kept in the disk cache once the frame has finished.
    store_volume_ = read_;
    if (!cache_key_.empty() && !loaded) store_slot_ = -2;  // the slot, set by the frame's prepare
  }
  const gpu::Texture& read = volumes_[read_];
  const gpu::Texture& built = completed_ ? volumes_[read_] : volumes_[1 - read_];
  set_.bind_storage_image(gpu::kLightVolumeOut, built);
  set_.bind_sampled_image(gpu::kLightVolume, read);
  const Key& target = completed_ ? *read_key_ : build_key_ ? *build_key_ : *read_key_;
  params.light_volume = glm::vec4(read_key_->centre_m, half_m, 1.0f);
  params.light_volume_build = glm::vec4(target.centre_m, half_m, 0.0f);
}

void LightVolumeModule::finished(int slot) {
  if (slot != store_slot_) return;
  store_slot_ = -1;
  store_lighting_texture(ctx_, volumes_[store_volume_], store_file_, kVolumeBytes);
}

void LightVolumeModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  if (rows_ == 0) return;
  // The band in pieces that each lie in one group of layers: a group reads the layers above
  // it, complete before it starts (a barrier after each piece). One pass in the timings.
  std::vector<glm::ivec2> pieces;  // first row, rows
  int most = 0;
  for (int row = first_row_; row < first_row_ + rows_;) {
    const int end = std::min(first_row_ + rows_, (row / kGroupRows + 1) * kGroupRows);
    pieces.emplace_back(row, end - row);
    most = std::max(most, end - row);
    row = end;
  }
  gpu::dispatch_repeated(
      cmd, kernels_.get({with_voxels_ ? 1 : 0, with_flow_ ? 1 : 0}), timer, "light_volume",
      int(pieces.size()), glm::uvec3(gpu::LIGHT_VOLUME_XY, most, 1), glm::uvec3(8, 8, 1),
      [&](int k) { return gpu::DispatchConstants{glm::ivec4(pieces[k].x, pieces[k].y, 0, 0)}; });
}

void LightVolumeModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  graph.import("light_volume", true);  // built over several frames
  graph.add_pass("light_volume", {"weather_map", "noise", "voxel_clouds", "atmosphere"},
                 {"light_volume"},
                 [timer = frame.timer, this](VkCommandBuffer cmd) { record(cmd, timer()); });
}

void LightVolumeModule::prepare(const FramePrepare& frame, FramePlan& plan) {
  // Only the march and Kajiya's model read the light volume.
  prepare(frame.scene, density_key(frame.scene), WeatherModule::weather_time(frame.scene),
          frame.still, plan.volumetric || frame.scene.clouds.model == CloudModel::Kajiya,
          frame.params);
  if (store_slot_ == -2) store_slot_ = frame.slot;
  plan.light_volume_built = completed_;
  plan.lighting_cache_key = cache_key_;
  if (!read_from_.empty())
    plan.cache_reads.push_back("light_volume read from " + read_from_.string());
  plan.light_volume_edited = completed_edit_;
  plan.building = plan.building || build_key_.has_value();
  plan.relit = plan.relit || completed_edit_;
}

}  // namespace nephele

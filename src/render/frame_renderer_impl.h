// nephele — internal: the state behind FrameRenderer, shared with Renderer (render.cpp),
// which records each frame into a command buffer of its own context and waits for it.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "nephele/frame.h"
#include "render/frame_params.h"
#include "render/passes.h"

namespace nephele {

struct FrameRenderer::Impl {
  Impl(const RendererOptions& options);
  Impl(const HostVulkan& host, const RendererOptions& options);

  gpu::Context ctx;
  GpuState state;
  bool verbose = false;
  std::optional<uint32_t> noise_seed_built;  // noise textures are valid for this seed
  std::optional<std::string> weather_built;  // key of the weather map in the texture
  std::optional<Scene> previous;             // the scene of the last frame recorded
  std::string previous_key;                  // its history_key()
  glm::vec3 previous_light_dir{0.0f};        // its key light (sky_lights)
  long long frame_counter = 0;               // frames since the history (re)started
  long long frames_recorded = 0;             // record_frame() calls that recorded a frame
  int last_slot = -1;                        // the slot of the last frame recorded
  // Per slot: the stats of the frame recorded there, waiting for its timings (collect()).
  std::optional<FrameStats> pending[gpu::kFramesInFlight];
  std::optional<FrameStats> completed;

  // The light volume in the buffer: what it was built for.
  struct LightVolumeKey {
    std::string clouds;    // history_key() of the scene
    glm::vec3 sun{0.0f};
    glm::vec2 centre_m{0.0f};  // in cloud space
    float drift_m = 0.0f;      // cloud_relative_drift_m
  };
  std::optional<LightVolumeKey> light_volume_built;
  // Sets params.light_volume; true when the volume must be rebuilt this frame.
  bool plan_light_volume(const Scene& scene, const std::string& key, gpu::FrameParams& params);

  // Inputs of the sky-view LUT in the texture and the LUT frame it was built in.
  struct SkyViewBuilt {
    SkyViewKey key;
    glm::vec4 up, forward;
  };
  std::optional<SkyViewBuilt> sky_view_built;
  // Hillaire's transmittance and multiple-scattering tables: what they were built for, and
  // their copy on the host for the lighting computed on the CPU.
  std::optional<AtmosphereParams> luts_built;
  AtmosphereTables tables;
  void update_atmosphere_luts(const Scene& scene);
  // The brute-force reference sky, tile by tile (one submission each), into state.reference_sky.
  void render_reference_sky(gpu::FrameParams params);

  FrameImages record_frame(VkCommandBuffer cmd, const Scene& scene, bool still);
  // After the frame of `slot` completed: its stats with the passes' timings (moved into
  // `completed`); nothing when none is pending there.
  void collect(int slot);
  // Reads back the last frame recorded (the device must have finished it).
  Frame download_last(const Scene& scene);
  // The clouds pass over the sky dome (after a frame, with its parameters and textures):
  // the share of the observer's upper hemisphere with cloud T < 0.5, and the pass's time.
  double measure_sky_cover(gpu::FrameParams params, MarchMode mode, double& ms);
  CloudProfile cloud_profile(const Scene& scene);
  gpu::FrameParams last_params{};  // of the last frame recorded

  void update_textures(const Scene& scene, const gpu::FrameParams& params);
  void upload_weather_png(const std::string& path);
  void resize_weather_map(uint32_t width, uint32_t height);
  void print_timings(const std::vector<std::pair<std::string, double>>& results,
                     const char* note) const;
};

}  // namespace nephele

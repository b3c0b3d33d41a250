// nephele — internal: the state behind FrameRenderer, shared with Renderer (render.cpp),
// which records each frame into a command buffer of its own context and waits for it.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "nephele/frame.h"
#include "render/frame_graph.h"
#include "render/frame_params.h"
#include "render/modules/atmosphere/atmosphere.h"
#include "render/modules/classic_clouds/classic_clouds.h"
#include "render/modules/clouds/clouds.h"
#include "render/modules/compose/compose.h"
#include "render/modules/host_lighting/host_lighting.h"
#include "render/modules/host_scene/host_scene.h"
#include "render/modules/light_shafts/light_shafts.h"
#include "render/modules/light_volume/light_volume.h"
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
#include "render/path_majorant.h"

namespace nephele {

// Share of above-horizon pixels (view ray rising above the camera's local horizontal) whose
// cloud transmittance is below 0.5 (FrameStats::cloud_cover_fraction).
double cloud_cover_fraction(const Scene& scene, const Image& clouds);

struct FrameRenderer::Impl {
  Impl(const RendererOptions& options);
  Impl(const HostVulkan& host, const RendererOptions& options);
  Impl(std::unique_ptr<gpu::Context> context, const RendererOptions& options);

  std::unique_ptr<gpu::Context> owned_ctx;  // its own, or the one on the host's device
  gpu::Context& ctx;
  GpuState state;
  bool verbose = false;
  ProgressCallback progress;
  std::optional<Scene> previous;             // the scene of the last frame recorded
  std::string previous_key;                  // its history_key()
  bool previous_reusable =
      false;  // it was recorded with FrameOptions::reuse_settled (and may be reused)
  bool previous_display = false;   // it made the display image
  bool previous_still = false;     // it was a still (every pixel marched at full resolution)
  int relit_frames_left = 0;       // frames whose marched pixels restart their means
  long long unchanged_frames = 0;  // frames recorded since the scene (or reuse_settled) changed
  glm::vec3 previous_light_dir{0.0f};        // its key light (sky_lights)
  long long frame_counter = 0;               // frames since the history (re)started
  long long frames_recorded = 0;             // record_frame() calls that recorded a frame
  int last_slot = -1;                        // the slot of the last frame recorded
  // Per slot: the stats of the frame recorded there, waiting for its timings (collect()).
  std::optional<FrameStats> pending[gpu::kFramesInFlight];
  std::optional<FrameStats> completed;
  std::optional<HostLighting> completed_lighting;  // of the same frame

  // The modules, each owning its kernels, textures and rebuild rule (src/render/modules).
  NoiseModule noise;
  AtmosphereModule atmosphere;
  WeatherModule weather;
  LightVolumeModule light_volume;
  VoxelCloudsModule voxel_clouds;
  SkyViewModule sky_view;
  CloudsModule clouds;
  ParticleCloudsModule particles;
  ClassicCloudsModule classic_clouds;  // seed 004's models, when clouds.model names one
  PostModule post;                      // screen-space god rays, bloom and glare
  LightShaftsModule light_shafts;       // volumetric light shafts, read by compose
  TerrainModule terrain;                // the heightfield under the clouds
  HostSceneModule host_scene;           // the host's geometry (FrameOptions::host_scene)
  HostLightingModule host_lighting;     // the host's light (FrameOptions::lighting)
  ParticleLightGpuModule particle_light;  // only measured against the CPU lighting
  PathTracerModule path_tracer;
  // The modules in their own folders (registered_modules(): the ground fog, a medium of
  // compose), made once, prepared and added to the graph before compose.
  std::vector<std::unique_ptr<RenderModule>> registered;
  ComposeModule compose{state};  // the final image: compose.comp, then the stars
  DisplayModule display{state};  // its meter and display image
  // The modules of a frame in the order their passes are added: the graph keeps it wherever
  // their reads and writes allow.
  std::vector<RenderModule*> frame_modules() {
    std::vector<RenderModule*> modules{
        &noise,   &atmosphere, &voxel_clouds,  &weather,        &sky_view,  &light_volume, &clouds,
        &terrain, &host_scene, &host_lighting, &classic_clouds, &particles, &light_shafts};
    for (const auto& module : registered) modules.push_back(module.get());
    modules.insert(modules.end(), {&compose, &post, &display, &path_tracer});
    return modules;
  }
  // The order of the modules' prepare (RenderModule::prepare): the voxel clouds first (they
  // widen the cloud shell); what reads files or may still refuse the frame (the host's scene,
  // a terrain mesh that does not parse, particles on a queue without graphics) before the
  // modules that advance their builds for this frame (weather, light volume, sky view), so that
  // a refused frame leaves them as they were; the weather's map file is read before it
  // advances. The clouds' history swaps last.
  std::vector<RenderModule*> prepare_order() {
    std::vector<RenderModule*> modules{
        &voxel_clouds, &host_scene,     &terrain, &particles,    &weather,       &light_volume,
        &sky_view,     &classic_clouds, &post,    &light_shafts, &host_lighting, &clouds};
    for (const auto& module : registered) modules.push_back(module.get());
    return modules;
  }
  // Records the pass `pass` of `graph` (built for a measurement: FramePlan::measure), after
  // the passes it needs when `with_needs`; without, it reads what the last frame left.
  void record_measure(VkCommandBuffer cmd, const FrameGraph& graph, const std::string& pass,
                      bool with_needs) const;

  void update_atmosphere_luts(const Scene& scene);
  // The brute-force reference sky, tile by tile (one submission each), into state.reference_sky.
  void render_reference_sky(gpu::FrameParams params);

  FrameImages record_frame(VkCommandBuffer cmd, const Scene& scene, const FrameOptions& options);
  // What record_frame reports of the frame it recorded (the timings come with collect), and
  // hands the host: the images of `slot`, with the host's lighting when it asked for it.
  FrameStats frame_stats(const Scene& scene, const SkyLights& lights) const;
  FrameImages frame_images(int slot, bool host_lighting_images) const;
  // The frame's passes as its modules declare them (render_module.h), compiled: the order, the
  // barriers and the part the march needs come from the graph (frame_graph.h).
  FrameGraph frame_graph(const Scene& scene, const gpu::FrameParams& params, const FramePlan& plan);
  // A still image with progress: the passes the march needs, then the march in bands of rows,
  // each submitted and waited for and reported. Returns the passes left for the frame.
  std::vector<std::string> march_in_bands(const FrameGraph& graph, const Scene& scene,
                                          const gpu::FrameParams& params);
  std::vector<PassTiming> band_timings;  // of march_in_bands, for the frame's stats
  // After the frame of `slot` completed: its stats with the passes' timings (moved into
  // `completed`); nothing when none is pending there.
  void collect(int slot);
  // Reads back the last frame recorded (the device must have finished it).
  Frame download_last(const Scene& scene);
  // The clouds pass over the sky dome (after a frame, with its parameters and textures):
  // the share of the observer's upper hemisphere with cloud T < 0.5, and the pass's time.
  double measure_sky_cover(const Scene& scene, double& ms);
  // After the last frame completed: compose again over its resolved clouds, writing film layer
  // `layer` (FramePlan::film_layer: 1 sky, 2 clouds, 3 depth) into its final
  // image, and read it back. The frame's own image must have been read back before.
  Image compose_layer(const Scene& scene, int layer);
  CloudProfile cloud_profile(const Scene& scene);
  // FrameRenderer::cloud_query: the noise textures read back (made first when stale).
  CloudQuery cloud_query(const Scene& scene);
  ReferenceImage render_reference(const Scene& scene, const ReferenceOptions& options);
  gpu::FrameParams lab_reference_params(const Scene& scene, const ReferenceOptions& options);
  gpu::FrameParams planet_reference_params(const Scene& scene, const ReferenceOptions& options);
  // The base noise's block bounds (path_majorant.h) for the seed they were made for.
  NoiseBlockBounds noise_bounds;
  uint32_t noise_bounds_seed = ~0u;
  gpu::FrameParams last_params{};  // of the last frame recorded
  FramePlan last_plan{};           // of the last frame recorded
  // Set while Renderer draws a still in tiles: the frames recorded are this window of it.
  std::optional<ImageWindow> window;

  void update_noise(const Scene& scene, const gpu::FrameParams& params);
  void print_timings(const std::vector<std::pair<std::string, double>>& results,
                     const char* note) const;
};

}  // namespace nephele

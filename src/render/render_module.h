// nephele — the module contract: what the frame asks of each of its modules
// (src/render/modules). A module owns its kernels, images and rebuild rule; each frame it
// declares the resources it keeps and the passes it records, each with the resources (by name)
// it reads and writes, and the frame graph (frame_graph.h) orders them and places the barriers.
// The frame owns no pass's logic: it builds the graph from its modules in a fixed order and
// executes it (FrameRenderer::Impl::frame_graph).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "gpu/kernel.h"
#include "nephele/scene.h"
#include "render/frame_graph.h"
#include "render/gpu_params.h"

namespace nephele {

class ImageLayers;
struct FrameOptions;
struct SkyLights;

// What a frame draws, decided from the scene and the modules' prepare.
struct FramePlan {
  bool volumetric = false;   // nephele's clouds are marched
  bool classic = false;      // a classical model (seed 004) draws the cloud layer instead
  bool host_scene = false;   // the host's geometry is drawn (FrameOptions::host_scene)
  bool host_lighting = false;  // the host's light is computed (FrameOptions::lighting)
  bool shafts = false;       // volumetric light shafts
  bool post = false;         // screen-space god rays, bloom and glare
  bool display = false;      // the display image (tonemap) is wanted
  bool ground_light = false; // the clouds' light on the ground is measured this frame
  bool layers = false;       // a translucent layer (a module's NAME_layer.glsl) draws this frame
  bool media = false;        // a medium's module (the ground fog) is on: compose draws media
  bool light_volume_built = false;  // a light volume is completed this frame (LightVolumeModule)
  bool light_volume_edited = false;  // and it was rebuilt for an edit of the clouds
  // A still's lighting in the disk cache (render/disk_cache.h): the hash of everything the light
  // volume, and what is built with it, are made from (LightVolumeModule), when this frame
  // builds or reads one; empty otherwise. A module keeps what it builds with the light volume
  // under that name, and reads it back instead of building it.
  std::string lighting_cache_key;
  // What modules read from the disk cache this frame instead of building it ("PASS from FILE"),
  // for --verbose.
  std::vector<std::string> cache_reads;
  // A module builds over frames and is not done (the light volume, the diffusion field): the
  // view is not settled (FrameOptions::reuse_settled), even if the scene is unchanged.
  bool building = false;
  // A module completed a build for an edit this frame (the light volume, the diffusion field):
  // the lighting changed, and the clouds' history restarts its means (FrameParams::cloud_grid).
  bool relit = false;
  // What the graph is built for besides a frame's image: a measurement whose pass the module
  // that owns it adds as an output; only that pass and what it needs are recorded
  // (FrameGraph::dependencies_of), so it runs after the same passes, in the same order, as in
  // a frame. kSkyDome: the clouds over the observer's dome (the sky cover); kCloudProfile: the
  // clouds' density by altitude; kReference: the path tracer's samples.
  enum class Measure { kNone, kSkyDome, kCloudProfile, kReference };
  Measure measure = Measure::kNone;
  bool planet_reference = true;  // kReference: the planet's scene, else the lab's grid
  // The film layer compose writes (render --layers): 0 the image, 1 the sky behind the clouds,
  // 2 the clouds premultiplied (a = 1 - T), 3 the clouds' depth (m).
  int film_layer = 0;
};

// What a module's passes see of the frame being recorded.
struct FrameSetup {
  const Scene& scene;
  const gpu::FrameParams& params;
  const FramePlan& plan;
  // The pass timer of the frame's slot: valid once the frame's command buffer has begun, which
  // is when the passes record.
  std::function<gpu::PassTimer&()> timer;
};

// What the clouds' density field reads: the passes that sample it (the march, the ground's
// light, a classical model, the shafts) read these.
inline std::vector<std::string> cloud_field_resources() {
  return {"weather_map", "noise", "voxel_clouds", "light_volume"};
}

// What a module sees of the frame before the graph is built.
struct FramePrepare {
  const Scene& scene;
  gpu::FrameParams& params;  // the frame's block: each module fills its own part
  int slot;    // the frame slot recorded: a module keeps per-slot copies of what frames read
  bool still;  // a still image (every pixel marched), not a frame of a sequence
  int width = 0, height = 0;              // the image's size (pixels)
  const FrameOptions* options = nullptr;  // the host's scene and light, if any
  const SkyLights* lights = nullptr;      // the frame's ephemeris and key light
};

class RenderModule {
 public:
  virtual ~RenderModule() = default;
  // Before the graph is built, in the frame's prepare order (FrameRenderer::Impl::
  // prepare_modules): updates what the module keeps for this frame (its uniform blocks, its
  // part of the frame's parameters, the images it rebuilds) and says what the frame draws
  // with it (`plan`). May refuse the frame (InputError) only before any module that advances
  // a build has run: the order puts those that read files first.
  virtual void prepare(const FramePrepare&, FramePlan&) {}
  // Declares what the module keeps (FrameGraph::import, output) and adds this frame's passes.
  virtual void add_passes(FrameGraph& graph, const FrameSetup& frame) = 0;
  // The frame recorded in `slot` has finished on the device (FrameRenderer::Impl::collect): a
  // module may read back what it built in it (the disk cache's files).
  virtual void finished(int /*slot*/) {}
};

// What a module is made with: the device, the frame's descriptor table (its set-1 bindings) and
// the image layers compose blends (a module that draws a layer writes its own).
struct ModuleContext {
  gpu::Context& ctx;
  gpu::DescriptorSet& set;
  ImageLayers& layers;
};

// The modules that live in their own folder, src/render/modules/NAME/, whose NAME.h declares
//   std::unique_ptr<RenderModule> make_NAME_module(const ModuleContext&);
// listed at configure time (cmake/module_registry.cmake) in the folders' order. The frame makes
// each once and runs its prepare and add_passes with its own modules': adding such a module
// edits nothing outside its folder.
struct RegisteredModule {
  const char* name;
  std::unique_ptr<RenderModule> (*make)(const ModuleContext&);
};
const std::vector<RegisteredModule>& registered_modules();

}  // namespace nephele

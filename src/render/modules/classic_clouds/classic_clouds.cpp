#include "render/modules/classic_clouds/classic_clouds.h"

#include "render/glsl.h"

namespace nephele {

// Gardner's cirrus: his plane's texture stretched eightfold along x into streaks, and at most
// this opaque (a thin veil).
constexpr float kGardnerCirrusStretch = 8.0f;
constexpr float kGardnerCirrusOpacity = 0.6f;

int blinn_phase_kind(const std::string& name) {
  if (name == "constant") return glsl::BLINN_PHASE_CONSTANT;
  if (name == "anisotropic") return glsl::BLINN_PHASE_ANISOTROPIC;
  if (name == "lambert") return glsl::BLINN_PHASE_LAMBERT;
  if (name == "rayleigh") return glsl::BLINN_PHASE_RAYLEIGH;
  return glsl::BLINN_PHASE_HG;
}

ClassicCloudsModule::ClassicCloudsModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx), set_(set), metaballs_(ctx, set) {}

ClassicCloudsModule::~ClassicCloudsModule() = default;

void ClassicCloudsModule::prepare(const Scene& scene, gpu::FrameParams& params) {
  const ClassicCloudParams& c = scene.classic;
  const float thickness_m = scene.clouds.top_altitude_m - scene.clouds.bottom_altitude_m;
  params.classic_blinn = glm::vec4(
      glsl::blinn_optical_depth(c.blinn_particles_per_m3, c.blinn_particle_radius_m, thickness_m),
      c.blinn_albedo, c.blinn_phase_x, float(blinn_phase_kind(c.blinn_phase)));
  params.classic_options =
      glm::vec4(c.seed_formulas ? 1.0f : 0.0f, c.gardner_clouds == "cumulus" ? 0.0f : 1.0f,
                float(c.gardner_terms), scene.clouds.coverage);
  params.classic_gardner =
      glm::vec4(2.0f * glsl::PI / c.gardner_period_m, c.gardner_t1, c.gardner_t2, c.gardner_range);
  params.classic_gardner_shading =
      glm::vec4(c.gardner_ambient, c.gardner_texture, c.gardner_specular, c.gardner_spacing_m);
  const bool cirrus = c.gardner_clouds == "cirrus";
  params.classic_gardner_plane =
      glm::vec4(cirrus ? scene.cirrus.altitude_m : scene.clouds.bottom_altitude_m,
                cirrus ? kGardnerCirrusStretch : 1.0f, cirrus ? kGardnerCirrusOpacity : 1.0f, 0.0f);
  params.classic_kajiya =
      glm::vec4(float(c.kajiya_levels), c.kajiya_reference ? 1.0f : 0.0f, 0.0f, 0.0f);
  if (scene.clouds.model == CloudModel::Nishita) metaballs_.prepare(scene, params);
}

void ClassicCloudsModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer, CloudModel model,
                                 int width, int height) {
  struct Pass {
    CloudModel model;
    int constant;
    const char* name;
  };
  static constexpr Pass kPasses[] = {
      {CloudModel::Blinn, glsl::CLASSIC_BLINN, "classic_blinn"},
      {CloudModel::Gardner, glsl::CLASSIC_GARDNER, "classic_gardner"},
      {CloudModel::GardnerQuadrics, glsl::CLASSIC_GARDNER_QUADRICS, "classic_gardner_quadrics"},
      {CloudModel::Kajiya, glsl::CLASSIC_KAJIYA, "classic_kajiya"},
      {CloudModel::Nishita, glsl::CLASSIC_NISHITA, "classic_nishita"}};
  if (model == CloudModel::Nishita) metaballs_.record_light(cmd, timer);
  for (const Pass& pass : kPasses) {
    if (pass.model != model) continue;
    std::unique_ptr<gpu::Kernel>& kernel = kernels_[model];
    if (!kernel)
      kernel = std::make_unique<gpu::Kernel>(ctx_, set_, "classic_clouds.comp.spv",
                                             std::vector<int32_t>{pass.constant});
    gpu::dispatch(cmd, *kernel, timer, pass.name, uint32_t(width), uint32_t(height), 1, 8, 8, 1);
  }
}

void ClassicCloudsModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  if (!frame.plan.classic) return;
  const CloudModel model = frame.scene.clouds.model;
  const int width = frame.params.cloud_grid.x, height = frame.params.cloud_grid.y;
  std::vector<std::string> reads = cloud_field_resources();
  reads.push_back(FrameGraph::kView);
  graph.add_pass("clouds", reads, {"cloud_layer"},
                 [timer = frame.timer, this, model, width, height](VkCommandBuffer cmd) {
                   record(cmd, timer(), model, width, height);
                 });
}

void ClassicCloudsModule::prepare(const FramePrepare& frame, FramePlan&) {
  prepare(frame.scene, frame.params);
}

}  // namespace nephele

#include "render/modules/particle_clouds/particle_clouds.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numeric>
#include <vector>

#include "nephele/error.h"
#include "particles/particle_lighting.h"
#include "particles/perlin.h"
#include "render/glsl.h"

namespace nephele {

namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// The particles' procedural textures (no image assets): PARTICLE_TEXTURES tiles side by side,
// each a detail pattern of fractal Perlin noise with its own frequency, stored halved in r
// (the shader doubles it) and scaled so that its mean over the particle, weighted by
// particle_profile, is 1: the opacity the CPU lighting splats is the drawn one on average.
std::vector<uint8_t> particle_texels() {
  const int n = gpu::PARTICLE_TEXTURE_SIZE, tiles = gpu::PARTICLE_TEXTURES;
  std::vector<uint8_t> texels(size_t(n) * n * tiles * 4, 0);
  const particles::PerlinNoise noise(20260122);
  for (int t = 0; t < tiles; ++t) {
    std::vector<float> detail(size_t(n) * n);
    double weighted = 0.0, weights = 0.0;
    const float frequency = 3.0f + 1.5f * float(t);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const float u = (x + 0.5f) / n * 2.0f - 1.0f, v = (y + 0.5f) / n * 2.0f - 1.0f;
        const float f =
            noise.noise3(u * frequency, v * frequency, 7.3f * t) +
            0.5f * noise.noise3(2.0f * u * frequency, 2.0f * v * frequency, 7.3f * t + 3.1f);
        const float d = std::clamp(1.0f + 0.6f * f, 0.3f, 1.7f);
        detail[size_t(y) * n + x] = d;
        const float w = glsl::particle_profile(u * u + v * v);
        weighted += w * d, weights += w;
      }
    const float scale = float(weights / weighted);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const float d = std::min(detail[size_t(y) * n + x] * scale, 2.0f);
        uint8_t* texel = &texels[(size_t(y) * n * tiles + size_t(t) * n + x) * 4];
        texel[0] = texel[1] = texel[2] = uint8_t(d * 0.5f * 255.0f + 0.5f);
        texel[3] = 255;
      }
  }
  return texels;
}

}  // namespace

ParticleCloudsModule::ParticleCloudsModule(gpu::Context& ctx, gpu::DescriptorSet& set,
                                           ImageLayers& layers)
    : ctx_(ctx), set_(set), layers_(layers), impostors_(ctx, set) {
  const int n = gpu::PARTICLE_TEXTURE_SIZE, tiles = gpu::PARTICLE_TEXTURES;
  textures_ = gpu::Texture(ctx, uint32_t(n * tiles), uint32_t(n), 1, VK_FORMAT_R8G8B8A8_UNORM,
                           VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  const std::vector<uint8_t> texels = particle_texels();
  gpu::Buffer staging(ctx, VkDeviceSize(texels.size()), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  std::memcpy(staging.data(), texels.data(), texels.size());
  // Until a scene has particle clouds: a one-particle buffer.
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { textures_.record_upload(cmd, staging); });
  for (gpu::Buffer& b : buffers_)
    b = gpu::Buffer(ctx, sizeof(gpu::ParticleGpu), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  set_.bind_sampled_image(gpu::kParticleTextures, textures_);
  set_.bind_buffer(gpu::kParticles, buffers_[0], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
}

ParticleCloudsModule::~ParticleCloudsModule() = default;

void ParticleCloudsModule::prepare(const Scene& scene, int slot, int width, int height, bool still,
                                   gpu::FrameParams& params) {
  const ParticleCloudParams& p = scene.particle_clouds;
  active_ = p.coverage > 0.0f;
  // The layer's pixels; compose.comp filters it up to the output's (its projection is the
  // same, in coordinates across the image).
  const int layer_width = std::max(1, int(std::lround(float(width) * p.layer_resolution)));
  const int layer_height = std::max(1, int(std::lround(float(height) * p.layer_resolution)));
  stats_ = {};
  near_first_ = near_count_ = 0;
  params.particle_shading =
      glm::vec4(p.albedo, p.phase_g, p.rayleigh_phase ? 1.0f : 0.0f, p.opacity);
  params.particle_light = glm::vec4(p.diffuse_strength, float(layer_width) / float(width),
                                    float(layer_height) / float(height), 0.0f);
  if (!active_) {
    field_ = {};
    field_shape_.reset();
    return;
  }
  if (!ctx_.has_graphics())
    throw InputError("particle_clouds.coverage = " + std::to_string(p.coverage) +
                     ": particle clouds are drawn by a raster pass, and the queue of " +
                     ctx_.device_name() + " has no graphics");
  if (!pass_)
    pass_ = std::make_unique<gpu::RasterPass>(
        ctx_, set_, std::vector<VkFormat>{ImageLayers::kFormat, ImageLayers::kFormat}, true,
        std::vector<gpu::RasterShaders>{
            {"particles.vert.spv", "particles.frag.spv"},
            {"impostor.vert.spv", "impostor.frag.spv", {gpu::IMPOSTOR_DIRECT}},
            {"impostor.vert.spv", "impostor.frag.spv", {gpu::IMPOSTOR_TILES}}});
  camera_.forward = glm::vec4(glm::vec3(params.camera_forward), params.camera_pos_m.w);
  camera_.right = glm::vec4(glm::vec3(params.camera_right), params.camera_forward.w);
  camera_.up = glm::vec4(glm::vec3(params.camera_up), 0.0f);
  // The field, for the evolving noise's time step.
  const float step_s = p.evolution_s > 0.0f ? p.evolution_s / 64.0f : 0.0f;
  const float field_time_s = step_s > 0.0f ? std::floor(scene.time_s / step_s) * step_s : 0.0f;
  const particles::FieldShape shape = particles::field_shape(p, field_time_s);
  auto start = std::chrono::steady_clock::now();
  const bool regenerated = shape != field_shape_;
  if (regenerated) {
    field_ = particles::generate_field(p, field_time_s);
    field_shape_ = shape;
    field_time_s_ = field_time_s;
    stats_.generate_ms = ms_since(start);
  }
  // Lit by the key light (the sun, or the moon at night), the planet frame's axes being ENU's.
  start = std::chrono::steady_clock::now();
  const particles::RelightReport relit = particles::relight(
      field_, glm::vec3(params.sun_dir), p, still ? ~size_t(0) : kParticleRelightBudget);
  stats_.relit_clouds = relit.clouds;
  stats_.lighting_ms = ms_since(start);

  // Which clouds are impostors, and which of those are drawn into the atlas this frame; the
  // field drifts with the wind since it was generated.
  start = std::chrono::steady_clock::now();
  const glm::vec3 offset =
      glm::vec3(p.wind_mps * (scene.time_s - field_time_s_), 0.0f) - scene.camera.position_m;
  const ImpostorCache::Plan plan =
      impostors_.plan(field_, p, offset, layer_height, params.camera_pos_m.w, regenerated, still);
  // The particle buffer: each updated impostor's particles, back to front from the eye, then
  // all the particles drawn one by one, back to front.
  size_t total = 0;
  for (size_t c : plan.updates) total += field_.clouds[c].particles.size();
  for (size_t c : plan.particle_clouds) total += field_.clouds[c].particles.size();
  gpu::Buffer& buffer = buffers_[slot];
  const VkDeviceSize bytes = std::max<VkDeviceSize>(total, 1) * sizeof(gpu::ParticleGpu);
  if (buffer.size() < bytes) {
    ctx_.wait_queue_idle();  // the frame in flight may still read the old buffer
    buffer = gpu::Buffer(ctx_, bytes + bytes / 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  }
  auto* out = static_cast<gpu::ParticleGpu*>(buffer.data());
  uint32_t written = 0;
  struct Entry {
    float distance2;
    const particles::Particle* particle;
  };
  std::vector<Entry> order;
  const auto write_back_to_front = [&](const std::vector<size_t>& clouds) {
    order.clear();
    for (size_t c : clouds)
      for (const particles::Particle& q : field_.clouds[c].particles) {
        const glm::vec3 d = q.position_m + offset;
        order.push_back({glm::dot(d, d), &q});
      }
    std::sort(order.begin(), order.end(),
              [](const Entry& a, const Entry& b) { return a.distance2 > b.distance2; });
    for (const Entry& e : order) {
      const particles::Particle& q = *e.particle;
      out[written].position_radius = glm::vec4(q.position_m + offset, q.radius_m);
      out[written].shading = glm::vec4(q.light, float(q.texture), 0.0f, 0.0f);
      ++written;
    }
  };
  std::vector<uint32_t> first, count;
  for (size_t c : plan.updates) {
    first.push_back(written);
    write_back_to_front({c});
    count.push_back(written - first.back());
  }
  near_first_ = written;
  write_back_to_front(plan.particle_clouds);
  near_count_ = written - near_first_;
  impostors_.place_updates(field_, first, count, slot);
  stats_.sort_ms = ms_since(start);
  stats_.particles = near_count_;
  stats_.field_particles = field_.particles();
  stats_.clouds = int(field_.clouds.size());
  set_.bind_buffer(gpu::kParticles, buffer, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);

  layers_.require(width, height);
  layer_width_ = layer_width;
  layer_height_ = layer_height;
}

ParticleCloudStats ParticleCloudsModule::frame_stats() const {
  ParticleCloudStats out;
  out.particles = stats_.field_particles;
  out.drawn = stats_.particles;
  out.layer_width = layer_width_;
  out.layer_height = layer_height_;
  out.clouds = stats_.clouds;
  out.relit_clouds = stats_.relit_clouds;
  out.generate_ms = stats_.generate_ms;
  out.lighting_ms = stats_.lighting_ms;
  out.sort_ms = stats_.sort_ms;
  const ImpostorFrameStats& im = impostors_.stats();
  out.impostors = im.impostors;
  out.impostor_updates = im.updates;
  out.impostors_waiting = im.waiting;
  out.impostor_resolution_scale = im.resolution_scale;
  out.atlas_occupancy = im.atlas.occupancy;
  out.atlas_wasted = im.atlas.wasted;
  out.atlas_fragmentation = im.atlas.fragmentation;
  out.atlas_defragmentations = im.atlas.defragmentations;
  out.atlas_defragmentations_per_s = im.atlas.defragmentations_per_s;
  out.atlas_downsized = im.atlas.downsized;
  out.atlas_failed = im.atlas.failed;
  out.atlas_mean_op_us = im.atlas.mean_op_us;
  out.atlas_max_op_us = im.atlas.max_op_us;
  return out;
}

void ParticleCloudsModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  if (active_) {
    impostors_.record_updates(cmd, timer);
    std::vector<gpu::RasterDraw> draws;
    if (impostors_.quad_count() > 0) draws.push_back(impostors_.quads(camera_));  // the farthest
    gpu::RasterDraw near;
    near.first_vertex = 6 * near_first_;
    near.vertex_count = 6 * near_count_;
    near.constants = camera_;
    draws.push_back(near);
    pass_->record(cmd, timer, "particles",
                  {layers_.target(gpu::LAYER_PARTICLES, layer_width_, layer_height_),
                   layers_.target(gpu::LAYER_PARTICLE_DEPTH, layer_width_, layer_height_)},
                  draws);
    drawn_ = true;
  } else if (drawn_) {  // a scene without particle clouds after one with them
    layers_.texture().record_clear_layer(cmd, gpu::LAYER_PARTICLES);
    layers_.texture().record_clear_layer(cmd, gpu::LAYER_PARTICLE_DEPTH);
    gpu::full_barrier(cmd);
    drawn_ = false;
  }
}

void ParticleCloudsModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  graph.import("layers");  // the translucent layers: read whether or not they are drawn
  graph.add_pass("particles", {"sky_view", "terrain", "atmosphere", FrameGraph::kView}, {"layers"},
                 [timer = frame.timer, this](VkCommandBuffer cmd) { record(cmd, timer()); });
}

void ParticleCloudsModule::prepare(const FramePrepare& frame, FramePlan& plan) {
  prepare(frame.scene, frame.slot, frame.width, frame.height, frame.still, frame.params);
  plan.layers = plan.layers || active();
}

}  // namespace nephele

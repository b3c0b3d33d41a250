#include "render/modules/cloud_diffusion/cloud_diffusion.h"

#include <algorithm>
#include <cstring>

#include "render/gpu_params.h"
#include "render/texture_cache.h"
// The block's one definition, as the shaders have it.
#include "render/modules/cloud_diffusion/cloud_diffusion_gpu_inc.glsl"

namespace nephele {

namespace {
constexpr const char* kBlockName = "CloudDiffusionBlock";
// The finest grid's horizontal half extent: 70 m cells at 128 a side (the lab's cube, 1 km, 14
// across); each further cascade's 4 times as wide (280 m cells to 18 km: the clouds a view
// above the layer or of a storm sees).
constexpr float kHalfExtentM = 4500.0f;
constexpr float kCascadeScale = 4.0f;
// Successive over-relaxation: near the optimum 2 / (1 + sin(pi / N)) for decks N = 100 cells
// across (64 sweeps at 1.8 left the suite's overcast deck 18% darker than converged).
constexpr float kOverRelaxation = 1.93f;

constexpr int kRows = gpu::DIFFUSION_XY * gpu::DIFFUSION_Z * gpu::DIFFUSION_CASCADES;
constexpr size_t kFieldBytes = size_t(kRows) * gpu::DIFFUSION_XY * 4 * sizeof(float);
uint32_t rows() {
  return uint32_t(kRows);
}
}  // namespace

CloudDiffusionModule::CloudDiffusionModule(const ModuleContext& context)
    : ctx_(context.ctx),
      set_(context.set),
      fill_(context.ctx, context.set, "diffusion_fill.comp.spv", 0, {1, 1}),
      exchange_kernel_(context.ctx, context.set, "diffusion_exchange.comp.spv", 1, {}),
      inflow_kernel_(context.ctx, context.set, "diffusion_inflow.comp.spv", 1, {}),
      gather_kernel_(context.ctx, context.set, "diffusion_field.comp.spv", 1, {}),
      solve_(context.ctx, context.set, "diffusion_solve.comp.spv"),
      column_kernel_(context.ctx, context.set, "diffusion_column.comp.spv"),
      boundary_kernel_(context.ctx, context.set, "diffusion_boundary.comp.spv") {
  const auto volume = [&](VkFormat format) {
    return gpu::Texture(context.ctx, gpu::DIFFUSION_XY, gpu::DIFFUSION_XY,
                        gpu::DIFFUSION_Z * gpu::DIFFUSION_CASCADES, format,
                        VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  };
  medium_ = volume(VK_FORMAT_R32G32B32A32_SFLOAT);
  phi_ = volume(VK_FORMAT_R32G32B32A32_SFLOAT);  // (phi, D, sigma_a, source): diffusion_solve.comp
  inflow_ = volume(VK_FORMAT_R32_SFLOAT);
  boundary_ = volume(VK_FORMAT_R32_SFLOAT);  // diffusion_boundary.comp
  for (gpu::Texture& f : fields_) f = volume(VK_FORMAT_R32G32B32A32_SFLOAT);
  for (gpu::Texture& e : exchange_)  // diffusion_exchange_inc.glsl: two texels a cell
    e = gpu::Texture(context.ctx, 2 * gpu::DIFFUSION_XY, gpu::DIFFUSION_XY,
                     gpu::DIFFUSION_Z * gpu::DIFFUSION_CASCADES, VK_FORMAT_R32G32B32A32_SFLOAT,
                     VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  for (gpu::Buffer& b : blocks_) {
    b = gpu::Buffer(context.ctx, sizeof(gpu::CloudDiffusionGpu),
                    VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    std::memset(b.data(), 0, sizeof(gpu::CloudDiffusionGpu));  // not in use
  }
  // The march declares the block and the field whatever its lighting: always bound.
  set_.bind_module_buffer(kBlockName, blocks_[0], VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  set_.bind_module_sampled_image("cloud_diffusion_field", fields_[0]);
  set_.bind_module_storage_image("cloud_diffusion_field_out", fields_[1]);
  set_.bind_module_storage_image("cloud_diffusion_medium_out", medium_);
  set_.bind_module_storage_image("cloud_diffusion_medium", medium_);
  set_.bind_module_storage_image("cloud_diffusion_phi_out", phi_);
  set_.bind_module_storage_image("cloud_diffusion_phi", phi_);
  set_.bind_module_storage_image("cloud_diffusion_exchange_a", exchange_[0]);
  set_.bind_module_storage_image("cloud_diffusion_exchange_b", exchange_[1]);
  set_.bind_module_storage_image("cloud_diffusion_inflow", inflow_);
  set_.bind_module_storage_image("cloud_diffusion_boundary", boundary_);
}

void CloudDiffusionModule::prepare(const FramePrepare& frame, FramePlan& plan) {
  const gpu::FrameParams& params = frame.params;
  // Its source's transmittance and its rebuilds follow the light volume: without one
  // (quality.light_volume_km = 0), the clouds take the two-stream light.
  const bool on =
      frame.scene.clouds.lighting == "diffusion" && plan.volumetric && params.light_volume.w > 0.0f;
  fill_rows_ = sweeps_ = 0;
  gather_ = false;
  with_voxels_ = params.voxel_info.x > 0;
  with_flow_ = params.cloud_flow.x > 0.0f;
  if (!on) {
    have_field_ = building_ = false;
  } else {
    // A still, or nothing to read yet: the field built at once, else a part a frame.
    const bool at_once = frame.still || !have_field_;
    if (!have_field_ || plan.light_volume_built) {
      // A new build, centred where the light volume is (the camera, when it was built), in
      // cloud space; an animation's from the last build's fluence where the grid has not moved,
      // a still's from zero (so that it does not depend on what was rendered before).
      const float thickness_m = params.radii_m.w - params.radii_m.z;
      bool moved = at_once || !phi_kept_;
      phi_kept_ = true;
      float half_m = kHalfExtentM;
      for (int k = 0; k < gpu::DIFFUSION_CASCADES; ++k, half_m *= kCascadeScale) {
        const glm::vec4 grid(params.light_volume.x, params.light_volume.y, half_m, 0.0f);
        const glm::vec4 cell(2.0f * half_m / float(gpu::DIFFUSION_XY),
                             thickness_m / float(gpu::DIFFUSION_Z), kOverRelaxation, 0.0f);
        moved = moved || grid != build_grid_[k] || cell != cell_[k];
        build_grid_[k] = grid;
        cell_[k] = cell;
      }
      zero_phi_ = moved;
      if (moved) exchange_read_ = 0;
      sweeps_since_exchange_ = exchange_row_ = 0;
      building_ = true;
      next_row_ = 0;
      sweeps_left_ = at_once ? kDiffusionSweeps : kDiffusionAnimationSweeps;
      edit_ = plan.light_volume_edited;
      // A still's field from the disk cache, where an earlier process built it with the same
      // light volume; else kept there once built (finished). No file: no cache.
      const std::filesystem::path file =
          frame.still ? lighting_cache_file("diffusion", plan.lighting_cache_key)
                      : std::filesystem::path();
      store_file_.clear();
      if (load_cached_texture(ctx_, fields_[1 - read_], file, kFieldBytes)) {
        plan.cache_reads.push_back("cloud_diffusion read from " + file.string());
        building_ = false;
        read_ = 1 - read_;
        have_field_ = true;
        plan.ground_light = true;  // the clouds' light on the ground, from this field
        phi_kept_ = false;  // the fluence is not this field's: the next build starts at zero
        for (int k = 0; k < gpu::DIFFUSION_CASCADES; ++k)
          read_grid_[k] = glm::vec4(glm::vec3(build_grid_[k]), 1.0f);
      } else {
        store_file_ = file;
      }
    }
    if (building_) {
      at_once_ = at_once;
      if (next_row_ < kRows) {
        fill_first_ = next_row_;
        // After an edit of the clouds, as the light volume was, over kDiffusionEditFrames each.
        const int frames = edit_ ? kDiffusionEditFrames : kDiffusionFillFrames;
        fill_rows_ = at_once ? kRows - next_row_
                             : std::min((kRows + frames - 1) / frames, kRows - next_row_);
        next_row_ += fill_rows_;
      } else {
        const int per_frame =
            edit_ ? kDiffusionAnimationSweeps / kDiffusionEditFrames : kDiffusionFrameSweeps;
        sweeps_ = std::min(at_once ? sweeps_left_ : per_frame, sweeps_left_);
        sweeps_left_ -= sweeps_;
      }
      if (at_once && fill_rows_ > 0) {
        sweeps_ = sweeps_left_;
        sweeps_left_ = 0;
      }
      if (next_row_ >= kRows && sweeps_left_ == 0) {
        // Complete this frame: read after its field pass.
        gather_ = true;
        building_ = false;
        read_ = 1 - read_;
        have_field_ = true;
        plan.ground_light = true;  // the clouds' light on the ground, from this field
        for (int k = 0; k < gpu::DIFFUSION_CASCADES; ++k)
          read_grid_[k] = glm::vec4(glm::vec3(build_grid_[k]), 1.0f);
        if (!store_file_.empty()) store_slot_ = frame.slot;
        store_field_ = read_;
      }
    }
  }
  plan.building = plan.building || building_;
  plan.relit = plan.relit || (gather_ && edit_);
  gpu::CloudDiffusionGpu block{};
  if (on) {
    for (int k = 0; k < gpu::DIFFUSION_CASCADES; ++k) {
      block.grid[k] = read_grid_[k];
      block.build[k] = build_grid_[k];
      block.cell[k] = cell_[k];
    }
  }
  std::memcpy(blocks_[frame.slot].data(), &block, sizeof(block));
  set_.bind_module_buffer(kBlockName, blocks_[frame.slot], VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  set_.bind_module_sampled_image("cloud_diffusion_field", fields_[read_]);
  set_.bind_module_storage_image("cloud_diffusion_field_out", fields_[read_]);
}

void CloudDiffusionModule::finished(int slot) {
  if (slot != store_slot_) return;
  store_slot_ = -1;
  store_lighting_texture(ctx_, fields_[store_field_], store_file_, kFieldBytes);
}

void CloudDiffusionModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  if (fill_rows_ > 0)
    gpu::dispatch(
        cmd, fill_.get({with_voxels_ ? 1 : 0, with_flow_ ? 1 : 0}), timer, "diffusion_fill",
        gpu::DIFFUSION_XY, uint32_t(fill_rows_), 1, 8, 8, 1,
        gpu::DispatchConstants{glm::ivec4(fill_first_, fill_rows_, zero_phi_ ? 1 : 0, 0)});
  // The medium complete: a deck's open base, then the cells the gathers cast rays from.
  if (fill_rows_ > 0 && fill_first_ + fill_rows_ >= kRows) {
    gpu::dispatch(cmd, column_kernel_, timer, "diffusion_column", gpu::DIFFUSION_XY,
                  gpu::DIFFUSION_XY * gpu::DIFFUSION_CASCADES, 1, 8, 8, 1);
    gpu::dispatch(cmd, boundary_kernel_, timer, "diffusion_boundary", rows(), 1, 1, 64, 1, 1,
                  gpu::DispatchConstants{glm::ivec4(zero_phi_ ? 1 : 0, 0, 0, 0)});
  }
  // The clear air's light gathered over rows [first, first + count) into the set not read.
  const auto exchange = [&](int first, int count) {
    gpu::dispatch(cmd, exchange_kernel_.get({exchange_read_}), timer, "diffusion_exchange",
                  gpu::DIFFUSION_XY, uint32_t(count), 1, 8, 8, 1,
                  gpu::DispatchConstants{glm::ivec4(0, first, count, 0)});
    if (first + count >= kRows) {
      exchange_read_ = 1 - exchange_read_;
      sweeps_since_exchange_ = 0;
      gpu::dispatch(cmd, inflow_kernel_.get({exchange_read_}), timer, "diffusion_inflow",
                    gpu::DIFFUSION_XY, rows(), 1, 8, 8, 1);
    }
  };
  // Each sweep the red cells, then the black.
  const auto sweep = [&](int count) {
    gpu::dispatch_repeated(
        cmd, solve_, timer, "diffusion_solve", 2 * count,
        glm::uvec3(gpu::DIFFUSION_XY / 2, rows(), 1), glm::uvec3(8, 8, 1),
        [](int k) { return gpu::DispatchConstants{glm::ivec4(k & 1, 0, 0, 0)}; });
  };
  if (at_once_) {
    // A still's build: the gather whole every kDiffusionExchangeSweeps sweeps and before the
    // field.
    for (int done = 0; done < sweeps_;) {
      const int chunk = std::min(sweeps_ - done, kDiffusionExchangeSweeps - sweeps_since_exchange_);
      sweep(chunk);
      done += chunk;
      sweeps_since_exchange_ += chunk;
      if (sweeps_since_exchange_ >= kDiffusionExchangeSweeps) exchange(0, kRows);
    }
    if (gather_ && sweeps_since_exchange_ > 0) exchange(0, kRows);
  } else if (sweeps_ > 0) {
    // An animation's: a band of the gather with each sweep, one gather completed every
    // kDiffusionAnimationExchangeSweeps sweeps (the field reads the last completed).
    sweep(sweeps_);
    const int band =
        std::min(kRows / kDiffusionAnimationExchangeSweeps * sweeps_, kRows - exchange_row_);
    exchange(exchange_row_, band);
    exchange_row_ = (exchange_row_ + band) % kRows;
  }
  if (gather_)
    gpu::dispatch(cmd, gather_kernel_.get({exchange_read_}), timer, "diffusion_field",
                  gpu::DIFFUSION_XY, rows(), 1, 8, 8, 1);
}

void CloudDiffusionModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  graph.import("cloud_diffusion", true);  // kept until the light volume is rebuilt
  if (fill_rows_ == 0 && sweeps_ == 0 && !gather_) return;
  graph.add_pass("cloud_diffusion", {"weather_map", "noise", "voxel_clouds", "light_volume"},
                 {"cloud_diffusion"},
                 [timer = frame.timer, this](VkCommandBuffer cmd) { record(cmd, timer()); });
}

std::unique_ptr<RenderModule> make_cloud_diffusion_module(const ModuleContext& context) {
  return std::make_unique<CloudDiffusionModule>(context);
}

}  // namespace nephele

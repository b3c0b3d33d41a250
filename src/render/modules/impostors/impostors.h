// Impostors of far particle clouds (seed 003, 3.3.4-3.3.6; issue 22): a cloud far enough away
// is drawn once into an atlas, from the eye, framing its particles' angular extent, and then
// drawn as one quad with that image (impostor.vert, impostor.frag). It is drawn again when the
// direction to it turns by more than a threshold angle, its distance changes by more than a
// factor, or its lighting changes, at most a budget of clouds a frame; the image it replaces
// fades out over a few frames so that an update never pops. The atlas is managed by either of
// the seed's methods (particles/atlas.h): rectangles (best fit, rate-limited defragmentation,
// else a smaller image) or tiles with a one-texel border, cut from the image drawn into a
// scratch image by impostor_tiles.comp. The images' resolution follows the atlas's room: when
// an image does not fit, or little room is left, all images are asked smaller (down to a
// quarter of impostor_resolution), and larger again when the room comes back; an image more
// than 30% off the resolution asked is drawn again like a stale one, so that a full atlas never
// leaves far clouds drawn particle by particle for long.
#pragma once

#include <chrono>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <memory>
#include <optional>
#include <vector>

#include "gpu/kernel.h"
#include "gpu/raster.h"
#include "nephele/scene.h"
#include "particles/atlas.h"
#include "particles/particle_field.h"
#include "render/gpu_params.h"

namespace nephele {

struct ImpostorFrameStats {
  int impostors = 0;              // clouds drawn as impostors this frame
  int updates = 0;                // drawn into the atlas this frame
  int fading = 0;                 // cross-fading from an older image
  int waiting = 0;                // far clouds still drawn particle by particle (no image yet)
  float resolution_scale = 1.0f;  // of impostor_resolution, for the atlas's room
  particles::AtlasStats atlas;
};

class ImpostorCache {
 public:
  ImpostorCache(gpu::Context& ctx, gpu::DescriptorSet& set);
  ~ImpostorCache();

  // The frame's plan for `field` seen from the camera (cloud centres + `offset` are camera-
  // relative): which clouds are drawn particle by particle (`particle_clouds`) and which are
  // drawn into the atlas this frame (`updates`, their particles to be written by the caller);
  // then place_updates with where their particles are in the buffer. `reset`: the field was
  // regenerated (every image is stale). `image_height` and `tan_half_fov`: the image's, for the
  // impostors' resolution. `still`: every image is brought up to date, whatever the budget.
  struct Plan {
    std::vector<size_t> particle_clouds;
    std::vector<size_t> updates;
  };
  Plan plan(const particles::ParticleField& field, const ParticleCloudParams& params,
            const glm::vec3& offset, int image_height, float tan_half_fov, bool reset, bool still);
  // The updates' particles are at [first[i], first[i] + count[i]) of the particle buffer:
  // allocates their images, lays out this frame's quads and binds the buffers of `slot`.
  void place_updates(const particles::ParticleField& field, const std::vector<uint32_t>& first,
                     const std::vector<uint32_t>& count, int slot);
  // Before the particle layer's pass: moves the atlas's images where a defragmentation put
  // them, draws the updates, and (tiles) splits them into tiles.
  void record_updates(VkCommandBuffer cmd, gpu::PassTimer& timer);
  // The impostors' quads, to draw before the near particles (farther than all of them).
  gpu::RasterDraw quads(const gpu::DrawConstants& camera) const;
  uint32_t quad_count() const { return uint32_t(quads_.size()); }

  const ImpostorFrameStats& stats() const { return stats_; }

 private:
  struct Impostor;
  struct Update;
  void configure(const ParticleCloudParams& params);
  void release(Impostor& im);
  glm::vec4 image_of(uint32_t id, std::vector<int>& slots) const;
  // id's image of `size` texels in the atlas, or none; the texels served (smaller when the
  // atlas is short of room, which sets short_of_room).
  std::optional<glm::ivec2> allocate(uint32_t id, const glm::ivec2& size, double now_s,
                                     bool& short_of_room);
  void adapt_resolution(bool short_of_room, int shrinking);
  double room() const;                             // the atlas's share free to allocate
  double footprint(const glm::ivec2& size) const;  // the atlas texels an image of `size` takes

  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  std::unique_ptr<gpu::RasterPass> pass_;  // into the atlas (direct) or the scratch (tiles)
  gpu::Kernel tiles_kernel_;
  gpu::Texture atlas_, atlas_aux_, scratch_, scratch_aux_, move_temp_;
  gpu::Buffer quads_buffers_[gpu::kFramesInFlight], slots_buffers_[gpu::kFramesInFlight];
  gpu::Buffer jobs_buffers_[gpu::kFramesInFlight];
  glm::vec3 offset_{0.0f};      // this frame's: cloud centre + offset_ = from the camera
  ParticleCloudParams params_;  // the atlas's configuration
  bool configured_ = false;
  std::unique_ptr<particles::DirectAtlas> direct_;
  std::unique_ptr<particles::TileAtlas> tiles_;
  std::vector<Impostor> impostors_;
  float scale_ = 1.0f;  // the images' resolution, of impostor_resolution, for the atlas's room
  std::vector<Update> updates_;
  std::vector<particles::AtlasMove> moves_;  // this frame's, to copy
  std::vector<gpu::ImpostorGpu> quads_;
  std::vector<gpu::ImpostorTileJob> jobs_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  ImpostorFrameStats stats_;
};

}  // namespace nephele

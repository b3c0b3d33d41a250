#include "render/modules/impostors/impostors.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace nephele {

namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kAuxFormat = VK_FORMAT_R16_SFLOAT;  // particles.frag's depth output, unused here
constexpr int kScratchSide = 1024;           // tiles: this frame's images before the split
constexpr int kMinSide = 8, kMaxSide = 256;  // an impostor's image (texels a side)
// The images' resolution for the atlas's room (ImpostorCache::adapt_resolution): down by
// kScaleDown a frame while images do not fit or less than kLowRoom of the atlas is free, up by
// kScaleUp while more than kHighRoom is; an image drawn at a resolution kRescale off is stale.
constexpr float kMinScale = 0.25f, kScaleDown = 0.85f, kScaleUp = 1.02f;
constexpr double kLowRoom = 0.05, kHighRoom = 0.3;
constexpr float kRescale = 1.3f;

gpu::Texture texture(gpu::Context& ctx, int w, int h, VkFormat format) {
  return gpu::Texture(ctx, uint32_t(w), uint32_t(h), 1, format,
                      VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 1, true);
}

template <typename T>
void upload(gpu::Context& ctx, gpu::Buffer& buffer, const std::vector<T>& items) {
  const VkDeviceSize bytes = std::max<VkDeviceSize>(items.size(), 1) * sizeof(T);
  if (buffer.size() < bytes) {
    ctx.wait_queue_idle();  // the frame in flight may still read the old buffer
    buffer = gpu::Buffer(ctx, bytes + bytes / 2, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  }
  if (!items.empty()) std::memcpy(buffer.data(), items.data(), items.size() * sizeof(T));
}

// The view of one cloud from the eye: towards the middle of its particles' angular extent,
// with the tangents of that extent's half width and half height: the image holds the cloud
// and little else (a bounding sphere's square wasted three quarters of its texels on a flat
// cumulus seen from the side, and every one was drawn as a quad's fragment).
struct Framing {
  glm::vec3 forward, right, up;
  glm::vec2 tan_half;
};

glm::vec3 right_of(const glm::vec3& forward) {
  const glm::vec3 r = glm::cross(forward, glm::vec3(0.0f, 0.0f, 1.0f));
  return glm::length(r) > 1e-3f ? glm::normalize(r) : glm::vec3(1.0f, 0.0f, 0.0f);
}

Framing frame_cloud(const particles::ParticleCloud& cloud, const glm::vec3& offset) {
  const glm::vec3 centre = cloud.center_m + offset;
  glm::vec3 forward = glm::normalize(centre);
  for (int pass = 0; pass < 2; ++pass) {  // centre the view on the extent, then measure it
    const glm::vec3 right = right_of(forward), up = glm::cross(right, forward);
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (const particles::Particle& p : cloud.particles) {
      const glm::vec3 q = p.position_m + offset;
      // The particle's sphere seen from the eye: its centre's tangents, widened by its angular
      // radius (over the distance to its near side, so the bound holds for any size).
      const float z = std::max(glm::dot(q, forward) - p.radius_m, 1.0f);
      const glm::vec2 t(glm::dot(q, right), glm::dot(q, up));
      lo = glm::min(lo, (t - p.radius_m) / z);
      hi = glm::max(hi, (t + p.radius_m) / z);
    }
    const glm::vec2 middle = 0.5f * (lo + hi);
    if (pass == 0) {
      forward = glm::normalize(forward + middle.x * right + middle.y * up);
      continue;
    }
    // A margin for the second pass's small residual offset.
    const glm::vec2 half = 0.5f * (hi - lo) + glm::abs(middle);
    return {forward, right, up, glm::max(half * 1.02f, glm::vec2(1e-4f))};
  }
  return {};
}

}  // namespace

struct ImpostorCache::Impostor {
  bool has_image = false;
  uint32_t id = 0;      // its image's atlas id: cloud index x 2 + 0 or 1, alternating
  glm::vec3 dir{0.0f};  // from the eye towards the cloud when drawn
  float distance_m = 0.0f;
  uint32_t lightings = 0;  // the cloud's lightings then (ParticleCloud::lightings)
  float scale = 1.0f;      // the resolution scale then (ImpostorCache::scale_)
  // The quad: its centre from the cloud's, and its half sides (its image's right and up).
  glm::vec3 center_from_cloud{0.0f};
  glm::vec3 right{0.0f}, up{0.0f};
  bool fading = false;
  float fade = 1.0f;  // the new image's weight
  uint32_t old_id = 0;
};

struct ImpostorCache::Update {
  size_t cloud = 0;
  uint32_t id = 0;
  uint32_t first = 0, count = 0;  // its particles in the particle buffer
  gpu::DrawConstants view{};
  glm::ivec2 scratch{0};  // tiles: where it is drawn in the scratch image
  glm::ivec2 size{0};     // its image's texels
  int batch = 0;          // tiles: the scratch's batches are drawn and cut one after another
};

ImpostorCache::ImpostorCache(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx), set_(set), tiles_kernel_(ctx, set, "impostor_tiles.comp.spv") {
  // Until a scene has impostors: 1 x 1 images and one-element buffers, so every binding is set.
  atlas_ = texture(ctx, 1, 1, kColorFormat);
  scratch_ = texture(ctx, 1, 1, kColorFormat);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    atlas_.record_clear(cmd);
    scratch_.record_clear(cmd);
  });
  for (int s = 0; s < gpu::kFramesInFlight; ++s) {
    upload(ctx, quads_buffers_[s], std::vector<gpu::ImpostorGpu>(1));
    upload(ctx, slots_buffers_[s], std::vector<int>(1));
    upload(ctx, jobs_buffers_[s], std::vector<gpu::ImpostorTileJob>(1));
  }
  set_.bind_sampled_image(gpu::kImpostorAtlas, atlas_);
  set_.bind_storage_image(gpu::kImpostorAtlasOut, atlas_);
  set_.bind_sampled_image(gpu::kImpostorScratch, scratch_);
  set_.bind_buffer(gpu::kImpostors, quads_buffers_[0], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  set_.bind_buffer(gpu::kImpostorTileSlots, slots_buffers_[0], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  set_.bind_buffer(gpu::kImpostorTileJobs, jobs_buffers_[0], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
}

ImpostorCache::~ImpostorCache() = default;

void ImpostorCache::configure(const ParticleCloudParams& p) {
  const bool same =
      configured_ && p.impostors == params_.impostors && p.atlas_size == params_.atlas_size &&
      p.atlas_granule == params_.atlas_granule && p.atlas_defragment == params_.atlas_defragment &&
      p.atlas_defragmentations_per_s == params_.atlas_defragmentations_per_s &&
      p.atlas_tile == params_.atlas_tile;
  if (same) return;
  params_ = p;
  configured_ = true;
  scale_ = 1.0f;
  impostors_.clear();
  direct_.reset();
  tiles_.reset();
  if (p.impostors == "off") return;
  ctx_.wait_queue_idle();  // the frames in flight read the atlas replaced
  const int n = p.atlas_size;
  atlas_ = texture(ctx_, n, n, kColorFormat);
  if (p.impostors == "direct") {
    direct_ = std::make_unique<particles::DirectAtlas>(
        n, n,
        particles::DirectAtlas::Options{p.atlas_granule, p.atlas_defragment,
                                        p.atlas_defragmentations_per_s});
    atlas_aux_ = texture(ctx_, n, n, kAuxFormat);
  } else {
    tiles_ = std::make_unique<particles::TileAtlas>(
        n, n,
        particles::TileAtlas::Options{p.atlas_tile, p.atlas_defragment,
                                      p.atlas_defragmentations_per_s});
    scratch_ = texture(ctx_, kScratchSide, kScratchSide, kColorFormat);
    scratch_aux_ = texture(ctx_, kScratchSide, kScratchSide, kAuxFormat);
  }
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) { atlas_.record_clear(cmd); });
  set_.bind_sampled_image(gpu::kImpostorAtlas, atlas_);
  set_.bind_storage_image(gpu::kImpostorAtlasOut, atlas_);
  set_.bind_sampled_image(gpu::kImpostorScratch, scratch_);
  if (!pass_)
    pass_ = std::make_unique<gpu::RasterPass>(
        ctx_, set_, std::vector<VkFormat>{kColorFormat, kAuxFormat}, false,
        std::vector<gpu::RasterShaders>{{"particles.vert.spv", "particles.frag.spv"}});
}

void ImpostorCache::release(Impostor& im) {
  const auto free_id = [&](uint32_t id) {
    if (direct_) direct_->release(id);
    if (tiles_) tiles_->release(id);
  };
  if (im.has_image) free_id(im.id);
  if (im.fading) free_id(im.old_id);
  im = Impostor{};
}

ImpostorCache::Plan ImpostorCache::plan(const particles::ParticleField& field,
                                        const ParticleCloudParams& params, const glm::vec3& offset,
                                        int image_height, float tan_half_fov, bool reset,
                                        bool still) {
  configure(params);
  offset_ = offset;
  Plan plan;
  updates_.clear();
  moves_.clear();
  stats_ = {};
  if (reset || impostors_.size() != field.clouds.size()) {
    for (Impostor& im : impostors_) release(im);
    impostors_.assign(field.clouds.size(), Impostor{});
  }
  const bool on = direct_ || tiles_;
  const double now_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  // The cross-fades go on; an image faded out is freed.
  for (Impostor& im : impostors_) {
    if (!im.fading) continue;
    im.fade = std::min(1.0f, im.fade + 1.0f / float(params.impostor_fade_frames));
    if (im.fade >= 1.0f) {
      if (direct_) direct_->release(im.old_id);
      if (tiles_) tiles_->release(im.old_id);
      im.fading = false;
    }
  }
  // Which far clouds need an image: none yet first, then the stalest.
  struct Candidate {
    size_t cloud;
    float staleness;
  };
  std::vector<Candidate> candidates;
  const float cos_angle = std::cos(glm::radians(params.impostor_max_angle_deg));
  const bool cramped = on && room() < kLowRoom;
  std::vector<char> far_cloud(field.clouds.size(), 0);
  int shrinking = 0;  // images waiting to be drawn smaller
  for (size_t i = 0; i < field.clouds.size(); ++i) {
    const particles::ParticleCloud& cloud = field.clouds[i];
    Impostor& im = impostors_[i];
    const glm::vec3 rel = cloud.center_m + offset;
    const float d = glm::length(rel);
    const bool far = on && d > params.impostor_distance_m && d > 2.0f * cloud.bound_radius_m;
    if (!far) {
      release(im);
      plan.particle_clouds.push_back(i);
      continue;
    }
    far_cloud[i] = 1;
    if (!im.has_image) {
      plan.particle_clouds.push_back(i);  // until its image exists
      candidates.push_back({i, 1e9f});
      continue;
    }
    const float angle = std::acos(std::clamp(glm::dot(im.dir, rel / d), -1.0f, 1.0f));
    const float ratio = std::max(d / im.distance_m, im.distance_m / d);
    const float rescale = std::max(im.scale / scale_, scale_ / im.scale);
    const bool relit = im.lightings != cloud.lightings;
    // An image too large for the atlas's room now: drawing it smaller makes room, first of all
    // when the atlas is full, else after the clouds waiting for their first image.
    if (im.scale > kRescale * scale_) {
      candidates.push_back({i, cramped ? 2e9f : 5e8f});
      ++shrinking;
    } else if (glm::dot(im.dir, rel / d) < cos_angle || ratio > params.impostor_distance_factor ||
               rescale > kRescale || relit)
      candidates.push_back(
          {i, relit ? 1e6f
                    : angle / glm::radians(params.impostor_max_angle_deg) +
                          std::log(ratio) / std::log(params.impostor_distance_factor) +
                          std::log(rescale) / std::log(kRescale)});
  }
  std::stable_sort(
      candidates.begin(), candidates.end(),
      [](const Candidate& a, const Candidate& b) { return a.staleness > b.staleness; });
  if (!still && int(candidates.size()) > params.impostor_updates_per_frame)
    candidates.resize(size_t(params.impostor_updates_per_frame));
  // A still has nothing to cross-fade: the images it replaces make room at once (their clouds
  // drawn particle by particle should the new image not fit).
  if (still && on)
    for (const Candidate& c : candidates) {
      if (!impostors_[c.cloud].has_image) continue;
      release(impostors_[c.cloud]);
      plan.particle_clouds.push_back(c.cloud);
    }
  // Each chosen cloud's view and image size: the image's resolution on the screen (texels per
  // unit of tangent) times the option and the scale for the atlas's room, within
  // [kMinSide, kMaxSide] keeping its proportions.
  std::vector<Framing> framings;
  for (const Candidate& c : candidates)
    framings.push_back(frame_cloud(field.clouds[c.cloud], offset));
  std::vector<glm::ivec2> sizes;
  const auto size_images = [&] {
    const float texels =
        scale_ * params.impostor_resolution * float(image_height) / (2.0f * tan_half_fov);
    sizes.clear();
    double texels_held = 0.0;  // in the atlas, with its rounding and borders
    for (const Framing& framing : framings) {
      glm::ivec2 size(glm::round(2.0f * framing.tan_half * texels));
      const float shrink = std::min(1.0f, float(kMaxSide) / float(std::max(size.x, size.y)));
      sizes.push_back(glm::clamp(glm::ivec2(glm::vec2(size) * shrink), glm::ivec2(kMinSide),
                                 glm::ivec2(kMaxSide)));
      texels_held += footprint(sizes.back());
    }
    return texels_held;
  };
  double texels_held = size_images();
  // A still's images all at once: at a resolution whose images take at most 85% of the free
  // room (the sizes' bounds and rounding make the scale's effect uneven: a few tries).
  if (still && on) {
    const double texels_free =
        0.85 * room() * double(params.atlas_size) * double(params.atlas_size);
    for (int attempt = 0; attempt < 4 && texels_held > texels_free && scale_ > kMinScale;
         ++attempt) {
      scale_ = std::max(kMinScale, scale_ * float(std::sqrt(texels_free / texels_held)));
      texels_held = size_images();
    }
  }
  // The seed's step 1: an empty atlas (the first frame, or after a reset) is filled by
  // rectangle packing all at once; later images come one at a time by best fit.
  std::vector<bool> packed(candidates.size(), false);
  if (direct_ && direct_->regions().empty() && candidates.size() > 1) {
    std::vector<particles::DirectAtlas::Request> requests;
    for (size_t k = 0; k < candidates.size(); ++k)
      requests.push_back({uint32_t(2 * candidates[k].cloud), sizes[k].x, sizes[k].y});
    if (direct_->pack(requests)) packed.assign(candidates.size(), true);
  }
  glm::ivec2 shelf(0);  // tiles: this frame's images placed in rows in the scratch
  int shelf_height = 0, batch = 0;
  bool short_of_room = false;  // an image did not fit, or only smaller
  for (size_t k = 0; k < candidates.size(); ++k) {
    const Candidate& c = candidates[k];
    const particles::ParticleCloud& cloud = field.clouds[c.cloud];
    Impostor& im = impostors_[c.cloud];
    const glm::vec3 rel = cloud.center_m + offset;
    const Framing& framing = framings[k];
    const glm::ivec2 size = sizes[k];
    // The image's id: the other of the cloud's two, the current one being kept to fade out.
    if (im.fading) {
      if (direct_) direct_->release(im.old_id);
      if (tiles_) tiles_->release(im.old_id);
      im.fading = false;
    }
    uint32_t id = im.has_image ? (im.id ^ 1u) : uint32_t(2 * c.cloud);
    Update u{c.cloud, id, 0, 0, {}, glm::ivec2(0), size};
    if (direct_ && packed[k]) {
      const particles::AtlasRect r = direct_->regions().at(id);
      u.size = glm::ivec2(r.w, r.h);
    } else {
      if (tiles_ && shelf.x + size.x > kScratchSide)
        shelf = glm::ivec2(0, shelf.y + shelf_height), shelf_height = 0;
      if (tiles_ &&
          shelf.y + size.y > kScratchSide) {  // the scratch is full: the next batch reuses it
        shelf = glm::ivec2(0);
        shelf_height = 0;
        ++batch;
      }
      std::optional<glm::ivec2> served = allocate(id, size, now_s, short_of_room);
      if (!served && im.has_image) {
        // No room for both images: the new one replaces the old at once (no cross-fade), or
        // else the cloud goes back to its particles until there is room.
        release(im);
        plan.particle_clouds.push_back(c.cloud);
        id = u.id = uint32_t(2 * c.cloud);
        served = allocate(id, size, now_s, short_of_room);
      }
      if (!served) continue;
      u.size = *served;
      u.scratch = shelf;
      u.batch = batch;
      if (tiles_) {
        shelf.x += u.size.x;
        shelf_height = std::max(shelf_height, u.size.y);
      }
    }
    u.view.forward = glm::vec4(framing.forward, framing.tan_half.y);
    u.view.right = glm::vec4(framing.right, framing.tan_half.x / framing.tan_half.y);
    u.view.up = glm::vec4(framing.up, 0.0f);
    if (im.has_image) {
      im.fading = true;
      im.fade = 1.0f / float(params.impostor_fade_frames);
      im.old_id = im.id;
    } else {
      im.fade = 1.0f;
    }
    // The quad: in the plane through the cloud's centre facing the view, where the image's
    // frustum cuts it; kept relative to the cloud's centre, which drifts with the wind.
    const float depth_m = glm::dot(rel, framing.forward);
    im.has_image = true;
    im.id = id;
    im.dir = rel / glm::length(rel);
    im.distance_m = glm::length(rel);
    im.lightings = cloud.lightings;
    im.scale = scale_;
    im.right = framing.right * depth_m * framing.tan_half.x;
    im.up = framing.up * depth_m * framing.tan_half.y;
    im.center_from_cloud = framing.forward * depth_m - rel;
    updates_.push_back(u);
    plan.updates.push_back(c.cloud);
  }
  // A cloud whose first image is drawn this frame is an impostor already; the far ones left
  // wait for theirs.
  std::vector<size_t> kept;
  for (size_t i : plan.particle_clouds)
    if (!impostors_[i].has_image) {
      kept.push_back(i);
      stats_.waiting += far_cloud[i];
    }
  plan.particle_clouds = std::move(kept);
  if (on) adapt_resolution(short_of_room, shrinking);
  return plan;
}

double ImpostorCache::footprint(const glm::ivec2& size) const {
  if (!direct_ && !tiles_) return 0.0;
  const auto whole = [](int texels, int unit) { return double((texels + unit - 1) / unit * unit); };
  if (direct_) return whole(size.x, direct_->granule()) * whole(size.y, direct_->granule());
  const int inner = tiles_->interior(), tile = tiles_->tile();
  return whole(size.x, inner) / inner * tile * (whole(size.y, inner) / inner * tile);
}

std::optional<glm::ivec2> ImpostorCache::allocate(uint32_t id, const glm::ivec2& size, double now_s,
                                                  bool& short_of_room) {
  if (direct_) {
    const particles::DirectAtlas::Result res = direct_->allocate(id, size.x, size.y, now_s);
    short_of_room |= !res.ok || res.downsized;
    if (!res.ok) return std::nullopt;
    if (res.defragmented) moves_ = direct_->last_moves();
    return glm::ivec2(res.rect.w, res.rect.h);
  }
  const particles::TileAtlas::Result res = tiles_->allocate(id, size.x, size.y, now_s);
  short_of_room |= !res.ok || res.downsized;
  if (!res.ok) return std::nullopt;
  if (res.defragmented) moves_ = tiles_->last_moves();
  return glm::ivec2(res.placement.width, res.placement.height);
}

double ImpostorCache::room() const {
  return direct_ ? direct_->free_share() : tiles_ ? tiles_->free_share() : 0.0;
}

// Smaller while images do not fit or the room runs low, unless images are still waiting to be
// drawn at the last scale (the room they free is on its way: going on would overshoot).
void ImpostorCache::adapt_resolution(bool short_of_room, int shrinking) {
  const double free = room();
  if ((short_of_room || free < kLowRoom) && shrinking == 0)
    scale_ = std::max(kMinScale, scale_ * kScaleDown);
  else if (free > kHighRoom)
    scale_ = std::min(1.0f, scale_ * kScaleUp);
  stats_.resolution_scale = scale_;
}

glm::vec4 ImpostorCache::image_of(uint32_t id, std::vector<int>& slots) const {
  if (direct_) {
    const particles::AtlasRect r = direct_->regions().at(id);
    return glm::vec4(r.x, r.y, r.x + r.w, r.y + r.h);
  }
  const particles::TileAtlas::Placement& p = tiles_->placements().at(id);
  const int first = int(slots.size());
  slots.insert(slots.end(), p.slots.begin(), p.slots.end());
  return glm::vec4(float(first), float(p.tiles_x), float(p.width), float(p.height));
}

void ImpostorCache::place_updates(const particles::ParticleField& field,
                                  const std::vector<uint32_t>& first,
                                  const std::vector<uint32_t>& count, int slot) {
  for (size_t k = 0; k < updates_.size(); ++k)
    updates_[k].first = first[k], updates_[k].count = count[k];
  quads_.clear();
  jobs_.clear();
  std::vector<int> slots;
  // This frame's quads, back to front by their distance now (the layer's pass draws them
  // before the near particles, all nearer than they).
  std::vector<std::pair<float, size_t>> order;
  for (size_t i = 0; i < impostors_.size(); ++i)
    if (impostors_[i].has_image)
      order.push_back({glm::length(field.clouds[i].center_m + offset_), i});
  std::sort(order.begin(), order.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  const int mode = tiles_ ? gpu::IMPOSTOR_TILES : gpu::IMPOSTOR_DIRECT;
  for (const auto& [distance_m, i] : order) {
    const Impostor& im = impostors_[i];
    gpu::ImpostorGpu q{};
    q.center_half = glm::vec4(field.clouds[i].center_m + offset_ + im.center_from_cloud, 1.0f);
    q.right = glm::vec4(im.right, im.fading ? im.fade : 1.0f);
    q.up = glm::vec4(im.up, distance_m * 1e-3f);
    q.image_new = image_of(im.id, slots);
    q.image_old = im.fading ? image_of(im.old_id, slots) : q.image_new;
    q.info = glm::ivec4(mode, params_.atlas_tile, 0, 0);
    quads_.push_back(q);
  }
  // Tiles: each image drawn this frame is cut into its tiles.
  for (const Update& u : updates_) {
    if (!tiles_) break;
    const particles::TileAtlas::Placement& p = tiles_->placements().at(u.id);
    for (size_t t = 0; t < p.slots.size(); ++t)
      jobs_.push_back(
          {glm::ivec4(p.slots[t], int(t) % p.tiles_x, int(t) / p.tiles_x, params_.atlas_tile),
           glm::ivec4(u.scratch, p.width, p.height)});
  }
  stats_.impostors = int(quads_.size());
  stats_.updates = int(updates_.size());
  for (const Impostor& im : impostors_) stats_.fading += im.fading ? 1 : 0;
  if (direct_) stats_.atlas = direct_->stats();
  if (tiles_) stats_.atlas = tiles_->stats();
  upload(ctx_, quads_buffers_[slot], quads_);
  upload(ctx_, slots_buffers_[slot], slots);
  upload(ctx_, jobs_buffers_[slot], jobs_);
  set_.bind_buffer(gpu::kImpostors, quads_buffers_[slot], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  set_.bind_buffer(gpu::kImpostorTileSlots, slots_buffers_[slot],
                   VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  set_.bind_buffer(gpu::kImpostorTileJobs, jobs_buffers_[slot], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
}

void ImpostorCache::record_updates(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  if (!moves_.empty()) {
    // A defragmentation moved images: the atlas copied aside, then each image from its old
    // place to its new one (the two may overlap).
    if (move_temp_.width() != atlas_.width())
      move_temp_ = texture(ctx_, int(atlas_.width()), int(atlas_.height()), kColorFormat);
    timer.begin(cmd, "impostor_moves");
    VkImageCopy whole{};
    whole.srcSubresource = whole.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    whole.extent = {atlas_.width(), atlas_.height(), 1};
    vkCmdCopyImage(cmd, atlas_.image(), VK_IMAGE_LAYOUT_GENERAL, move_temp_.image(),
                   VK_IMAGE_LAYOUT_GENERAL, 1, &whole);
    gpu::full_barrier(cmd);
    std::vector<VkImageCopy> copies;
    for (const particles::AtlasMove& m : moves_) {
      VkImageCopy c{};
      c.srcSubresource = c.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      c.srcOffset = {m.from.x, m.from.y, 0};
      c.dstOffset = {m.to.x, m.to.y, 0};
      c.extent = {uint32_t(std::min(m.from.w, m.to.w)), uint32_t(std::min(m.from.h, m.to.h)), 1};
      copies.push_back(c);
    }
    vkCmdCopyImage(cmd, move_temp_.image(), VK_IMAGE_LAYOUT_GENERAL, atlas_.image(),
                   VK_IMAGE_LAYOUT_GENERAL, uint32_t(copies.size()), copies.data());
    gpu::full_barrier(cmd);
    timer.end(cmd);
  }
  if (updates_.empty()) return;
  // Each image drawn from the eye with its own view, into its rectangle of the atlas (direct)
  // or of the scratch image (tiles: a batch at a time, each cut into tiles before the next).
  size_t job = 0;
  for (size_t k = 0; k < updates_.size();) {
    const int batch = updates_[k].batch;
    std::vector<gpu::RasterDraw> draws;
    size_t jobs = 0;
    for (; k < updates_.size() && updates_[k].batch == batch; ++k) {
      const Update& u = updates_[k];
      gpu::RasterDraw d;
      d.first_vertex = 6 * u.first;
      d.vertex_count = 6 * u.count;
      d.constants = u.view;
      glm::ivec2 corner = u.scratch;
      if (direct_) {
        const particles::AtlasRect r = direct_->regions().at(u.id);
        corner = glm::ivec2(r.x, r.y);
      } else {
        jobs += tiles_->placements().at(u.id).slots.size();
      }
      d.area = {{corner.x, corner.y}, {uint32_t(u.size.x), uint32_t(u.size.y)}};
      d.clear_area = true;
      draws.push_back(d);
    }
    if (direct_) {
      pass_->record(cmd, timer, "impostor_draw",
                    {atlas_.render_target(), atlas_aux_.render_target()}, draws);
      continue;
    }
    pass_->record(cmd, timer, "impostor_draw",
                  {scratch_.render_target(), scratch_aux_.render_target()}, draws);
    gpu::DrawConstants first{};
    first.info.x = int(job);  // impostor_tiles.comp's first job
    vkCmdPushConstants(cmd, tiles_kernel_.interface().pipeline_layout(), gpu::kDrawConstantStages,
                       0, sizeof(gpu::DrawConstants), &first);
    const int tile = params_.atlas_tile;
    gpu::dispatch(cmd, tiles_kernel_, timer, "impostor_tiles", uint32_t(tile), uint32_t(tile),
                  uint32_t(jobs), 8, 8, 1);
    job += jobs;
  }
}

gpu::RasterDraw ImpostorCache::quads(const gpu::DrawConstants& camera) const {
  gpu::RasterDraw d;
  d.pipeline = tiles_ ? 2 : 1;  // the layer pass's impostor pipelines (particle_clouds.cpp)
  d.vertex_count = 6 * uint32_t(quads_.size());
  d.constants = camera;
  d.constants.info.x = 0;
  return d;
}

}  // namespace nephele

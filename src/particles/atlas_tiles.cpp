// TileAtlas (seed 003, 3.3.6). Tiles are all alike, so any free tile serves any impostor and
// the atlas never runs out of room through fragmentation; what fragments is the impostors'
// locality: after many updates an impostor's tiles lie scattered over the atlas. Allocation
// therefore prefers one run of consecutive slots (best fit: the shortest run long enough) and
// the optional defragmentation compacts all impostors into runs. Every operation is a constant
// number of passes over the slots (4096 of 32 texels in a 2048-texel atlas).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "particles/atlas.h"

namespace nephele::particles {

namespace {

using atlas_detail::require_positive;
using Clock = atlas_detail::OpLog::Clock;

bool one_run(const std::vector<int>& slots) {
  for (size_t k = 1; k < slots.size(); ++k)
    if (slots[k] != slots[k - 1] + 1) return false;
  return true;
}

int min_slot(const std::vector<int>& slots) {
  return slots.empty() ? 0 : *std::min_element(slots.begin(), slots.end());
}

struct Run {
  int start, length;
};

// The runs of consecutive free slots, in slot order.
std::vector<Run> free_runs(const std::vector<uint8_t>& used) {
  std::vector<Run> runs;
  const int n = int(used.size());
  for (int s = 0; s < n;) {
    if (used[size_t(s)]) {
      ++s;
      continue;
    }
    int end = s;
    while (end < n && !used[size_t(end)]) ++end;
    runs.push_back({s, end - s});
    s = end;
  }
  return runs;
}

}  // namespace

TileAtlas::TileAtlas(int width, int height, Options options)
    : width_(width),
      height_(height),
      options_(options),
      limiter_(options.max_defragmentations_per_s) {
  require_positive("TileAtlas width", width);
  require_positive("TileAtlas height", height);
  if (options.tile != 16 && options.tile != 32)
    throw std::invalid_argument("TileAtlas tile = " + std::to_string(options.tile) +
                                ": must be 16 or 32");
  if (options.tile > std::min(width, height))
    throw std::invalid_argument("TileAtlas tile = " + std::to_string(options.tile) +
                                ": must not exceed the atlas's smaller side " +
                                std::to_string(std::min(width, height)));
  atlas_detail::require_rate("TileAtlas", options.defragment, options.max_defragmentations_per_s);
  slots_x_ = width / options.tile;
  slots_y_ = height / options.tile;
  used_.assign(size_t(slot_count()), 0);
  free_tiles_ = slot_count();
}

AtlasRect TileAtlas::slot_rect(int slot) const {
  const int t = options_.tile;
  return {(slot % slots_x_) * t, (slot / slots_x_) * t, t, t};
}

void TileAtlas::free_placement(uint32_t id, long long& work) {
  const auto it = placements_.find(id);
  if (it == placements_.end()) return;
  for (int slot : it->second.slots) used_[size_t(slot)] = 0;
  free_tiles_ += int(it->second.slots.size());
  work += (long long)it->second.slots.size();
  placements_.erase(it);
}

// The largest served size with the asked proportions whose tiles number at most `tiles`. The
// tile counts only step up where a side reaches a whole number of tile interiors, so the best
// size has one side at such a multiple: try them all on both sides.
bool TileAtlas::fit_proportional(int width, int height, int tiles, int& served_w,
                                 int& served_h) const {
  const long long inner = interior();
  long long best_area = 0;
  const auto consider = [&](long long w, long long h) {
    if (w < 1 || h < 1 || (long long)tiles_for(int(w)) * tiles_for(int(h)) > tiles) return;
    if (w * h <= best_area) return;
    best_area = w * h;
    served_w = int(w);
    served_h = int(h);
  };
  // A side of k tiles needs k tiles at least: no more candidates than free tiles.
  for (int across = 1; across <= std::min(tiles_for(width), tiles); ++across) {
    const long long w = std::min<long long>(width, across * inner);
    consider(w, w * height / width);
  }
  for (int down = 1; down <= std::min(tiles_for(height), tiles); ++down) {
    const long long h = std::min<long long>(height, down * inner);
    consider(h * width / height, h);
  }
  return best_area > 0;
}

int TileAtlas::shortest_run(int count, long long& work) const {
  int best_start = -1, best_length = 0;
  for (const Run& run : free_runs(used_)) {
    if (run.length >= count && (best_start < 0 || run.length < best_length)) {
      best_start = run.start;
      best_length = run.length;
    }
  }
  work += slot_count();
  return best_start;
}

// No run is long enough: the tiles come from the shortest runs first, which fills the small
// holes and keeps the long runs for impostors that can still have one. A counting sort keeps it
// linear in the slots.
std::vector<int> TileAtlas::gather(int count, long long& work) const {
  const int n = slot_count();
  const std::vector<Run> runs = free_runs(used_);
  std::vector<int> first_of_length(size_t(n) + 2, 0);
  for (const Run& run : runs) ++first_of_length[size_t(run.length) + 1];
  for (size_t l = 1; l < first_of_length.size(); ++l) first_of_length[l] += first_of_length[l - 1];
  std::vector<Run> by_length(runs.size());
  for (const Run& run : runs) by_length[size_t(first_of_length[size_t(run.length)]++)] = run;
  std::vector<int> slots;
  slots.reserve(size_t(count));
  for (const Run& run : by_length) {
    for (int k = 0; k < run.length && int(slots.size()) < count; ++k)
      slots.push_back(run.start + k);
    if (int(slots.size()) == count) break;
  }
  std::sort(slots.begin(), slots.end());  // the impostor's tiles in slot order: nearer together
  work += 3LL * n + count;
  return slots;
}

// Defragmentation: every impostor's tiles become one run, the impostors in the order of their
// first slots (so that most move little), the one being allocated last. Tiles that end up in
// their old slot are not moved.
void TileAtlas::compact(uint32_t id, const Placement& placement, long long& work) {
  std::vector<std::pair<int, uint32_t>> order;  // (first slot, id)
  order.reserve(placements_.size());
  for (const auto& [other, p] : placements_) order.push_back({min_slot(p.slots), other});
  std::sort(order.begin(), order.end());
  placements_[id] = placement;
  order.push_back({slot_count(), id});

  moves_.clear();
  int next = 0;
  for (const auto& [first, other] : order) {
    Placement& p = placements_[other];
    const int count = p.tiles_x * p.tiles_y;
    for (int k = 0; k < count; ++k) {
      if (other != id && p.slots[size_t(k)] != next + k)
        moves_.push_back({other, slot_rect(p.slots[size_t(k)]), slot_rect(next + k)});
    }
    p.slots.resize(size_t(count));
    for (int k = 0; k < count; ++k) p.slots[size_t(k)] = next + k;
    next += count;
  }
  std::fill(used_.begin(), used_.end(), 0);
  std::fill_n(used_.begin(), next, 1);
  free_tiles_ = slot_count() - next;
  work += (long long)slot_count() + next + (long long)order.size();
}

TileAtlas::Result TileAtlas::allocate(uint32_t id, int width, int height, double now_s) {
  require_positive("TileAtlas::allocate width", width);
  require_positive("TileAtlas::allocate height", height);
  log_.observe(now_s);
  const Clock::time_point start = Clock::now();
  long long work = 0;
  free_placement(id, work);

  Result result;
  Placement p;
  p.width = width;
  p.height = height;
  if ((long long)tiles_for(width) * tiles_for(height) > free_tiles_) {
    if (!fit_proportional(width, height, free_tiles_, p.width, p.height)) {
      ++failed_;
      log_.record(start, work, false);
      return result;
    }
    result.downsized = true;
    ++downsized_;
  }
  p.tiles_x = tiles_for(p.width);
  p.tiles_y = tiles_for(p.height);
  const int count = p.tiles_x * p.tiles_y;

  const int run = shortest_run(count, work);
  if (run < 0 && options_.defragment && limiter_.allows(now_s)) {
    limiter_.record(now_s);
    ++defragmentations_;
    compact(id, p, work);
    result.defragmented = true;
  } else {
    if (run >= 0) {
      for (int k = 0; k < count; ++k) p.slots.push_back(run + k);
    } else {
      p.slots = gather(count, work);
    }
    for (int slot : p.slots) used_[size_t(slot)] = 1;
    free_tiles_ -= count;
    work += count;
    placements_[id] = p;
  }
  result.ok = true;
  result.placement = placements_.at(id);
  log_.record(start, work, result.defragmented);
  return result;
}

void TileAtlas::release(uint32_t id) {
  const Clock::time_point start = Clock::now();
  long long work = 0;
  free_placement(id, work);
  log_.record(start, work, false);
}

// The tile holding (u, v) (on a shared edge, either: both hold the texels on each side), then
// the offset inside its interior, which starts one texel in from the tile's corner.
std::pair<float, float> TileAtlas::atlas_texel(const Placement& placement, float u, float v) const {
  const float inner = float(interior());
  u = std::fmin(std::fmax(u, 0.0f), float(placement.width));  // NaN and strays: to the image
  v = std::fmin(std::fmax(v, 0.0f), float(placement.height));
  const int column = std::min(int(u / inner), placement.tiles_x - 1);
  const int row = std::min(int(v / inner), placement.tiles_y - 1);
  const AtlasRect slot = slot_rect(placement.slots.at(size_t(row * placement.tiles_x + column)));
  const float local_u = std::clamp(u - float(column) * inner, 0.0f, inner);
  const float local_v = std::clamp(v - float(row) * inner, 0.0f, inner);
  return {float(slot.x) + 1.0f + local_u, float(slot.y) + 1.0f + local_v};
}

AtlasStats TileAtlas::stats() const {
  AtlasStats s;
  const long long atlas = (long long)width_ * height_;
  const long long tile_texels = (long long)options_.tile * options_.tile;
  long long held = 0, tiles = 0;
  int scattered = 0;
  for (const auto& [id, p] : placements_) {
    held += (long long)p.width * p.height;
    tiles += (long long)p.slots.size();
    scattered += !one_run(p.slots);
  }
  s.occupancy = double(held) / double(atlas);
  s.wasted = double(tiles * tile_texels - held) / double(atlas);
  s.free = double((long long)free_tiles_ * tile_texels) / double(atlas);
  s.unusable = double(atlas - (long long)slot_count() * tile_texels) / double(atlas);
  s.fragmentation = placements_.empty() ? 0.0 : double(scattered) / double(placements_.size());
  s.defragmentations = defragmentations_;
  s.downsized = downsized_;
  s.failed = failed_;
  log_.fill(s);
  return s;
}

}  // namespace nephele::particles

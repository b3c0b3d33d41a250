// The impostor atlas (seed 003, 3.3.5-3.3.6): far clouds are drawn as impostors, pre-rendered
// images kept in one big atlas texture. Their sizes change with every update, so the atlas is a
// memory manager, not a one-off packing. Two managers:
//   DirectAtlas (3.3.5): each impostor is one axis-aligned rectangle. Sizes are rounded up to a
//     granule (16 texels) and the atlas is a grid of granule cells; an update frees the old
//     rectangle and takes the best-fitting free one; when none fits, a rate-limited
//     defragmentation repacks everything; failing that, the impostor is stored smaller.
//   TileAtlas (3.3.6): each impostor is cut into square tiles (16 or 32 texels) with a
//     one-texel border for bilinear filtering; tiles pack without loss, so only their scatter
//     over the atlas needs a (rate-limited) defragmentation.
// Both report the texel moves of a defragmentation so that the renderer can copy the texels, and
// statistics (occupancy, waste, fragmentation, time and work per operation). Neither is
// thread-safe; both are copyable (a copy is an independent atlas, used by tests for what-ifs).
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace nephele::particles {

// A rectangle of atlas texels: [x, x + w) x [y, y + h).
struct AtlasRect {
  int x = 0, y = 0, w = 0, h = 0;
  bool operator==(const AtlasRect&) const = default;
};

// Texels to copy after a defragmentation. `from` is in the atlas as it was before the
// defragmentation, `to` as it is after; sources and destinations of different moves may
// overlap, so the renderer gathers all of them from a snapshot (or a second atlas texture)
// rather than copying them one after another in place. Tiles: one move per tile.
struct AtlasMove {
  uint32_t id = 0;
  AtlasRect from, to;
};

// All shares are of the atlas's texels: occupancy + wasted + free + unusable = 1.
struct AtlasStats {
  double occupancy = 0.0;  // texels holding impostors' own texels
  double wasted = 0.0;     // allocated but not holding impostor texels (granule or tile
                           // rounding, tile borders)
  double free = 0.0;       // not allocated and allocatable
  double unusable = 0.0;   // the strip past the last whole granule or tile of a row or column
  // Direct: 1 - largest free rectangle / free area (0 when the free space is one rectangle or
  // there is none). Tiles: the share of impostors whose tiles are not one run of consecutive
  // slots in row-major slot order (0 with no impostors).
  double fragmentation = 0.0;
  int defragmentations = 0;                  // calls, successful or not (each costs the same time)
  int failed_defragmentations = 0;           // calls after which everything still did not fit
  double defragmentations_per_s = 0.0;       // calls / the time between the first and last allocate
  int downsized = 0;                         // allocations served smaller than asked
  int failed = 0;                            // allocations not served at all
  long long operations = 0;                  // allocate and release calls
  double mean_op_us = 0.0, max_op_us = 0.0;  // wall time per operation (steady_clock), all ops
  // Elementary steps (grid cells, tile slots or free rectangles examined) of the costliest
  // operation that did not defragment: deterministic, unlike the wall time. The rate-limited
  // defragmentations are reported apart.
  long long max_op_work = 0;
  long long max_defrag_work = 0;
  double max_defrag_us = 0.0;
};

namespace atlas_detail {

// Defragmentations at most once per 1 / per_s seconds of the caller's clock: then any half-open
// window of 1 s holds at most ceil(per_s) of them, and a defragmentation's hitch is never
// repeated on the next frames as a burst allowance would permit.
class RateLimiter {
 public:
  explicit RateLimiter(double per_s) : min_interval_s_(1.0 / per_s) {}
  bool allows(double now_s) const { return !any_ || now_s - last_s_ >= min_interval_s_; }
  void record(double now_s) {
    any_ = true;
    last_s_ = now_s;
  }

 private:
  double min_interval_s_;
  bool any_ = false;
  double last_s_ = 0.0;
};

// The per-operation time and work, and the span of the caller's clock, behind AtlasStats.
class OpLog {
 public:
  // Throws std::invalid_argument when now_s is not finite or is earlier than the last one.
  void observe(double now_s);
  using Clock = std::chrono::steady_clock;
  // One operation begun at `start`: its wall time runs until now.
  void record(Clock::time_point start, long long work, bool defragmented);
  void fill(AtlasStats& stats) const;  // the operation and time fields; defragmentations set

 private:
  long long operations_ = 0;
  double total_us_ = 0.0, max_us_ = 0.0, max_defrag_us_ = 0.0;
  long long max_work_ = 0, max_defrag_work_ = 0;
  bool any_time_ = false;
  double first_s_ = 0.0, last_s_ = 0.0;
};

// std::invalid_argument naming `what`, its value and what is allowed.
void require_positive(const char* what, int value);
void require_rate(const char* what, bool defragment, double per_s);

}  // namespace atlas_detail

// Method A: impostors as rectangles on a grid of granule cells. Every search but the
// defragmentation is a constant number of passes over the grid, so an operation's work is
// linear in the atlas's cells whatever the number of impostors.
class DirectAtlas {
 public:
  struct Options {
    int granule = 16;  // texels; sizes and positions are whole granules
    bool defragment = true;
    double max_defragmentations_per_s = 2.0;
  };
  struct Request {
    uint32_t id = 0;
    int width = 0, height = 0;  // texels
  };
  struct Result {
    bool ok = false;
    AtlasRect rect;  // as regions() holds it
    bool downsized = false;
    bool defragmented = false;  // last_moves() lists the texels to copy
  };

  // width, height: the atlas's texels (a strip narrower than a granule at the right or bottom is
  // left unused). Throws std::invalid_argument on a non-positive size, a granule < 1 or larger
  // than the atlas, or a non-positive rate of defragmentations while defragmenting.
  DirectAtlas(int width, int height, Options options);

  // Step 1, into an empty atlas: packs all requests (MaxRects) and returns true, or returns
  // false and places none. Throws std::logic_error when the atlas is not empty and
  // std::invalid_argument on a non-positive size or a repeated id.
  bool pack(const std::vector<Request>& requests);

  // Steps 2-4 at now_s (seconds, non-decreasing): frees id's area if it has one; then takes the
  // best-fitting free area; else, when enabled, allowed by the rate limit and the free area is
  // large enough in total, repacks all impostors (id at its new size) and moves them; else
  // serves the largest free area with the asked proportions (downsized, at least one texel a
  // side); else fails (ok = false, id holds nothing). Throws std::invalid_argument on a
  // non-positive size or a time earlier than the last one.
  Result allocate(uint32_t id, int width, int height, double now_s);
  void release(uint32_t id);  // no-op for an id that holds nothing

  // The texels each id's impostor is drawn into: at a granule-aligned corner, the served size
  // (the asked one, or the downsized one). Its granule-rounded allocation is allocation(rect).
  const std::map<uint32_t, AtlasRect>& regions() const { return regions_; }
  AtlasRect allocation(const AtlasRect& region) const;
  // The moves of the last successful defragmentation; the impostor being allocated then is not
  // among them (it is rendered anew), nor are impostors that stayed in place.
  const std::vector<AtlasMove>& last_moves() const { return moves_; }
  AtlasStats stats() const;

  // Whether a width x height texel request fits somewhere in the free space as it is now (a
  // check independent of the best-fit search, for tests and callers planning ahead).
  bool can_fit(int width, int height) const;
  // The share of the atlas's texels free to allocate (AtlasStats::free, without the rest).
  double free_share() const {
    return double((long long)used_.size() - used_cells_) * options_.granule * options_.granule /
           (double(width_) * double(height_));
  }
  int granule() const { return options_.granule; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  struct CellRect {
    int x = 0, y = 0, w = 0, h = 0;
  };

  // Whole granules covering `texels` > 0, written so that INT_MAX cannot overflow.
  int cells_of(int texels) const { return (texels - 1) / options_.granule + 1; }
  CellRect cells_of(const AtlasRect& region) const;
  void fill_cells(const CellRect& cells, uint8_t value, long long& work);
  void free_region(uint32_t id, long long& work);
  void place(uint32_t id, const AtlasRect& region, long long& work);
  bool best_fit(int cells_w, int cells_h, CellRect& found, long long& work);
  bool largest_proportional(int width, int height, AtlasRect& found, long long& work) const;
  bool defragment(uint32_t id, int width, int height, long long& work);

  int width_, height_;
  Options options_;
  int cells_x_, cells_y_;      // whole granules across and down
  std::vector<uint8_t> used_;  // cells_x_ * cells_y_, row-major: 1 where allocated
  long long used_cells_ = 0;
  std::map<uint32_t, AtlasRect> regions_;
  std::vector<AtlasMove> moves_;
  std::vector<int> scratch_;  // the best-fit search's run lengths and window minima
  atlas_detail::RateLimiter limiter_;
  atlas_detail::OpLog log_;
  int defragmentations_ = 0, failed_defragmentations_ = 0, downsized_ = 0, failed_ = 0;
};

// Method B: impostors as square tiles of `tile` texels, each holding (tile - 2) x (tile - 2) of
// the impostor's texels inside a one-texel border that repeats the neighbouring tile's edge
// texels (at the impostor's own edges, and past its last texel in a partly used tile, the edge
// texel itself), so that bilinear filtering inside a tile reads what it would read in the
// whole image. Tile k of an impostor (column k % tiles_x, row k / tiles_x) shows its texels
// [c (tile - 2) - 1, (c + 1) (tile - 2) + 1) x [r (tile - 2) - 1, (r + 1) (tile - 2) + 1).
class TileAtlas {
 public:
  struct Options {
    int tile = 32;  // 16 or 32 texels
    bool defragment = false;
    double max_defragmentations_per_s = 1.0;
  };
  struct Placement {
    int tiles_x = 0, tiles_y = 0;
    int width = 0, height = 0;  // the texels served
    // Row-major over the tiles_x x tiles_y tiles; slot s is the atlas texel square at
    // ((s % slots_per_row) tile, (s / slots_per_row) tile).
    std::vector<int> slots;
  };
  struct Result {
    bool ok = false;
    Placement placement;
    bool downsized = false;
    bool defragmented = false;
  };

  // Throws std::invalid_argument on a non-positive atlas size, a tile other than 16 or 32 or
  // larger than the atlas, or a non-positive rate of defragmentations while defragmenting.
  TileAtlas(int width, int height, Options options);

  // At now_s (seconds, non-decreasing): frees id's tiles, then takes
  // ceil(width / (tile - 2)) x ceil(height / (tile - 2)) free tiles, one run of consecutive
  // slots if one is long enough (the shortest such). Otherwise, when enabled and allowed by the
  // rate limit, the atlas is compacted so that every impostor's tiles are one run again;
  // else the tiles are gathered from the shortest runs. Too few free tiles (fragmentation never
  // costs capacity here): the largest size with the asked proportions that fits (downsized,
  // at least one texel a side), else failure. Throws std::invalid_argument on a non-positive
  // size or a time earlier than the last one.
  Result allocate(uint32_t id, int width, int height, double now_s);
  void release(uint32_t id);  // no-op for an id that holds nothing

  const std::map<uint32_t, Placement>& placements() const { return placements_; }
  // Where the impostor's continuous texel coordinate (u, v) in [0, width] x [0, height] (texel
  // centres at +0.5) is sampled: continuous atlas texel coordinates inside the interior of the
  // tile holding (u, v), reaching at most half a texel into its border, so that the bilinear
  // 2 x 2 footprint never leaves the tile. (u, v) outside the image (or NaN) is clamped to it.
  std::pair<float, float> atlas_texel(const Placement& placement, float u, float v) const;
  // The moves of the last defragmentation, one per tile that changed slot; not the impostor
  // being allocated then (it is rendered anew).
  const std::vector<AtlasMove>& last_moves() const { return moves_; }
  AtlasStats stats() const;

  AtlasRect slot_rect(int slot) const;
  int tile() const { return options_.tile; }
  int interior() const { return options_.tile - 2; }  // impostor texels a tile holds a side
  int slots_per_row() const { return slots_x_; }
  int slot_count() const { return slots_x_ * slots_y_; }
  int free_tiles() const { return free_tiles_; }
  double free_share() const {  // AtlasStats::free, without the rest
    return double(free_tiles_) * options_.tile * options_.tile / (double(width_) * double(height_));
  }

 private:
  int tiles_for(int texels) const { return (texels - 1) / interior() + 1; }  // texels > 0
  void free_placement(uint32_t id, long long& work);
  bool fit_proportional(int width, int height, int tiles, int& served_w, int& served_h) const;
  int shortest_run(int count, long long& work) const;  // its first slot, or -1
  std::vector<int> gather(int count, long long& work) const;
  void compact(uint32_t id, const Placement& placement, long long& work);

  int width_, height_;
  Options options_;
  int slots_x_, slots_y_;
  std::vector<uint8_t> used_;  // per slot
  int free_tiles_;
  std::map<uint32_t, Placement> placements_;
  std::vector<AtlasMove> moves_;
  atlas_detail::RateLimiter limiter_;
  atlas_detail::OpLog log_;
  int defragmentations_ = 0, downsized_ = 0, failed_ = 0;
};

}  // namespace nephele::particles

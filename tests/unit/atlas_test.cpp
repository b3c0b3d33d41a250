// The impostor atlases (seed 003, 3.3.5-3.3.6): DirectAtlas and TileAtlas under seeded random
// updates (no overlaps, sizes as asked unless downsized, downsizing only when it had to be,
// rate-limited defragmentations with exact moves), bilinear sampling inside tiles, bounded work
// per operation, statistics and argument checks. Deterministic: a simulated clock, no timings.
#include "particles/atlas.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace nephele::particles {
namespace {

constexpr double kFrameS = 1.0 / 60.0;

// --- a seeded workload: impostors appearing, changing size every few frames, vanishing -------

struct Op {
  bool release = false;
  uint32_t id = 0;
  int width = 0, height = 0;
};

class Workload {
 public:
  Workload(uint32_t seed, int ids, int min_side, int max_side)
      : rng_(seed), sizes_(size_t(ids)), min_side_(min_side), max_side_(max_side) {}

  // An update of a random impostor: a new one gets a fresh size, a live one changes its size by
  // up to 25% (or, now and then, vanishes).
  Op next() {
    const uint32_t id =
        std::uniform_int_distribution<uint32_t>(0, uint32_t(sizes_.size()) - 1)(rng_);
    auto& size = sizes_[id];
    const double roll = std::uniform_real_distribution<double>(0.0, 1.0)(rng_);
    if (size.first > 0 && roll < 0.1) {
      size = {0, 0};
      return {true, id, 0, 0};
    }
    if (size.first == 0) {
      const double side = std::exp(std::uniform_real_distribution<double>(
          std::log(double(min_side_)), std::log(double(max_side_)))(rng_));
      const double aspect = std::uniform_real_distribution<double>(0.5, 2.0)(rng_);
      size = {clamp_side(side * std::sqrt(aspect)), clamp_side(side / std::sqrt(aspect))};
    } else {
      const double scale = std::uniform_real_distribution<double>(0.8, 1.25)(rng_);
      size = {clamp_side(size.first * scale), clamp_side(size.second * scale)};
    }
    return {false, id, size.first, size.second};
  }

 private:
  int clamp_side(double side) const {
    return std::clamp(int(std::lround(side)), min_side_, max_side_);
  }

  std::mt19937 rng_;
  std::vector<std::pair<int, int>> sizes_;
  int min_side_, max_side_;
};

bool inside(const AtlasRect& inner, const AtlasRect& outer) {
  return inner.x >= outer.x && inner.y >= outer.y && inner.x + inner.w <= outer.x + outer.w &&
         inner.y + inner.h <= outer.y + outer.h;
}

// The served size keeps the asked proportions to within a texel: one side is the other scaled
// by the asked ratio, rounded down.
bool same_proportions(int served_w, int served_h, int width, int height) {
  const double by_width = double(served_w) * height / width - served_h;
  const double by_height = double(served_h) * width / height - served_w;
  return std::min(std::abs(by_width), std::abs(by_height)) < 1.0;
}

// Any half-open second of the clock holds at most `per_s` defragmentations (a whole number).
void expect_rate_limited(const std::vector<double>& times_s, double per_s) {
  for (size_t i = 0; i < times_s.size(); ++i) {
    int in_window = 0;
    for (size_t j = i; j < times_s.size() && times_s[j] < times_s[i] + 1.0 - 1e-9; ++j) ++in_window;
    EXPECT_LE(in_window, int(per_s)) << "second starting at " << times_s[i];
  }
}

// --- DirectAtlas ---------------------------------------------------------------------------

struct DirectRun {
  AtlasStats stats;
  int defragmented = 0, downsized = 0, rate_limited = 0;
};

long long free_cells(const DirectAtlas& atlas) {
  long long used = 0;
  for (const auto& [id, region] : atlas.regions()) {
    const AtlasRect a = atlas.allocation(region);
    used += (long long)(a.w / atlas.granule()) * (a.h / atlas.granule());
  }
  return (long long)(atlas.width() / atlas.granule()) * (atlas.height() / atlas.granule()) - used;
}

// Every allocation inside the whole granules, none sharing a cell (an occupancy grid of cells),
// each impostor's texels inside its allocation.
void expect_disjoint_inside(const DirectAtlas& atlas) {
  const int g = atlas.granule(), cells_x = atlas.width() / g, cells_y = atlas.height() / g;
  const AtlasRect usable = {0, 0, cells_x * g, cells_y * g};
  std::vector<uint32_t> owner(size_t(cells_x) * size_t(cells_y), UINT32_MAX);
  for (const auto& [id, region] : atlas.regions()) {
    const AtlasRect a = atlas.allocation(region);
    ASSERT_TRUE(inside(a, usable)) << "id " << id;
    ASSERT_TRUE(inside(region, a)) << "id " << id;
    ASSERT_EQ(a.x % g + a.y % g, 0) << "id " << id;
    for (int y = a.y / g; y < (a.y + a.h) / g; ++y)
      for (int x = a.x / g; x < (a.x + a.w) / g; ++x) {
        uint32_t& cell = owner[size_t(y) * size_t(cells_x) + size_t(x)];
        ASSERT_EQ(cell, UINT32_MAX) << "ids " << cell << " and " << id << " share a cell";
        cell = id;
      }
  }
}

void expect_stats_add_up(const DirectAtlas& atlas) {
  const AtlasStats s = atlas.stats();
  const double texels = double(atlas.width()) * atlas.height(),
               cell = atlas.granule() * atlas.granule();
  double held = 0.0;
  for (const auto& [id, region] : atlas.regions()) held += double(region.w) * region.h;
  EXPECT_NEAR(s.occupancy, held / texels, 1e-12);
  EXPECT_NEAR(s.free, double(free_cells(atlas)) * cell / texels, 1e-12);
  EXPECT_NEAR(s.occupancy + s.wasted + s.free + s.unusable, 1.0, 1e-12);
  EXPECT_GE(s.occupancy, 0.0);
  EXPECT_LE(s.occupancy, 1.0);
  EXPECT_GE(s.wasted, 0.0);
  EXPECT_GE(s.fragmentation, 0.0);
  EXPECT_LT(s.fragmentation, 1.0);
}

// One allocate with every check that needs the atlas as it was before: a copy of it answers
// whether the best fit could have succeeded and whether a repack of everything fits.
void checked_allocate(DirectAtlas& atlas, const Op& op, double now_s, double& last_defrag_s,
                      std::vector<double>& defrag_times_s, DirectRun& run,
                      const DirectAtlas::Options& options) {
  DirectAtlas before = atlas;
  before.release(op.id);
  const bool fitted = before.can_fit(op.width, op.height);
  const int cells_w = (op.width + options.granule - 1) / options.granule;
  const int cells_h = (op.height + options.granule - 1) / options.granule;
  const bool room = cells_w <= atlas.width() / options.granule &&
                    cells_h <= atlas.height() / options.granule &&
                    (long long)cells_w * cells_h <= free_cells(before);
  const bool allowed =
      defrag_times_s.empty() || now_s - last_defrag_s >= 1.0 / options.max_defragmentations_per_s;
  const int calls_before = atlas.stats().defragmentations;

  const DirectAtlas::Result result = atlas.allocate(op.id, op.width, op.height, now_s);

  const bool called = atlas.stats().defragmentations > calls_before;
  if (called) {
    defrag_times_s.push_back(now_s);
    last_defrag_s = now_s;
  }
  // The decision: best fit when it can; else a repack when enabled, allowed and not hopeless.
  EXPECT_EQ(called, !fitted && options.defragment && allowed && room) << "id " << op.id;
  run.rate_limited += !fitted && options.defragment && room && !allowed;
  if (called) {
    std::vector<DirectAtlas::Request> all;
    for (const auto& [id, region] : before.regions()) all.push_back({id, region.w, region.h});
    all.push_back({op.id, op.width, op.height});
    DirectAtlas fresh(atlas.width(), atlas.height(), options);
    EXPECT_EQ(result.defragmented, fresh.pack(all));
  }
  ASSERT_TRUE(result.ok || !fitted);
  if (fitted) {
    EXPECT_FALSE(result.downsized || result.defragmented);
  }
  if (!result.ok) {
    EXPECT_EQ(atlas.regions().count(op.id), 0u);
    return;
  }
  const AtlasRect region = atlas.regions().at(op.id);
  EXPECT_EQ(region, result.rect);
  if (result.downsized) {
    ++run.downsized;
    EXPECT_LE(region.w, op.width);
    EXPECT_LE(region.h, op.height);
    EXPECT_TRUE(same_proportions(region.w, region.h, op.width, op.height))
        << region.w << "x" << region.h << " for " << op.width << "x" << op.height;
  } else {
    EXPECT_EQ(region.w, op.width);
    EXPECT_EQ(region.h, op.height);
  }
  if (result.defragmented) {
    ++run.defragmented;
    // Each impostor that moved is one move from its old rectangle to its new one.
    size_t moved = 0;
    for (const auto& [id, old_region] : before.regions()) {
      const AtlasRect now = atlas.regions().at(id);
      EXPECT_EQ(now.w, old_region.w);
      EXPECT_EQ(now.h, old_region.h);
      if (now == old_region) continue;
      ++moved;
      const auto move = std::find_if(atlas.last_moves().begin(), atlas.last_moves().end(),
                                     [&](const AtlasMove& m) { return m.id == id; });
      ASSERT_NE(move, atlas.last_moves().end()) << "id " << id << " moved unreported";
      EXPECT_EQ(move->from, old_region);
      EXPECT_EQ(move->to, now);
    }
    EXPECT_EQ(atlas.last_moves().size(), moved);
  }
}

// A seeded churn of the atlas (defined with the tiles' below).
DirectRun random_direct(const DirectAtlas::Options& options, uint32_t seed, int frames);

TEST(DirectAtlas, RandomUpdatesKeepRegionsDisjointAsAskedAndDownsizeOnlyWhenForced) {
  DirectAtlas::Options plain;
  plain.defragment = false;
  const DirectRun without = random_direct(plain, 7, 1200);
  ASSERT_FALSE(HasFailure());
  EXPECT_GT(without.downsized, 20);  // the workload does press the atlas
  EXPECT_EQ(without.stats.defragmentations, 0);

  DirectAtlas::Options defragmenting;  // 2 per second
  const DirectRun with = random_direct(defragmenting, 7, 1200);
  ASSERT_FALSE(HasFailure());
  EXPECT_GT(with.defragmented, 10);
  EXPECT_GT(with.rate_limited, 0);  // the limit did bite
  EXPECT_LE(with.stats.defragmentations_per_s, 2.0);
  EXPECT_LT(with.downsized, without.downsized);  // what defragmenting is for
}

TEST(DirectAtlas, BestFitTakesTheTightestHole) {
  DirectAtlas::Options options;
  options.defragment = false;
  DirectAtlas atlas(8 * 16, 3 * 16, options);  // 8 x 3 granules
  // Fill it as 3 | 2 | 1 | 2 granules wide, then free the 3 and the 1: two holes.
  EXPECT_EQ(atlas.allocate(1, 48, 48, 0.0).rect, (AtlasRect{0, 0, 48, 48}));
  EXPECT_EQ(atlas.allocate(2, 32, 48, 0.0).rect, (AtlasRect{48, 0, 32, 48}));
  EXPECT_EQ(atlas.allocate(3, 16, 48, 0.0).rect, (AtlasRect{80, 0, 16, 48}));
  EXPECT_EQ(atlas.allocate(4, 30, 40, 0.0).rect, (AtlasRect{96, 0, 30, 40}));
  atlas.release(1);
  atlas.release(3);
  // First fit would take the wide hole on the left; best fit the narrow one that it fills.
  const DirectAtlas::Result r = atlas.allocate(5, 10, 20, 0.1);
  EXPECT_TRUE(r.ok && !r.downsized && !r.defragmented);
  EXPECT_EQ(r.rect, (AtlasRect{80, 0, 10, 20}));
  // 64 x 32 fits nowhere: the largest 2:1 rectangle in the 3 x 3 hole is 48 x 24.
  const DirectAtlas::Result smaller = atlas.allocate(6, 64, 32, 0.2);
  EXPECT_TRUE(smaller.ok && smaller.downsized);
  EXPECT_EQ(smaller.rect, (AtlasRect{0, 0, 48, 24}));
  EXPECT_EQ(atlas.stats().downsized, 1);
}

TEST(DirectAtlas, DefragmentsWhenBestFitFailsThenRespectsTheRateLimit) {
  DirectAtlas::Options options;
  options.max_defragmentations_per_s = 2.0;
  DirectAtlas atlas(8 * 16, 2 * 16, options);  // 8 x 2 granules
  for (uint32_t id = 0; id < 8; ++id) atlas.allocate(id, 16, 32, 0.0);
  atlas.release(1);
  atlas.release(3);  // free: two one-granule columns apart
  const auto before = atlas.regions();
  const DirectAtlas::Result r = atlas.allocate(10, 32, 32, 1.0);
  ASSERT_TRUE(r.ok);
  EXPECT_TRUE(r.defragmented);
  EXPECT_FALSE(r.downsized);
  EXPECT_EQ(r.rect.w, 32);
  EXPECT_EQ(atlas.stats().fragmentation, 0.0);  // full
  ASSERT_FALSE(atlas.last_moves().empty());
  for (const AtlasMove& m : atlas.last_moves()) {
    EXPECT_EQ(m.from, before.at(m.id));
    EXPECT_EQ(m.to, atlas.regions().at(m.id));
  }
  expect_disjoint_inside(atlas);

  // The same squeeze 0.3 s later: too soon after the last one, so served smaller instead.
  const AtlasRect gap_a = atlas.regions().at(2), gap_b = atlas.regions().at(5);
  ASSERT_GT(std::abs(gap_a.x - gap_b.x), 16);  // two columns apart, not one 2 x 2 hole
  atlas.release(2);
  atlas.release(5);
  const DirectAtlas::Result limited = atlas.allocate(11, 32, 32, 1.3);
  EXPECT_TRUE(limited.ok && limited.downsized && !limited.defragmented);
  EXPECT_EQ(limited.rect.w, 16);
  EXPECT_EQ(limited.rect.h, 16);
  EXPECT_EQ(atlas.stats().defragmentations, 1);
  atlas.release(11);
  const DirectAtlas::Result later = atlas.allocate(11, 32, 32, 1.5);  // 0.5 s after: allowed
  EXPECT_TRUE(later.ok && later.defragmented && !later.downsized);
  EXPECT_EQ(atlas.stats().defragmentations, 2);
  EXPECT_NEAR(atlas.stats().defragmentations_per_s, 2.0 / 1.5, 1e-12);
}

TEST(DirectAtlas, PackPlacesAWholeBatchOrNothing) {
  DirectAtlas atlas(512, 512, {});
  std::mt19937 rng(3);
  std::vector<DirectAtlas::Request> batch;
  for (uint32_t id = 0; id < 40; ++id)
    batch.push_back({id, std::uniform_int_distribution<int>(20, 100)(rng),
                     std::uniform_int_distribution<int>(20, 100)(rng)});
  ASSERT_TRUE(atlas.pack(batch));
  ASSERT_EQ(atlas.regions().size(), batch.size());
  for (const DirectAtlas::Request& r : batch) {
    EXPECT_EQ(atlas.regions().at(r.id).w, r.width);
    EXPECT_EQ(atlas.regions().at(r.id).h, r.height);
  }
  expect_disjoint_inside(atlas);
  EXPECT_THROW(atlas.pack(batch), std::logic_error);  // not empty any more

  DirectAtlas small(128, 128, {});
  EXPECT_FALSE(small.pack({{1, 100, 100}, {2, 100, 100}}));
  EXPECT_TRUE(small.regions().empty());
  EXPECT_EQ(small.stats().free, 1.0);
}

TEST(DirectAtlas, WorkPerOperationIsBoundedByTheGrid) {
  for (int side : {256, 1024}) {
    DirectAtlas::Options options;
    options.defragment = false;
    DirectAtlas atlas(side, side, options);
    Workload work(11, side / 5, 8, side / 4);
    for (int i = 0; i < 600; ++i) {
      const Op op = work.next();
      if (op.release) {
        atlas.release(op.id);
      } else {
        atlas.allocate(op.id, op.width, op.height, i * kFrameS);
      }
    }
    const AtlasStats s = atlas.stats();
    const long long cells = (long long)(side / 16) * (side / 16);
    EXPECT_GT(s.downsized, 0) << side;  // the costliest path was taken too
    EXPECT_LE(s.max_op_work, 24 * cells) << side;
    EXPECT_GT(s.max_op_work, cells) << side;
    EXPECT_EQ(s.operations, 600);
  }
}

TEST(DirectAtlas, StatisticsOfAnEmptyAndAFullAtlas) {
  DirectAtlas atlas(100, 70, {});  // 6 x 4 granules; 4 and 6 texels unusable
  AtlasStats s = atlas.stats();
  EXPECT_EQ(s.occupancy, 0.0);
  EXPECT_EQ(s.fragmentation, 0.0);
  EXPECT_NEAR(s.free, 96.0 * 64.0 / 7000.0, 1e-12);
  EXPECT_NEAR(s.unusable, 1.0 - 96.0 * 64.0 / 7000.0, 1e-12);
  EXPECT_EQ(s.operations, 0);
  atlas.allocate(1, 90, 60, 0.0);  // 6 x 4 granules: all of it
  s = atlas.stats();
  EXPECT_NEAR(s.occupancy, 5400.0 / 7000.0, 1e-12);
  EXPECT_NEAR(s.wasted, (96.0 * 64.0 - 5400.0) / 7000.0, 1e-12);
  EXPECT_EQ(s.free, 0.0);
  EXPECT_EQ(s.fragmentation, 0.0);
  EXPECT_FALSE(atlas.allocate(2, 16, 16, 0.5).ok);  // nothing free: fails
  EXPECT_EQ(atlas.stats().failed, 1);
  atlas.release(1);
  atlas.allocate(2, 16, 64, 1.0);  // a column off the middle: free space in two blocks
  atlas.allocate(3, 32, 16, 1.0);
  s = atlas.stats();
  EXPECT_GT(s.fragmentation, 0.0);
  EXPECT_EQ(s.operations, 5);
  EXPECT_NEAR(s.occupancy + s.wasted + s.free + s.unusable, 1.0, 1e-12);
}

// A request larger than the atlas is the downsizing path's extreme: served at the atlas's size
// in the asked proportions, with no overflow and no work beyond the usual passes.
TEST(AtlasExtremes, RequestsLargerThanTheAtlasAreServedSmallerInProportion) {
  constexpr int kHuge = std::numeric_limits<int>::max();
  DirectAtlas direct(256, 128, {});
  const DirectAtlas::Result r = direct.allocate(1, kHuge, kHuge / 4, 0.0);
  ASSERT_TRUE(r.ok && r.downsized && !r.defragmented);
  EXPECT_EQ(r.rect, (AtlasRect{0, 0, 256, 63}));  // 4:1, the width limiting, rounded down
  EXPECT_EQ(direct.stats().defragmentations, 0);  // hopeless: no repack tried
  EXPECT_LE(direct.stats().max_op_work, 24LL * 16 * 8);

  TileAtlas tiles(256, 256, {.tile = 32});  // 64 tiles of 30 texels inside
  const TileAtlas::Result t = tiles.allocate(1, kHuge, kHuge, 0.0);
  ASSERT_TRUE(t.ok && t.downsized);
  EXPECT_EQ(t.placement.width, 240);  // 8 x 8 tiles
  EXPECT_EQ(t.placement.height, 240);
  EXPECT_EQ(tiles.free_tiles(), 0);
  EXPECT_LE(tiles.stats().max_op_work, 8LL * tiles.slot_count());
  // Sampling outside the image, or at NaN, stays inside the impostor's tiles.
  for (const auto& [u, v] : {std::pair{-5.0f, 3.0f}, {1e9f, 1e9f}, {NAN, NAN}}) {
    const auto [x, y] = tiles.atlas_texel(t.placement, u, v);
    EXPECT_TRUE(x >= 1.0f && x <= 255.0f && y >= 1.0f && y <= 255.0f) << x << ", " << y;
  }
}

TEST(DirectAtlas, RejectsBadArgumentsNamingThem) {
  const auto message_of = [](auto&& call) -> std::string {
    try {
      call();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no std::invalid_argument";
  };
  EXPECT_NE(message_of([] { DirectAtlas(0, 64, {}); }).find("width = 0: must be positive"),
            std::string::npos);
  EXPECT_NE(message_of([] { DirectAtlas(64, -3, {}); }).find("height = -3"), std::string::npos);
  EXPECT_NE(message_of([] {
              DirectAtlas(64, 64, {.granule = 0});
            }).find("granule = 0: must be at least 1"),
            std::string::npos);
  EXPECT_NE(message_of([] { DirectAtlas(64, 32, {.granule = 48}); }).find("at most"),
            std::string::npos);
  EXPECT_NE(message_of([] {
              DirectAtlas(64, 64, {.max_defragmentations_per_s = 0.0});
            }).find("max_defragmentations_per_s = 0"),
            std::string::npos);
  EXPECT_NO_THROW(DirectAtlas(64, 64, {.defragment = false, .max_defragmentations_per_s = 0.0}));
  DirectAtlas atlas(64, 64, {});
  EXPECT_NE(message_of([&] { atlas.allocate(1, 0, 16, 0.0); }).find("width = 0"),
            std::string::npos);
  EXPECT_NE(message_of([&] { atlas.allocate(1, 16, -1, 0.0); }).find("height = -1"),
            std::string::npos);
  atlas.allocate(1, 16, 16, 2.0);
  EXPECT_NE(message_of([&] { atlas.allocate(1, 16, 16, 1.0); }).find("not earlier"),
            std::string::npos);
  EXPECT_THROW(atlas.allocate(1, 16, 16, NAN), std::invalid_argument);
  DirectAtlas empty(64, 64, {});
  EXPECT_NE(message_of([&] {
              empty.pack({{1, 8, 8}, {1, 8, 8}});
            }).find("id = 1"),
            std::string::npos);
  EXPECT_THROW(empty.pack({{1, 8, 0}}), std::invalid_argument);
}

// --- TileAtlas -----------------------------------------------------------------------------

struct TileRun {
  AtlasStats stats;
  int defragmented = 0, downsized = 0, scattered = 0;
};

std::vector<uint8_t> used_slots(const TileAtlas& atlas) {
  std::vector<uint8_t> used(size_t(atlas.slot_count()), 0);
  for (const auto& [id, p] : atlas.placements())
    for (int s : p.slots) used[size_t(s)] = 1;
  return used;
}

bool has_run(const std::vector<uint8_t>& used, int count) {
  int length = 0;
  for (uint8_t u : used) {
    length = u ? 0 : length + 1;
    if (length >= count) return true;
  }
  return false;
}

bool one_run(const std::vector<int>& slots) {
  for (size_t k = 1; k < slots.size(); ++k)
    if (slots[k] != slots[k - 1] + 1) return false;
  return true;
}

// Every slot in the atlas and owned by one impostor at most (an occupancy grid of slots); each
// placement's tiles cover its texels.
void expect_disjoint_inside(const TileAtlas& atlas) {
  std::vector<uint32_t> owner(size_t(atlas.slot_count()), UINT32_MAX);
  for (const auto& [id, p] : atlas.placements()) {
    ASSERT_EQ(p.tiles_x, (p.width + atlas.interior() - 1) / atlas.interior()) << "id " << id;
    ASSERT_EQ(p.tiles_y, (p.height + atlas.interior() - 1) / atlas.interior()) << "id " << id;
    ASSERT_EQ(p.slots.size(), size_t(p.tiles_x) * size_t(p.tiles_y)) << "id " << id;
    for (int s : p.slots) {
      ASSERT_TRUE(s >= 0 && s < atlas.slot_count()) << "id " << id << " slot " << s;
      ASSERT_TRUE(inside(atlas.slot_rect(s), {0, 0, 1 << 20, 1 << 20}));
      ASSERT_EQ(owner[size_t(s)], UINT32_MAX) << "ids " << owner[size_t(s)] << ", " << id;
      owner[size_t(s)] = id;
    }
  }
  EXPECT_EQ(atlas.free_tiles(), std::count(owner.begin(), owner.end(), UINT32_MAX));
}

// The shares add up exactly: each is a whole number of texels over the atlas's texels.
void expect_stats_add_up(const TileAtlas& atlas, int width, int height) {
  const AtlasStats s = atlas.stats();
  const double texels = double(width) * height, tile = atlas.tile() * atlas.tile();
  long long held = 0, tiles = 0;
  for (const auto& [id, p] : atlas.placements()) {
    held += (long long)p.width * p.height;
    tiles += (long long)p.slots.size();
  }
  EXPECT_EQ(s.occupancy, double(held) / texels);
  EXPECT_EQ(s.wasted, double(tiles * (long long)tile - held) / texels);
  EXPECT_EQ(s.free, double(atlas.free_tiles()) * tile / texels);
  EXPECT_EQ(s.unusable, (texels - atlas.slot_count() * tile) / texels);
  EXPECT_NEAR(s.occupancy + s.wasted + s.free + s.unusable, 1.0, 1e-15);
  EXPECT_GE(s.occupancy, 0.0);
  EXPECT_LE(s.occupancy, 1.0);
}

void checked_allocate(TileAtlas& atlas, const Op& op, double now_s, double& last_defrag_s,
                      std::vector<double>& defrag_times_s, TileRun& run,
                      const TileAtlas::Options& options) {
  TileAtlas before = atlas;
  before.release(op.id);
  const int inner = atlas.interior();
  const int needed = ((op.width + inner - 1) / inner) * ((op.height + inner - 1) / inner);
  const bool enough = needed <= before.free_tiles();
  const bool allowed =
      defrag_times_s.empty() || now_s - last_defrag_s >= 1.0 / options.max_defragmentations_per_s;

  const TileAtlas::Result result = atlas.allocate(op.id, op.width, op.height, now_s);

  EXPECT_EQ(result.ok, before.free_tiles() > 0);
  if (!result.ok) return;
  EXPECT_EQ(result.downsized, !enough);  // tiles fragment locality, never capacity
  const TileAtlas::Placement& p = atlas.placements().at(op.id);
  EXPECT_EQ(p.slots, result.placement.slots);
  if (result.downsized) {
    ++run.downsized;
    EXPECT_LE(p.width, op.width);
    EXPECT_LE(p.height, op.height);
    EXPECT_LE(int(p.slots.size()), before.free_tiles());
    EXPECT_TRUE(same_proportions(p.width, p.height, op.width, op.height))
        << p.width << "x" << p.height << " for " << op.width << "x" << op.height;
  } else {
    EXPECT_EQ(p.width, op.width);
    EXPECT_EQ(p.height, op.height);
  }
  // A run of slots when one is free; else a compaction when enabled and allowed.
  const bool run_free = has_run(used_slots(before), int(p.slots.size()));
  EXPECT_EQ(result.defragmented, !run_free && options.defragment && allowed);
  if (run_free || result.defragmented) {
    EXPECT_TRUE(one_run(p.slots));
  }
  run.scattered += !one_run(p.slots);
  if (!result.defragmented) return;
  ++run.defragmented;
  defrag_times_s.push_back(now_s);
  last_defrag_s = now_s;
  EXPECT_EQ(atlas.stats().fragmentation, 0.0);
  // One move per tile that changed slot, from the old slot's square to the new one's.
  std::set<std::tuple<uint32_t, int, int, int, int>> moves;
  for (const AtlasMove& m : atlas.last_moves()) {
    EXPECT_EQ(m.from.w, atlas.tile());
    moves.insert({m.id, m.from.x, m.from.y, m.to.x, m.to.y});
  }
  EXPECT_EQ(moves.size(), atlas.last_moves().size());
  size_t moved = 0;
  for (const auto& [id, old] : before.placements()) {
    const TileAtlas::Placement& now = atlas.placements().at(id);
    ASSERT_EQ(now.slots.size(), old.slots.size());
    for (size_t k = 0; k < old.slots.size(); ++k) {
      if (old.slots[k] == now.slots[k]) continue;
      ++moved;
      const AtlasRect from = atlas.slot_rect(old.slots[k]), to = atlas.slot_rect(now.slots[k]);
      EXPECT_EQ(moves.count({id, from.x, from.y, to.x, to.y}), 1u) << "id " << id << " tile " << k;
    }
  }
  EXPECT_EQ(atlas.last_moves().size(), moved);
}

// Seeded random allocations and releases, three a frame at kFrameS, each allocation checked
// against the atlas as it was (checked_allocate), the layout after every operation, the
// statistics every 50 frames and the defragmentations' rate at the end.
template <typename Run, typename Atlas, typename Options>
Run churn(Atlas& atlas, const Options& options, Workload work, int frames, int width, int height) {
  std::vector<double> defrag_times_s;
  double last_defrag_s = 0.0;
  Run run;
  for (int frame = 0; frame < frames; ++frame) {
    const double now_s = frame * kFrameS;
    for (int k = 0; k < 3; ++k) {
      const Op op = work.next();
      if (op.release) {
        atlas.release(op.id);
        if constexpr (std::is_same_v<Atlas, DirectAtlas>)
          EXPECT_EQ(atlas.regions().count(op.id), 0u);
        else
          EXPECT_EQ(atlas.placements().count(op.id), 0u);
      } else {
        checked_allocate(atlas, op, now_s, last_defrag_s, defrag_times_s, run, options);
      }
      expect_disjoint_inside(atlas);
      if (::testing::Test::HasFailure()) return run;
    }
    if (frame % 50 != 0) continue;
    if constexpr (std::is_same_v<Atlas, DirectAtlas>)
      expect_stats_add_up(atlas);
    else
      expect_stats_add_up(atlas, width, height);
  }
  if (options.defragment) expect_rate_limited(defrag_times_s, options.max_defragmentations_per_s);
  run.stats = atlas.stats();
  return run;
}

DirectRun random_direct(const DirectAtlas::Options& options, uint32_t seed, int frames) {
  DirectAtlas atlas(390, 260, options);  // 24 x 16 granules and an unusable strip
  return churn<DirectRun>(atlas, options, Workload(seed, 28, 10, 120), frames, 390, 260);
}

TileRun random_tiles(const TileAtlas::Options& options, uint32_t seed, int frames) {
  const int width = 330, height = 230;  // an unusable strip whichever the tile
  TileAtlas atlas(width, height, options);
  return churn<TileRun>(atlas, options, Workload(seed, 24, 8, 110), frames, width, height);
}

TEST(TileAtlas, RandomUpdatesKeepTilesDisjointAsAskedAndDownsizeOnlyWhenFull) {
  for (int tile : {16, 32}) {
    SCOPED_TRACE("tile " + std::to_string(tile));
    const TileRun without = random_tiles({.tile = tile, .defragment = false}, 5, 1000);
    ASSERT_FALSE(HasFailure());
    EXPECT_GT(without.downsized, 10);
    EXPECT_GT(without.scattered, 10);
    EXPECT_EQ(without.stats.defragmentations, 0);
    const TileRun with = random_tiles(
        {.tile = tile, .defragment = true, .max_defragmentations_per_s = 3.0}, 5, 1000);
    ASSERT_FALSE(HasFailure());
    EXPECT_GT(with.defragmented, 10);
    EXPECT_LE(with.stats.defragmentations_per_s, 3.0);
    EXPECT_LT(with.stats.fragmentation, 0.5);
  }
}

TEST(TileAtlas, CompactionMovesTheScatteredTilesTogether) {
  for (bool defragment : {false, true}) {
    TileAtlas atlas(4 * 32, 32, {.tile = 32, .defragment = defragment});  // 4 slots in a row
    for (uint32_t id = 0; id < 4; ++id)
      EXPECT_EQ(atlas.allocate(id, 30, 30, 0.0).placement.slots, std::vector<int>{int(id)});
    atlas.release(0);
    atlas.release(2);
    const TileAtlas::Result r = atlas.allocate(9, 60, 30, 1.0);  // two tiles; no two free together
    ASSERT_TRUE(r.ok);
    EXPECT_FALSE(r.downsized);
    EXPECT_EQ(r.defragmented, defragment);
    if (!defragment) {
      EXPECT_EQ(r.placement.slots, (std::vector<int>{0, 2}));
      EXPECT_NEAR(atlas.stats().fragmentation, 1.0 / 3.0, 1e-12);
      continue;
    }
    EXPECT_EQ(atlas.placements().at(1).slots, std::vector<int>{0});
    EXPECT_EQ(atlas.placements().at(3).slots, std::vector<int>{1});
    EXPECT_EQ(r.placement.slots, (std::vector<int>{2, 3}));
    ASSERT_EQ(atlas.last_moves().size(), 2u);
    EXPECT_EQ(atlas.last_moves()[0].id, 1u);
    EXPECT_EQ(atlas.last_moves()[0].from, (AtlasRect{32, 0, 32, 32}));
    EXPECT_EQ(atlas.last_moves()[0].to, (AtlasRect{0, 0, 32, 32}));
    EXPECT_EQ(atlas.last_moves()[1].id, 3u);
    EXPECT_EQ(atlas.last_moves()[1].from, (AtlasRect{96, 0, 32, 32}));
    EXPECT_EQ(atlas.last_moves()[1].to, (AtlasRect{32, 0, 32, 32}));
    EXPECT_EQ(atlas.stats().fragmentation, 0.0);
  }
}

TEST(TileAtlas, DownsizesToTheFreeTilesKeepingProportionsThenFails) {
  TileAtlas atlas(4 * 16, 2 * 16, {.tile = 16});  // 8 slots, 14 texels inside each
  EXPECT_EQ(atlas.allocate(1, 14, 28, 0.0).placement.slots.size(), 2u);
  const TileAtlas::Result r = atlas.allocate(2, 56, 28, 0.0);  // 4 x 2 tiles; 6 free
  ASSERT_TRUE(r.ok && r.downsized);
  EXPECT_EQ(r.placement.width, 42);  // 3 x 1.5 -> 3 x 2 tiles
  EXPECT_EQ(r.placement.height, 21);
  EXPECT_EQ(r.placement.slots.size(), 6u);
  EXPECT_FALSE(atlas.allocate(3, 10, 10, 0.0).ok);
  EXPECT_EQ(atlas.stats().failed, 1);
  EXPECT_EQ(atlas.stats().downsized, 1);
  EXPECT_EQ(atlas.stats().free, 0.0);
}

// Bilinear filtering reads the 2 x 2 texels around (x - 0.5, y - 0.5): they must lie in the
// tile's slot, and the tile texel there must hold the impostor's texel at (u, v) (interior
// texel t of tile column c is the impostor's texel c (tile - 2) + t - 1, border included).
TEST(TileAtlas, BilinearFootprintStaysInTheTileAndReadsTheImpostorsTexels) {
  for (int tile : {16, 32}) {
    TileAtlas atlas(256, 256, {.tile = tile});
    atlas.allocate(1, 20, 20, 0.0);  // the tiles of the next ones do not start at slot 0
    for (const auto& [w, h] : {std::pair{45, 29}, {14, 14}, {100, 3}, {31, 90}}) {
      const TileAtlas::Placement p = atlas.allocate(uint32_t(w), w, h, 0.0).placement;
      const int inner = atlas.interior();
      for (float u = 0.0f; u <= float(w); u += 0.125f) {
        for (float v = 0.0f; v <= float(h); v += 0.375f) {
          const auto [x, y] = atlas.atlas_texel(p, u, v);
          const int x0 = int(std::floor(x - 0.5f)), y0 = int(std::floor(y - 0.5f));
          const int column = std::min(int(u) / inner, p.tiles_x - 1);
          const int row = std::min(int(v) / inner, p.tiles_y - 1);
          // On a shared edge either tile will do: find the one it chose.
          const AtlasRect slot = [&] {
            for (int s : p.slots) {
              const AtlasRect r = atlas.slot_rect(s);
              if (x >= r.x && x < r.x + r.w && y >= r.y && y < r.y + r.h) return r;
            }
            return AtlasRect{};
          }();
          ASSERT_GT(slot.w, 0) << "u " << u << " v " << v;
          const int k = int(std::find_if(p.slots.begin(), p.slots.end(),
                                         [&](int s) { return atlas.slot_rect(s) == slot; }) -
                            p.slots.begin());
          const int c = k % p.tiles_x, r = k / p.tiles_x;
          EXPECT_LE(std::abs(c - column), 1);
          EXPECT_LE(std::abs(r - row), 1);
          EXPECT_TRUE(x0 >= slot.x && x0 + 1 < slot.x + tile) << "u " << u << " x " << x;
          EXPECT_TRUE(y0 >= slot.y && y0 + 1 < slot.y + tile) << "v " << v << " y " << y;
          EXPECT_NEAR(float(c * inner - 1) + (x - float(slot.x)), u, 1e-4f);
          EXPECT_NEAR(float(r * inner - 1) + (y - float(slot.y)), v, 1e-4f);
        }
      }
      if (HasFailure()) return;
    }
  }
}

TEST(TileAtlas, WorkPerOperationIsBoundedByTheSlots) {
  for (int side : {256, 1024}) {
    TileAtlas atlas(side, side, {.tile = 16});
    Workload work(13, side / 6, 8, side / 4);
    for (int i = 0; i < 600; ++i) {
      const Op op = work.next();
      if (op.release) {
        atlas.release(op.id);
      } else {
        atlas.allocate(op.id, op.width, op.height, i * kFrameS);
      }
    }
    const AtlasStats s = atlas.stats();
    EXPECT_GT(s.downsized, 0) << side;
    EXPECT_LE(s.max_op_work, 8LL * atlas.slot_count()) << side;
    EXPECT_EQ(s.operations, 600);
  }
}

TEST(TileAtlas, StatisticsOfAnEmptyAtlas) {
  TileAtlas atlas(100, 70, {.tile = 32});  // 3 x 2 slots
  const AtlasStats s = atlas.stats();
  EXPECT_EQ(s.occupancy, 0.0);
  EXPECT_EQ(s.wasted, 0.0);
  EXPECT_EQ(s.fragmentation, 0.0);
  EXPECT_EQ(s.free, 6.0 * 1024.0 / 7000.0);
  expect_stats_add_up(atlas, 100, 70);
  atlas.allocate(1, 31, 5, 0.0);  // 2 x 1 tiles
  expect_stats_add_up(atlas, 100, 70);
  EXPECT_EQ(atlas.stats().wasted, (2.0 * 1024.0 - 155.0) / 7000.0);
}

TEST(TileAtlas, RejectsBadArgumentsNamingThem) {
  const auto message_of = [](auto&& call) -> std::string {
    try {
      call();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no std::invalid_argument";
  };
  EXPECT_NE(message_of([] { TileAtlas(64, 64, {.tile = 24}); }).find("tile = 24: must be 16 or 32"),
            std::string::npos);
  EXPECT_NE(message_of([] { TileAtlas(64, 20, {.tile = 32}); }).find("must not exceed"),
            std::string::npos);
  EXPECT_NE(message_of([] { TileAtlas(-1, 64, {}); }).find("width = -1: must be positive"),
            std::string::npos);
  EXPECT_NE(message_of([] { TileAtlas(64, 0, {}); }).find("height = 0"), std::string::npos);
  EXPECT_NE(message_of([] {
              TileAtlas(64, 64, {.defragment = true, .max_defragmentations_per_s = -1.0});
            }).find("max_defragmentations_per_s"),
            std::string::npos);
  TileAtlas atlas(64, 64, {});
  EXPECT_NE(message_of([&] { atlas.allocate(1, -2, 8, 0.0); }).find("width = -2"),
            std::string::npos);
  atlas.allocate(1, 8, 8, 1.0);
  EXPECT_NE(message_of([&] { atlas.allocate(1, 8, 8, 0.5); }).find("now_s = 0.5"),
            std::string::npos);
}

// The table of the two methods under churn in docs/particle-clouds.md: a 2048^2 atlas, 100
// impostors of 48-400 texels a side (aspect 0.5-2), each changing size every four frames or so
// (sometimes vanishing), 30 s at 60 frames/s. A measurement, not a check: run it with
//   build/tests/nephele_tests --gtest_also_run_disabled_tests \
//       --gtest_filter='AtlasChurn.DISABLED_*'
template <typename Atlas>
void print_churn(const char* label, Atlas atlas) {
  Workload workload(20261126, 100, 48, 400);
  double occupancy = 0.0, wasted = 0.0, fragmentation = 0.0;
  long long allocations = 0, downsized = 0;
  constexpr int kFrames = 30 * 60;
  for (int frame = 0; frame < kFrames; ++frame) {
    const double now_s = frame * kFrameS;
    for (int k = 0; k < 25; ++k) {
      const Op op = workload.next();
      if (op.release) {
        atlas.release(op.id);
        continue;
      }
      ++allocations;
      downsized += atlas.allocate(op.id, op.width, op.height, now_s).downsized ? 1 : 0;
    }
    const AtlasStats s = atlas.stats();
    occupancy += s.occupancy / kFrames;
    wasted += s.wasted / kFrames;
    fragmentation += s.fragmentation / kFrames;
  }
  const AtlasStats s = atlas.stats();
  std::printf("| %s | %.2f | %.2f | %.2f | %.2f | %.1f%% | %.1f |\n", label, occupancy, wasted,
              fragmentation, s.defragmentations_per_s, 100.0 * double(downsized) / double(allocations),
              s.mean_op_us);
}

TEST(AtlasChurn, DISABLED_StatisticsOfBothMethods) {
  std::printf("| method | occupancy | waste | fragmentation | defragmentations/s | downsized | "
              "us/operation |\n");
  print_churn("direct, no defragmentation", DirectAtlas(2048, 2048, {16, false, 2.0}));
  print_churn("direct, at most 2/s", DirectAtlas(2048, 2048, {16, true, 2.0}));
  print_churn("tiles of 32", TileAtlas(2048, 2048, {32, false, 1.0}));
  print_churn("tiles of 32, at most 1/s", TileAtlas(2048, 2048, {32, true, 1.0}));
  print_churn("tiles of 16", TileAtlas(2048, 2048, {16, false, 1.0}));
}

}  // namespace
}  // namespace nephele::particles

// The shaders read a tiled impostor through common/impostor_inc.glsl: the same texels as
// TileAtlas::atlas_texel, inside the tile's slot with the bilinear footprint.
#include "render/glsl.h"

namespace nephele::particles {
namespace {

TEST(TileAtlas, TheShadersLookupIsTheAtlasOwn) {
  for (int tile : {16, 32}) {
    TileAtlas atlas(512, 512, {tile, false, 1.0});
    const TileAtlas::Result r = atlas.allocate(7, 100, 70, 0.0);
    ASSERT_TRUE(r.ok);
    const TileAtlas::Placement& p = r.placement;
    int checked = 0;
    for (int j = 0; j <= 40; ++j)
      for (int i = 0; i <= 40; ++i) {
        const glm::vec2 uv(i / 40.0f, j / 40.0f);
        const glm::vec2 size(p.width, p.height);
        const glm::ivec2 t = glsl::impostor_tile_of(uv, size, tile, p.tiles_x);
        const int slot = p.slots[size_t(t.y * p.tiles_x + t.x)];
        const glm::vec2 texel =
            glsl::impostor_tile_texel(uv, size, tile, t, slot, atlas.slots_per_row());
        const auto [ax, ay] = atlas.atlas_texel(p, uv.x * p.width, uv.y * p.height);
        EXPECT_NEAR(texel.x, ax, 1e-3f) << "tile " << tile << " uv " << uv.x << ", " << uv.y;
        EXPECT_NEAR(texel.y, ay, 1e-3f) << "tile " << tile << " uv " << uv.x << ", " << uv.y;
        const AtlasRect slot_rect = atlas.slot_rect(slot);
        const int x0 = int(std::floor(texel.x - 0.5f)), y0 = int(std::floor(texel.y - 0.5f));
        EXPECT_GE(x0, slot_rect.x);
        EXPECT_GE(y0, slot_rect.y);
        EXPECT_LT(x0 + 1, slot_rect.x + slot_rect.w);
        EXPECT_LT(y0 + 1, slot_rect.y + slot_rect.h);
        ++checked;
      }
    EXPECT_EQ(checked, 41 * 41);
  }
}

}  // namespace
}  // namespace nephele::particles

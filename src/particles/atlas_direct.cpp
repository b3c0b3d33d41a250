// DirectAtlas (seed 003, 3.3.5) and the statistics both atlases share.
//
// The atlas is a grid of granule cells, one byte each (128 x 128 for 2048 texels and 16-texel
// granules). The best fit scores every corner where the request fits from run lengths of free
// cells and their sliding-window minima: a constant number of passes over the grid, so the
// search is linear in the atlas's cells however many impostors it holds, and it needs no list
// of free rectangles to keep up to date when impostors are freed. Defragmentation packs all
// impostors anew with MaxRects, which packs a known batch far better than any online rule.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "particles/atlas.h"

namespace nephele::particles {

namespace atlas_detail {

void OpLog::observe(double now_s) {
  if (!std::isfinite(now_s) || (any_time_ && now_s < last_s_)) {
    std::ostringstream message;
    message << "now_s = " << now_s << ": must be finite and not earlier than the last call's";
    if (any_time_) message << ' ' << last_s_;
    throw std::invalid_argument(message.str());
  }
  if (!any_time_) first_s_ = now_s;
  any_time_ = true;
  last_s_ = now_s;
}

void OpLog::record(Clock::time_point start, long long work, bool defragmented) {
  const double op_us = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
  ++operations_;
  total_us_ += op_us;
  max_us_ = std::max(max_us_, op_us);
  if (defragmented) {
    max_defrag_work_ = std::max(max_defrag_work_, work);
    max_defrag_us_ = std::max(max_defrag_us_, op_us);
  } else {
    max_work_ = std::max(max_work_, work);
  }
}

void OpLog::fill(AtlasStats& stats) const {
  stats.operations = operations_;
  stats.mean_op_us = operations_ > 0 ? total_us_ / double(operations_) : 0.0;
  stats.max_op_us = max_us_;
  stats.max_op_work = max_work_;
  stats.max_defrag_work = max_defrag_work_;
  stats.max_defrag_us = max_defrag_us_;
  const double span_s = last_s_ - first_s_;
  stats.defragmentations_per_s = span_s > 0.0 ? stats.defragmentations / span_s : 0.0;
}

void require_positive(const char* what, int value) {
  if (value <= 0)
    throw std::invalid_argument(std::string(what) + " = " + std::to_string(value) +
                                ": must be positive");
}

void require_rate(const char* what, bool defragment, double per_s) {
  if (defragment && !(per_s > 0.0 && std::isfinite(per_s))) {
    std::ostringstream message;
    message << what << ".max_defragmentations_per_s = " << per_s
            << ": must be positive and finite when defragmenting";
    throw std::invalid_argument(message.str());
  }
}

}  // namespace atlas_detail

namespace {

using atlas_detail::require_positive;
using atlas_detail::require_rate;
using Clock = atlas_detail::OpLog::Clock;

// out[i] = min(in[i], ..., in[i + window - 1]) for i in [0, n - window], where each element is a
// row of `lanes` ints minimised lane by lane (a grid's rows, for minima down its columns). Van
// Herk and Gil-Werman: minima from each block of `window` elements' start (kept in `scratch`)
// and to its end (written to out) meet in any window; three branch-free passes that vectorise
// across the lanes. out and scratch hold n * lanes ints.
void window_min(const int* in, int n, int lanes, int window, int* out, int* scratch) {
  const auto row = [lanes](int* a, int i) { return a + ptrdiff_t(i) * lanes; };
  const auto crow = [lanes](const int* a, int i) { return a + ptrdiff_t(i) * lanes; };
  for (int i = 0; i < n; ++i) {
    const int* source = crow(in, i);
    int* to_here = row(scratch, i);
    if (i % window == 0) {
      std::copy_n(source, lanes, to_here);
    } else {
      const int* before = row(scratch, i - 1);
      for (int l = 0; l < lanes; ++l) to_here[l] = std::min(before[l], source[l]);
    }
  }
  for (int i = n - 1; i >= 0; --i) {
    const int* source = crow(in, i);
    int* from_here = row(out, i);
    if (i % window == window - 1 || i == n - 1) {
      std::copy_n(source, lanes, from_here);
    } else {
      const int* after = row(out, i + 1);
      for (int l = 0; l < lanes; ++l) from_here[l] = std::min(after[l], source[l]);
    }
  }
  for (int i = 0; i + window <= n; ++i) {
    int* result = row(out, i);
    const int* block_start_side = row(scratch, i + window - 1);
    for (int l = 0; l < lanes; ++l) result[l] = std::min(result[l], block_start_side[l]);
  }
}

// The free space beside a cells_w x cells_h block at each corner (x, y), from the runs of free
// cells through every cell. right_min at (x, y): the least free run rightwards from column x
// over the block's rows (the block fits where it is >= cells_w); left_min at (x - 1, y): the
// free cells left of it in all its rows; down_min and up_min likewise along its columns (at
// (x, y) and (x, y - 1)). The runs along columns are stored column-major so that their minima
// along a row are minima of whole columns too, which vectorise.
struct BlockSlack {
  int nx, ny;
  const int *right_min, *left_min, *down_min, *up_min;
  size_t row_major(int x, int y) const { return size_t(y) * size_t(nx) + size_t(x); }
  size_t column_major(int x, int y) const { return size_t(x) * size_t(ny) + size_t(y); }
};

BlockSlack block_slack(const std::vector<uint8_t>& used, int nx, int ny, int cells_w, int cells_h,
                       std::vector<int>& scratch, long long& work) {
  const size_t n = size_t(nx) * size_t(ny);
  scratch.resize(9 * n);
  int* right = scratch.data();
  int* left = right + n;
  int* down = left + n;
  int* up = down + n;
  int* minima = up + n;
  int* partial = minima + 4 * n;
  const BlockSlack slack = {nx, ny, minima, minima + n, minima + 2 * n, minima + 3 * n};
  // All ones where free, zero where used: run = (run + 1) & mask counts without a branch or a
  // multiplication on the loop's critical path.
  const auto free_mask = [&](int x, int y) { return int(used[slack.row_major(x, y)]) - 1; };
  for (int y = 0; y < ny; ++y) {
    int run = 0;
    for (int x = nx - 1; x >= 0; --x)
      right[slack.row_major(x, y)] = run = (run + 1) & free_mask(x, y);
    run = 0;
    for (int x = 0; x < nx; ++x) left[slack.row_major(x, y)] = run = (run + 1) & free_mask(x, y);
  }
  for (int x = 0; x < nx; ++x) {
    int run = 0;
    for (int y = ny - 1; y >= 0; --y)
      down[slack.column_major(x, y)] = run = (run + 1) & free_mask(x, y);
    run = 0;
    for (int y = 0; y < ny; ++y) up[slack.column_major(x, y)] = run = (run + 1) & free_mask(x, y);
  }
  window_min(right, ny, nx, cells_h, minima, partial);
  window_min(left, ny, nx, cells_h, minima + n, partial);
  window_min(down, nx, ny, cells_w, minima + 2 * n, partial);
  window_min(up, nx, ny, cells_w, minima + 3 * n, partial);
  work += 16LL * (long long)n;  // four run passes, four window minima of three passes each
  return slack;
}

// Calls visit(x, y, w, h) with rectangles of free cells (used[i] == 0) such that every free
// rectangle lies inside one of them: for each row, the widest rectangles standing on it under
// each column's free height (the histogram's stack algorithm). At most one per cell.
template <typename Visit>
void for_each_maximal_free_rect(const std::vector<uint8_t>& used, int cells_x, int cells_y,
                                long long& work, Visit visit) {
  std::vector<int> heights(size_t(cells_x) + 1, 0), stack;
  stack.reserve(size_t(cells_x) + 1);
  for (int y = 0; y < cells_y; ++y) {
    for (int x = 0; x < cells_x; ++x)
      heights[size_t(x)] =
          used[size_t(y) * size_t(cells_x) + size_t(x)] ? 0 : heights[size_t(x)] + 1;
    stack.clear();
    for (int x = 0; x <= cells_x; ++x) {  // heights[cells_x] = 0 empties the stack
      while (!stack.empty() && heights[size_t(stack.back())] >= heights[size_t(x)]) {
        const int h = heights[size_t(stack.back())];
        stack.pop_back();
        const int left = stack.empty() ? 0 : stack.back() + 1;
        if (h > 0) visit(left, y - h + 1, x - left, h);
      }
      stack.push_back(x);
    }
    work += 2LL * cells_x;
  }
}

// --- MaxRects, for step 1 and the defragmentation ------------------------------------------

struct PackItem {
  uint32_t id;
  int w, h;  // cells
};
struct PackRect {
  int x, y, w, h;
};

bool overlaps(const PackRect& a, const PackRect& b) {
  return a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;
}
bool contains(const PackRect& outer, const PackRect& inner) {
  return inner.x >= outer.x && inner.y >= outer.y && inner.x + inner.w <= outer.x + outer.w &&
         inner.y + inner.h <= outer.y + outer.h;
}

// Cuts `placed` out of the free rectangles: each one it overlaps becomes up to four maximal
// strips around it; then rectangles inside others are dropped (they add nothing).
void split_free(std::vector<PackRect>& free, const PackRect& placed, long long& work) {
  std::vector<PackRect> next;
  next.reserve(free.size() + 8);
  for (const PackRect& f : free) {
    ++work;
    if (!overlaps(f, placed)) {
      next.push_back(f);
      continue;
    }
    if (placed.x > f.x) next.push_back({f.x, f.y, placed.x - f.x, f.h});
    if (placed.x + placed.w < f.x + f.w)
      next.push_back({placed.x + placed.w, f.y, f.x + f.w - placed.x - placed.w, f.h});
    if (placed.y > f.y) next.push_back({f.x, f.y, f.w, placed.y - f.y});
    if (placed.y + placed.h < f.y + f.h)
      next.push_back({f.x, placed.y + placed.h, f.w, f.y + f.h - placed.y - placed.h});
  }
  std::vector<bool> dropped(next.size(), false);
  for (size_t i = 0; i < next.size(); ++i) {
    for (size_t j = 0; j < next.size() && !dropped[i]; ++j) {
      ++work;
      // Of two equal rectangles the later goes, so exactly one stays.
      if (i != j && !dropped[j] && contains(next[j], next[i]) &&
          (!contains(next[i], next[j]) || j < i))
        dropped[i] = true;
    }
  }
  free.clear();
  for (size_t i = 0; i < next.size(); ++i)
    if (!dropped[i]) free.push_back(next[i]);
}

// Packs `items` in the given order with the best-short-side-fit rule; corners[i] for items[i].
bool max_rects(int cells_x, int cells_y, const std::vector<PackItem>& items,
               std::vector<PackRect>& corners, long long& work) {
  std::vector<PackRect> free = {{0, 0, cells_x, cells_y}};
  corners.assign(items.size(), {});
  for (size_t i = 0; i < items.size(); ++i) {
    const PackItem& item = items[i];
    int best = -1;
    int best_short = std::numeric_limits<int>::max(), best_long = best_short;
    for (size_t f = 0; f < free.size(); ++f) {
      ++work;
      const PackRect& r = free[f];
      if (r.w < item.w || r.h < item.h) continue;
      const int dw = r.w - item.w, dh = r.h - item.h;
      const int short_side = std::min(dw, dh), long_side = std::max(dw, dh);
      if (short_side < best_short || (short_side == best_short && long_side < best_long)) {
        best = int(f);
        best_short = short_side;
        best_long = long_side;
      }
    }
    if (best < 0) return false;
    corners[i] = {free[size_t(best)].x, free[size_t(best)].y, item.w, item.h};
    split_free(free, corners[i], work);
  }
  return true;
}

// Tries a few orders (largest side, area, height first): one usually packs what another
// cannot. Returns the corners in the order of `items`.
bool pack_cells(int cells_x, int cells_y, const std::vector<PackItem>& items,
                std::vector<PackRect>& corners, long long& work) {
  long long area = 0;
  for (const PackItem& item : items) {
    if (item.w > cells_x || item.h > cells_y) return false;
    area += (long long)item.w * item.h;
  }
  if (area > (long long)cells_x * cells_y) return false;
  using Less = bool (*)(const PackItem&, const PackItem&);
  const Less orders[] = {
      [](const PackItem& a, const PackItem& b) {
        const int a_long = std::max(a.w, a.h), b_long = std::max(b.w, b.h);
        if (a_long != b_long) return a_long > b_long;
        return std::min(a.w, a.h) > std::min(b.w, b.h);
      },
      [](const PackItem& a, const PackItem& b) { return a.w * a.h > b.w * b.h; },
      [](const PackItem& a, const PackItem& b) { return a.h != b.h ? a.h > b.h : a.w > b.w; },
  };
  std::vector<size_t> order(items.size());
  for (Less less : orders) {
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return less(items[a], items[b]); });
    std::vector<PackItem> sorted;
    for (size_t i : order) sorted.push_back(items[i]);
    std::vector<PackRect> sorted_corners;
    if (max_rects(cells_x, cells_y, sorted, sorted_corners, work)) {
      corners.assign(items.size(), {});
      for (size_t i = 0; i < order.size(); ++i) corners[order[i]] = sorted_corners[i];
      return true;
    }
  }
  return false;
}

}  // namespace

// --- DirectAtlas ---------------------------------------------------------------------------

DirectAtlas::DirectAtlas(int width, int height, Options options)
    : width_(width),
      height_(height),
      options_(options),
      limiter_(options.max_defragmentations_per_s) {
  require_positive("DirectAtlas width", width);
  require_positive("DirectAtlas height", height);
  if (options.granule < 1 || options.granule > std::min(width, height))
    throw std::invalid_argument("DirectAtlas granule = " + std::to_string(options.granule) +
                                ": must be at least 1 and at most the atlas's smaller side " +
                                std::to_string(std::min(width, height)));
  require_rate("DirectAtlas", options.defragment, options.max_defragmentations_per_s);
  cells_x_ = width / options.granule;
  cells_y_ = height / options.granule;
  used_.assign(size_t(cells_x_) * size_t(cells_y_), 0);
}

DirectAtlas::CellRect DirectAtlas::cells_of(const AtlasRect& region) const {
  return {region.x / options_.granule, region.y / options_.granule, cells_of(region.w),
          cells_of(region.h)};
}

AtlasRect DirectAtlas::allocation(const AtlasRect& region) const {
  const CellRect c = cells_of(region);
  const int g = options_.granule;
  return {c.x * g, c.y * g, c.w * g, c.h * g};
}

void DirectAtlas::fill_cells(const CellRect& c, uint8_t value, long long& work) {
  for (int y = c.y; y < c.y + c.h; ++y)
    std::fill_n(used_.begin() + ptrdiff_t(y) * cells_x_ + c.x, c.w, value);
  const long long cells = (long long)c.w * c.h;
  used_cells_ += value ? cells : -cells;
  work += cells;
}

void DirectAtlas::free_region(uint32_t id, long long& work) {
  const auto it = regions_.find(id);
  if (it == regions_.end()) return;
  fill_cells(cells_of(it->second), 0, work);
  regions_.erase(it);
}

void DirectAtlas::place(uint32_t id, const AtlasRect& region, long long& work) {
  fill_cells(cells_of(region), 1, work);
  regions_[id] = region;
}

// Scores every corner (x, y) where a cells_w x cells_h block is free by the free space around
// it: the slack to the left and right (free cells beside it in all its rows) and above and
// below (in all its columns). Best fit takes the smallest block of free space that holds it,
// (w + slack) x (h + slack); of equal ones, the position that touches a neighbour or the edge
// on each axis (the corner of its hole, not its middle); then the topmost, leftmost.
bool DirectAtlas::best_fit(int cells_w, int cells_h, CellRect& found, long long& work) {
  const int nx = cells_x_, ny = cells_y_;
  if (cells_w > nx || cells_h > ny ||
      used_cells_ + (long long)cells_w * cells_h > (long long)nx * ny)
    return false;
  const BlockSlack slack = block_slack(used_, nx, ny, cells_w, cells_h, scratch_, work);
  bool any = false;
  long long best_block = 0;
  int best_corner = 0;
  for (int y = 0; y + cells_h <= ny; ++y) {
    for (int x = 0; x + cells_w <= nx; ++x) {
      const int fits_w = slack.right_min[slack.row_major(x, y)];  // free width in all its rows
      if (fits_w < cells_w) continue;
      const int right = fits_w - cells_w;
      const int left = x > 0 ? slack.left_min[slack.row_major(x - 1, y)] : 0;
      const int down = slack.down_min[slack.column_major(x, y)] - cells_h;
      const int up = y > 0 ? slack.up_min[slack.column_major(x, y - 1)] : 0;
      const long long block = (long long)(cells_w + left + right) * (cells_h + up + down);
      const int corner = std::min(left, right) + std::min(up, down);
      if (!any || block < best_block || (block == best_block && corner < best_corner)) {
        any = true;
        best_block = block;
        best_corner = corner;
        found = {x, y, cells_w, cells_h};
      }
    }
  }
  work += (long long)(nx - cells_w + 1) * (ny - cells_h + 1);
  return any;
}

// Step 4: every free rectangle lies in one of the maximal ones, so the largest rectangle with
// the asked proportions is the largest one fitting in any maximal rectangle: the asked size
// scaled by the smaller of the two ratios, rounded down to texels.
bool DirectAtlas::largest_proportional(int width, int height, AtlasRect& found,
                                       long long& work) const {
  const int g = options_.granule;
  long long best_area = 0;
  for_each_maximal_free_rect(used_, cells_x_, cells_y_, work, [&](int x, int y, int w, int h) {
    const long long free_w = (long long)w * g, free_h = (long long)h * g;
    long long served_w, served_h;
    if (free_w * height <= free_h * width) {  // the width limits
      served_w = std::min<long long>(width, free_w);
      served_h = served_w * height / width;
    } else {
      served_h = std::min<long long>(height, free_h);
      served_w = served_h * width / height;
    }
    if (served_w < 1 || served_h < 1 || served_w * served_h <= best_area) return;
    best_area = served_w * served_h;
    found = {x * g, y * g, int(served_w), int(served_h)};
  });
  return best_area > 0;
}

// Step 3: all impostors, id at its new size, packed anew; on success they move there.
bool DirectAtlas::defragment(uint32_t id, int width, int height, long long& work) {
  std::vector<PackItem> items;
  items.reserve(regions_.size() + 1);
  for (const auto& [other, region] : regions_)
    items.push_back({other, cells_of(region.w), cells_of(region.h)});
  items.push_back({id, cells_of(width), cells_of(height)});
  std::vector<PackRect> corners;
  if (!pack_cells(cells_x_, cells_y_, items, corners, work)) return false;

  const int g = options_.granule;
  moves_.clear();
  std::fill(used_.begin(), used_.end(), 0);
  used_cells_ = 0;
  work += (long long)used_.size();
  for (size_t i = 0; i < items.size(); ++i) {
    const uint32_t other = items[i].id;
    const bool is_new = other == id;
    AtlasRect to = {corners[i].x * g, corners[i].y * g, is_new ? width : regions_[other].w,
                    is_new ? height : regions_[other].h};
    if (!is_new && !(to == regions_[other])) moves_.push_back({other, regions_[other], to});
    place(other, to, work);
  }
  return true;
}

bool DirectAtlas::pack(const std::vector<Request>& requests) {
  if (!regions_.empty())
    throw std::logic_error("DirectAtlas::pack: the atlas must be empty (it holds " +
                           std::to_string(regions_.size()) + " impostors)");
  std::vector<PackItem> items;
  std::map<uint32_t, int> seen;
  for (const Request& r : requests) {
    require_positive("DirectAtlas::pack width", r.width);
    require_positive("DirectAtlas::pack height", r.height);
    if (seen[r.id]++)
      throw std::invalid_argument("DirectAtlas::pack id = " + std::to_string(r.id) +
                                  ": appears more than once; ids must be unique");
    items.push_back({r.id, cells_of(r.width), cells_of(r.height)});
  }
  long long work = 0;
  std::vector<PackRect> corners;
  if (!pack_cells(cells_x_, cells_y_, items, corners, work)) return false;
  const int g = options_.granule;
  for (size_t i = 0; i < requests.size(); ++i)
    place(requests[i].id,
          {corners[i].x * g, corners[i].y * g, requests[i].width, requests[i].height}, work);
  return true;
}

DirectAtlas::Result DirectAtlas::allocate(uint32_t id, int width, int height, double now_s) {
  require_positive("DirectAtlas::allocate width", width);
  require_positive("DirectAtlas::allocate height", height);
  log_.observe(now_s);
  const Clock::time_point start = Clock::now();
  long long work = 0;
  free_region(id, work);

  Result result;
  const int g = options_.granule;
  const int cells_w = cells_of(width), cells_h = cells_of(height);
  bool tried_defragmentation = false;
  CellRect cells;
  if (best_fit(cells_w, cells_h, cells, work)) {
    place(id, {cells.x * g, cells.y * g, width, height}, work);
    result.ok = true;
  } else {
    // A repack cannot succeed with too little free area in total; such a call would only
    // spend the rate limit's allowance.
    const long long free_cells = (long long)used_.size() - used_cells_;
    const bool could_fit =
        cells_w <= cells_x_ && cells_h <= cells_y_ && (long long)cells_w * cells_h <= free_cells;
    if (options_.defragment && could_fit && limiter_.allows(now_s)) {
      limiter_.record(now_s);
      ++defragmentations_;
      tried_defragmentation = true;
      if (defragment(id, width, height, work)) {
        result.ok = result.defragmented = true;
      } else {
        ++failed_defragmentations_;
      }
    }
  }
  if (!result.ok) {
    AtlasRect smaller;
    if (largest_proportional(width, height, smaller, work)) {
      place(id, smaller, work);
      result.ok = result.downsized = true;
      ++downsized_;
    } else {
      ++failed_;
    }
  }
  if (result.ok) result.rect = regions_.at(id);
  log_.record(start, work, tried_defragmentation);
  return result;
}

void DirectAtlas::release(uint32_t id) {
  const Clock::time_point start = Clock::now();
  long long work = 0;
  free_region(id, work);
  log_.record(start, work, false);
}

bool DirectAtlas::can_fit(int width, int height) const {
  require_positive("DirectAtlas::can_fit width", width);
  require_positive("DirectAtlas::can_fit height", height);
  const int cells_w = cells_of(width), cells_h = cells_of(height);
  bool fits = false;
  long long work = 0;
  for_each_maximal_free_rect(used_, cells_x_, cells_y_, work, [&](int, int, int w, int h) {
    fits = fits || (w >= cells_w && h >= cells_h);
  });
  return fits;
}

AtlasStats DirectAtlas::stats() const {
  AtlasStats s;
  const double atlas = double(width_) * double(height_);
  const double cell = double(options_.granule) * double(options_.granule);
  long long held = 0;
  for (const auto& [id, region] : regions_) held += (long long)region.w * region.h;
  const long long free_cells = (long long)used_.size() - used_cells_;
  s.occupancy = double(held) / atlas;
  s.wasted = (double(used_cells_) * cell - double(held)) / atlas;
  s.free = double(free_cells) * cell / atlas;
  s.unusable = (atlas - double(used_.size()) * cell) / atlas;
  long long largest = 0, work = 0;
  for_each_maximal_free_rect(used_, cells_x_, cells_y_, work, [&](int, int, int w, int h) {
    largest = std::max(largest, (long long)w * h);
  });
  s.fragmentation = free_cells > 0 ? 1.0 - double(largest) / double(free_cells) : 0.0;
  s.defragmentations = defragmentations_;
  s.failed_defragmentations = failed_defragmentations_;
  s.downsized = downsized_;
  s.failed = failed_;
  log_.fill(s);
  return s;
}

}  // namespace nephele::particles

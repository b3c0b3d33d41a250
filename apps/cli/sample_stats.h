// nephele CLI — order statistics of timing samples, shared by the benchmarks and the gallery.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace nephele::cli {

// The median (the mean of the middle two for an even count); 0 for no samples.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The q-quantile (0 < q <= 1) of `v` by the nearest-rank method: the smallest value with at
// least a share q of the values at or below it (q = 1: the maximum); 0 for no samples.
inline double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t rank = size_t(std::ceil(q * double(v.size())));
  return v[std::clamp<size_t>(rank, 1, v.size()) - 1];
}

}  // namespace nephele::cli

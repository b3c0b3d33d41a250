// `nephele bench`: the seed's frame-rate study (seed 000, section 4) for both march modes.
#pragma once

#include <string>

#include "scene_flags.h"

namespace CLI {
class App;
}

namespace nephele::cli {

struct BenchOptions {
  SceneFlags scene;
  std::string out_dir = "bench-out";  // CSV, JSON and plot go here
  int frames = 3;                     // timed frames per configuration (one warm-up per mode)
  bool quick = false;                 // fewer points, small resolutions (for tests)
  bool realtime_only = false;         // skip the seed's sweeps
  bool ablation = false;              // only seed 002's voxel-cloud ablation
  bool impostors = false;             // only seed 003's particle clouds and impostors
  bool no_error = false;              // real time: no comparison with the reference
  bool full_shaders = false;          // RendererOptions::feature_variants off
  std::string json;                   // also write the real-time figures here
  std::string device;
  bool verbose = false;
  bool validation = false;
  bool progress = false;  // a progress line on standard error even when it is not a terminal
  bool quiet = false;     // no progress
};

void add_bench_flags(CLI::App& cmd, BenchOptions& options);
int run_bench(const BenchOptions& options);

}  // namespace nephele::cli

#include "bench.h"

#include <CLI/CLI.hpp>

#include "nephele/error.h"
#include "render_command.h"

namespace nephele::cli {

void add_bench_flags(CLI::App& cmd, BenchOptions& options) {
  add_scene_flags(cmd, options.scene);
  cmd.add_option("--out-dir", options.out_dir, "folder for bench.csv, bench.json, bench.png")
      ->capture_default_str();
  cmd.add_option("--frames", options.frames, "timed frames per configuration")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd.add_flag("--quick", options.quick, "a few small configurations only");
  add_device_flags(cmd, options.device, options.verbose, options.validation);
}

int run_bench(const BenchOptions&) { throw RuntimeError("bench: not implemented yet"); }

}  // namespace nephele::cli

// `nephele bench`'s figures, drawn by scripts/plot_bench.py (matplotlib) from bench.json.
#pragma once

#include <string>
#include <vector>

namespace nephele::cli {

// The interpreter that runs the script: Debian's, which sees Debian's matplotlib
// (python3-matplotlib) whatever python3 comes first on PATH.
inline constexpr const char* kPlotPython = "/usr/bin/python3";

struct BenchPlots {
  enum class Outcome {
    kDrawn,    // the script ran; `files` lists what it wrote
    kSkipped,  // no interpreter or no matplotlib: nothing was drawn
    kFailed,   // the script failed
  };
  Outcome outcome = Outcome::kFailed;
  std::vector<std::string> files;  // the PNGs written (bench.png, bench_frame_times.png)
  std::string reason;              // why skipped or failed, one line
};

// Runs the copy of scripts/plot_bench.py embedded in the binary with `python` on `bench_json`,
// writing its PNGs into `out_dir` (an existing folder). Never throws for what the script or
// the interpreter does: a benchmark's data stays valid without its plots.
BenchPlots draw_bench_plots(const std::string& bench_json, const std::string& out_dir,
                            const std::string& python = kPlotPython);

}  // namespace nephele::cli

// `nephele validate`: the fast mode against the reference path tracer on a suite of views
// with their tolerances kept as data (data/validation.toml; issue 21).
#pragma once

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace nephele::cli {

// One view of a suite: a scene (TOML, as a scene file) and its tolerance.
struct ValidationView {
  std::string name;
  std::string description;
  std::string scene_toml;
  double max_mean_error = 0.05;  // of BlockLuminanceError::mean_error
  double max_block_error = 0.0;  // of BlockLuminanceError::max_lit_error; 0: none
};

// The clear sky's targets (`validate --sky`; the [sky] table of data/validation.toml).
struct SkyTargets {
  std::vector<double> sun_elevations_deg;
  double max_pattern_mean = 0.02;
  double max_pattern_horizon = 0.05;
  double max_colour_ratio = 0.03;
  double max_zenith_jump = 0.01;
};

struct ValidationSuite {
  int width = 160, height = 100;  // pixels of every view
  int block = 8;                  // pixels per side of the blocks compared
  std::vector<ValidationView> views;
  SkyTargets sky;
};

// Parses a suite (the format of data/validation.toml); `source` names it in errors. Throws
// InputError with one line naming the key, the value and what is allowed.
ValidationSuite parse_validation_suite(const std::string& text, const std::string& source);
// The suite nephele ships (data/validation.toml, embedded).
ValidationSuite default_validation_suite();

struct ValidateOptions {
  std::string suite;       // a suite file; "" the shipped one
  std::string views;       // comma-separated names to run; "" all
  bool sky = false;        // the clear sky's targets instead of the views
  int width = 0, height = 0;  // 0: the suite's
  int spp = 1024;          // the reference's samples per pixel
  double time_limit_s = 0.0;  // per view's reference (0: none)
  std::string references;  // a folder of references (name.exr): read when there, else written
  std::string out_dir = "validation";  // images per view, the table, the JSON
  std::string json;        // also write the results here
  std::string device;
  bool verbose = false;
  bool validation = false;
  bool progress = false;
  bool quiet = false;
};

void add_validate_flags(CLI::App& cmd, ValidateOptions& options);
// 0 when every view is within its tolerance, 1 when one is not (or validation messages).
int run_validate(const ValidateOptions& options);

}  // namespace nephele::cli

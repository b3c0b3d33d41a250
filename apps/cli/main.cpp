// nephele — command-line tool: render a scene to PNG/EXR, run the benchmark, render the preset gallery, list presets, make voxel clouds.
#include <sys/resource.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "bench.h"
#include "gallery.h"
#include "nephele/error.h"
#include "nephele/version.h"
#include "nephele/output_file.h"
#include "nephele/scene_io.h"
#include "render_command.h"
#include "scene_reference.h"
#include "validate.h"
#include "voxel_commands.h"

namespace {

// Errors are one line of at most kMaxLineChars: each part of a message is already short
// (shorten_for_message), but a message from a library (CLI11's echo values whole) may not be.
void print_error(const std::string& kind, const std::string& message, const std::string& suffix = "") {
  constexpr size_t kMaxLineChars = 1000;
  const std::string prefix = "nephele: " + kind + ": ";
  const size_t room = kMaxLineChars - prefix.size() - suffix.size();
  // Control characters, bidirectional overrides and bytes that are not UTF-8 as '?'.
  std::string text = nephele::one_line_for_message(message);
  if (text.size() > room) text = text.substr(0, room - 3) + "...";
  std::fprintf(stderr, "%s%s%s\n", prefix.c_str(), text.c_str(), suffix.c_str());
}

// Edits (insertions, deletions, substitutions, swaps of neighbours) from a to b.
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1,
                          d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

// " (did you mean --coverage?)" for the first `--flag` on the command line that the command
// does not know and that is a few edits from one it does; "" otherwise.
std::string flag_suggestion(const CLI::App& app, int argc, char** argv) {
  const CLI::App* command = &app;
  for (const CLI::App* sub : app.get_subcommands({})) {
    for (int i = 1; i < argc; ++i)
      if (sub->get_name() == argv[i]) command = sub;
  }
  std::vector<std::string> known;
  for (const CLI::Option* option : command->get_options())
    for (const std::string& name : option->get_lnames()) known.push_back("--" + name);
  for (int i = 1; i < argc; ++i) {
    std::string typed = argv[i];
    if (!typed.starts_with("--")) continue;
    typed = typed.substr(0, typed.find('='));
    if (std::find(known.begin(), known.end(), typed) != known.end()) continue;
    std::string best;
    size_t best_distance = std::max<size_t>(2, typed.size() / 4) + 1;
    for (const std::string& name : known)
      if (const size_t d = edit_distance(typed, name); d < best_distance) best = name, best_distance = d;
    if (!best.empty()) return " (did you mean " + best + "?)";
  }
  return "";
}

// `--verbose`: the process's peak resident memory, which on a CPU driver (lavapipe) holds the
// device's memory too.
void print_peak_memory(const CLI::App& app) {
  for (const CLI::App* command : app.get_subcommands()) {
    const CLI::Option* verbose = command->get_option_no_throw("--verbose");
    if (!verbose || verbose->count() == 0) continue;
    rusage usage = {};
    if (getrusage(RUSAGE_SELF, &usage) == 0)
      std::fprintf(stderr, "nephele: peak resident memory %.0f MiB\n", usage.ru_maxrss / 1024.0);
  }
}

int run_command(const CLI::App& app, int status) {
  print_peak_memory(app);
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"nephele: physically based skies and volumetric clouds, rendered with Vulkan"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("nephele ") + nephele::kVersion);

  nephele::cli::RenderOptions render;
  CLI::App* render_cmd = app.add_subcommand(
      "render", "render a frame, a sequence (--frames) or a flight (--camera-path) to images");
  nephele::cli::add_render_flags(*render_cmd, render);

  nephele::cli::BenchOptions bench;
  CLI::App* bench_cmd = app.add_subcommand(
      "bench", "frame rate against density, coverage and resolution (seed 000 section 4)");
  nephele::cli::add_bench_flags(*bench_cmd, bench);

  nephele::cli::GalleryOptions gallery;
  CLI::App* gallery_cmd = app.add_subcommand(
      "gallery", "the sky-cover presets (clear to overcast, stratus, storm, cirrus, sunset) side by side, labelled with their measured oktas; with --classic, the classical cloud models of seed 004 and nephele's on one scene, labelled with their frame times");
  nephele::cli::add_gallery_flags(*gallery_cmd, gallery);

  nephele::cli::ValidateOptions validate;
  CLI::App* validate_cmd = app.add_subcommand(
      "validate", "the fast mode against the reference path tracer on a suite of views, each "
                  "with its tolerance (data/validation.toml)");
  nephele::cli::add_validate_flags(*validate_cmd, validate);

  CLI::App* presets_cmd = app.add_subcommand("presets", "list the built-in scene presets: a name and what it shows a line");

  CLI::App* keys_cmd = app.add_subcommand(
      "keys", "print the scene reference (Markdown): every scene key with its unit, allowed "
              "values, default, flag and meaning, as docs/scene-reference.md holds it");

  nephele::cli::MakeCloudOptions make_cloud;
  CLI::App* make_cloud_cmd = app.add_subcommand(
      "make-cloud", "generate a voxel cloud (cumulus, congestus, cumulonimbus) as OpenVDB");
  nephele::cli::add_make_cloud_flags(*make_cloud_cmd, make_cloud);

  nephele::cli::VoxelizeOptions voxelize;
  CLI::App* voxelize_cmd = app.add_subcommand(
      "voxelize", "bake a closed OBJ mesh into a voxel cloud (OpenVDB) with eroded edges");
  nephele::cli::add_voxelize_flags(*voxelize_cmd, voxelize);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    print_error("error", e.what(), flag_suggestion(app, argc, argv) + " (see nephele --help)");
    return 2;
  }

  // An interrupted write leaves no temporary file behind.
  nephele::install_temporary_file_cleanup();
  try {
    if (render_cmd->parsed()) return run_command(app, nephele::cli::run_render(render));
    if (bench_cmd->parsed()) return run_command(app, nephele::cli::run_bench(bench));
    if (validate_cmd->parsed()) return run_command(app, nephele::cli::run_validate(validate));
    if (gallery_cmd->parsed()) return run_command(app, nephele::cli::run_gallery(gallery));
    if (make_cloud_cmd->parsed()) return run_command(app, nephele::cli::run_make_cloud(make_cloud));
    if (voxelize_cmd->parsed()) return run_command(app, nephele::cli::run_voxelize(voxelize));
    if (keys_cmd->parsed()) {
      std::fputs(nephele::cli::scene_reference_markdown().c_str(), stdout);
      return 0;
    }
    if (presets_cmd->parsed()) {
      // A name a line, as scripts read it, then what the preset shows.
      for (const std::string& name : nephele::preset_names())
        std::printf("%-20s %s\n", name.c_str(), nephele::preset_description(name).c_str());
      return 0;
    }
  } catch (const nephele::InputError& e) {
    print_error("error", e.what());
    return 2;
  } catch (const std::exception& e) {
    print_error("failed", e.what());
    return 1;
  }
  return 0;
}

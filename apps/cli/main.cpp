// nephele — command-line tool: render a scene to PNG/EXR, run the benchmark, render the preset gallery, list presets, make voxel clouds.
#include <sys/resource.h>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>

#include "bench.h"
#include "gallery.h"
#include "nephele/error.h"
#include "nephele/version.h"
#include "nephele/output_file.h"
#include "nephele/scene_io.h"
#include "render_command.h"
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

  CLI::App* presets_cmd = app.add_subcommand("presets", "list the built-in scene presets");

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
    print_error("error", e.what(), " (see nephele --help)");
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
    if (presets_cmd->parsed()) {
      for (const std::string& name : nephele::preset_names()) std::cout << name << "\n";
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

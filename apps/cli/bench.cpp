// `nephele bench`: seed 000's frame-rate study (section 4) — frames per second against cloud
// density and coverage over their whole ranges and against resolution 640x360 ... 3840x2160 —
// for the default march and the seed's algorithm as written (`baseline`), in one run, so
// speed-ups are ratios measured on the same machine at the same time. The data goes to
// bench.csv and bench.json; scripts/plot_bench.py draws the figures from bench.json.
#include "bench.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "nephele/error.h"
#include "nephele/output_file.h"
#include "nephele/renderer.h"
#include "bench_ablation.h"
#include "bench_impostors.h"
#include "bench_plot.h"
#include "bench_realtime.h"
#include "progress.h"
#include "render_command.h"

namespace nephele::cli {

namespace {

struct Sample {
  std::string sweep;  // "density", "coverage" or "resolution"
  MarchMode mode;
  float density, coverage;
  int width, height;
  double gpu_ms, wall_ms;
  double fps() const { return 1000.0 / gpu_ms; }
};

// Mean GPU time of `frames` animation frames after one warm-up (the device's timestamps;
// wall time alongside): the default mode marches 1 / march_stride^2 of its pixels per frame.
Sample measure(Renderer& renderer, Scene scene, const std::string& sweep, int frames) {
  double gpu = 0.0, wall = 0.0;
  renderer.render_next(scene, false);
  for (int i = 0; i < frames; ++i) {
    const FrameStats stats = renderer.render_next(scene, false).stats;
    gpu += stats.frame_ms;
    wall += stats.wall_ms;
  }
  return {sweep,
          scene.quality.mode,
          scene.clouds.density,
          scene.clouds.coverage,
          scene.output.width,
          scene.output.height,
          gpu / frames,
          wall / frames};
}

std::vector<float> sweep_values(bool quick) {
  std::vector<float> v;
  const int n = quick ? 2 : 8;
  for (int i = 0; i <= n; ++i) v.push_back(float(i) / float(n));
  return v;
}

std::vector<std::pair<int, int>> resolutions(bool quick) {
  if (quick) return {{64, 36}, {128, 72}};
  return {{640, 360}, {800, 480}, {900, 600}, {1280, 720}, {1920, 1080}, {3840, 2160}};
}

std::string to_csv(const std::vector<Sample>& samples) {
  std::ostringstream out;
  out << "sweep,mode,density,coverage,width,height,gpu_ms,fps,wall_ms\n";
  for (const Sample& s : samples)
    out << s.sweep << ',' << to_string(s.mode) << ',' << s.density << ',' << s.coverage << ','
        << s.width << ',' << s.height << ',' << s.gpu_ms << ',' << s.fps() << ',' << s.wall_ms
        << '\n';
  return out.str();
}

// The CSV's rows as JSON objects (bench.json's "sweeps"), so that the JSON alone holds
// every figure scripts/plot_bench.py draws.
nlohmann::json to_json(const std::vector<Sample>& samples) {
  nlohmann::json rows = nlohmann::json::array();
  for (const Sample& s : samples)
    rows.push_back({{"sweep", s.sweep},
                    {"mode", to_string(s.mode)},
                    {"density", s.density},
                    {"coverage", s.coverage},
                    {"width", s.width},
                    {"height", s.height},
                    {"gpu_ms", s.gpu_ms},
                    {"fps", s.fps()},
                    {"wall_ms", s.wall_ms}});
  return rows;
}

// Draws the figures from bench.json. A missing interpreter or matplotlib, or a failing
// script, is reported in one line and does not fail the benchmark: its data is written.
void draw_plots(const std::string& json, const std::string& out_dir) {
  const BenchPlots plots = draw_bench_plots(json, out_dir);
  for (const std::string& file : plots.files) std::printf("%s\n", file.c_str());
  if (plots.outcome == BenchPlots::Outcome::kSkipped)
    std::fprintf(stderr,
                 "nephele: plot skipped: %s; draw it later with %s scripts/plot_bench.py %s %s "
                 "(from nephele's source tree)\n",
                 plots.reason.c_str(), kPlotPython, json.c_str(), out_dir.c_str());
  else if (plots.outcome == BenchPlots::Outcome::kFailed)
    std::fprintf(stderr, "nephele: plot not drawn: %s; the data is in %s\n", plots.reason.c_str(),
                 json.c_str());
  std::fflush(stdout);
}

}  // namespace

void add_bench_flags(CLI::App& cmd, BenchOptions& options) {
  add_scene_flags(cmd, options.scene);
  cmd.add_option("--out-dir", options.out_dir,
                 "folder for bench.csv, bench.json and the plots bench.png, "
                 "bench_frame_times.png (drawn by scripts/plot_bench.py when /usr/bin/python3 "
                 "has matplotlib)")
      ->capture_default_str();
  cmd.add_option("--frames", options.frames, "timed frames per configuration")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd.add_flag("--quick", options.quick, "a few small configurations only");
  cmd.add_flag("--realtime-only", options.realtime_only,
               "only the real-time figures (still and flying camera, error, speed-up)");
  cmd.add_flag("--ablation", options.ablation,
               "only seed 002's ablation: a voxel-heavy view with the plain march and a light "
               "march (the seed's baseline), the SDF march, SDF shadows and both; writes "
               "ablation.png to --out-dir and, with --json, baseline_ms, sdf_march_ms, "
               "sdf_shadow_ms, sdf_both_ms, speedup_sdf_march, speedup_sdf_both, "
               "max_luminance_difference");
  cmd.add_flag("--impostors", options.impostors,
               "only seed 003's particle clouds: a flight drawing every particle against "
               "impostors in a direct and a tiled atlas; writes impostors.png to --out-dir and, "
               "with --json, all_particles_ms, impostors_direct_ms, impostors_tiles_ms, "
               "speedup_direct, speedup_tiles, luminance_difference, cpu_lighting_ms, "
               "gpu_lighting_ms (the same splat on the device) and the atlas statistics "
               "(--frames: the timed frames, default 3)");
  cmd.add_flag("--no-error", options.no_error,
               "time the real-time frames only: no comparison with the converged reference "
               "(the error columns, which take minutes at 900x600 on a CPU device)");
  cmd.add_flag("--full-shaders", options.full_shaders,
               "run every pass's full shader rather than the variant compiled for the scene's "
               "features (RendererOptions::feature_variants off): what the variants save");
  cmd.add_option("--json", options.json,
                 "write the real-time figures (static_fps, moving_fps, static_p99_ms, "
                 "moving_p99_ms, moving_max_ms, speedup_vs_baseline, cost_vs_seed_lit, "
                 "cost_vs_seed_lighting, cost_of_rain, rain_p99_ms, storm_p99_over_median, "
                 "cost_of_three_layers, static_error, "
                 "moving_error, "
                 "frame_times_ms, device, "
                 "...) to this file, or to standard output with -");
  add_device_flags(cmd, options.device, options.verbose, options.validation);
  add_progress_flags(cmd, options.progress, options.quiet);
}

namespace {

std::string pass_list(const nlohmann::json& passes) {
  std::string s;
  for (const auto& [name, ms] : passes.items()) {
    char item[64];
    std::snprintf(item, sizeof item, "%s%s %.1f", s.empty() ? "" : ", ", name.c_str(),
                  ms.get<double>());
    s += item;
  }
  return s;
}

void print_realtime(const nlohmann::json& r) {
  std::printf("real time %dx%d on %s (host wall time per frame, weather evolving)\n"
              "  %-14s %8s %8s %8s %8s %7s %7s  %s\n",
              r["width"].get<int>(), r["height"].get<int>(),
              r["device"].get<std::string>().c_str(), "", "median", "p95", "p99", "max",
              "fps", "error", "rebuild frames (light volume, weather)");
  for (const char* series : {"static", "moving", "rain", "storm", "layers"}) {
    const std::string p = series;
    if (!r.contains(p + "_ms")) continue;
    char error[16] = "      -";  // not measured (--no-error)
    if (r.contains(p + "_error") && !r[p + "_error"].is_null())
      std::snprintf(error, sizeof error, "%6.2f%%", 100.0 * r[p + "_error"].get<double>());
    std::printf("  %-14s %8.1f %8.1f %8.1f %8.1f %7.2f %s  %d, %d of %d\n",
                p == "static"   ? "still camera"
                : p == "moving" ? "flying camera"
                : p == "rain"   ? "in heavy rain"
                : p == "storm"  ? "thunderstorm"
                                : "three layers",
                r[p + "_ms"].get<double>(), r[p + "_p95_ms"].get<double>(),
                r[p + "_p99_ms"].get<double>(), r[p + "_max_ms"].get<double>(),
                r[p + "_fps"].get<double>(), error, r[p + "_light_volume_frames"].get<int>(),
                r[p + "_weather_frames"].get<int>(), r[p + "_frames"].get<int>());
  }
  std::printf("  flight %g m/s, %g deg/s; seed's algorithm: %.1f ms (%.2f fps); speed-up %.1fx\n",
              r["flight"]["speed_mps"].get<double>(), r["flight"]["turn_deg_s"].get<double>(),
              r["baseline_ms"].get<double>(), r["baseline_fps"].get<double>(),
              r["speedup_vs_baseline"].get<double>());
  std::printf(
      "  the still camera lit as the seed lights clouds (its lighting and optics, 6 light "
      "steps, no light shafts): %.1f ms; the default costs %.2fx that\n"
      "  the same with the default's droplets (the seed's lighting alone): %.1f ms; the "
      "default costs %.2fx that\n",
      r["seed_lit_ms"].get<double>(), r["cost_vs_seed_lit"].get<double>(),
      r["seed_lighting_ms"].get<double>(), r["cost_vs_seed_lighting"].get<double>());
  std::printf(
      "  the still camera in heavy rain (20 mm/h everywhere): %.2fx its cost (target <= 1.2 "
      "on lavapipe)\n",
      r["cost_of_rain"].get<double>());
  if (r.contains("storm_p99_over_median"))
    std::printf(
        "  the still camera in a thunderstorm (30 flashes a minute a cell): p99 %.2fx its "
        "median (target <= 2)\n",
        r["storm_p99_over_median"].get<double>());
  if (r.contains("cost_of_three_layers"))
    std::printf(
        "  the still camera under three volumetric layers (two more from [[cloud_layers]]): "
        "%.2fx its cost (target <= 1.5)\n",
        r["cost_of_three_layers"].get<double>());
  if (r.contains("flight_from_still")) {
    const std::vector<double> e = r["flight_from_still"].get<std::vector<double>>();
    const size_t worst = size_t(std::max_element(e.begin(), e.end()) - e.begin());
    std::printf(
        "  flight from a still, against stills of its frames: frame 1 %.2f%%, frame %zu "
        "%.2f%%, worst %.2f%% (frame %zu): %.2fx the last ten's mean (target <= 2)\n",
        100.0 * e.front(), e.size(), 100.0 * e.back(), 100.0 * e[worst], worst + 1,
        r["flight_from_still_ratio"].get<double>());
  }
  std::printf("  passes, still (ms):  %s\n  passes, flying (ms): %s\n",
              pass_list(r["static_passes_ms"]).c_str(), pass_list(r["moving_passes_ms"]).c_str());
  std::fflush(stdout);
}

// The number of configurations run_sweeps measures.
int sweep_count(bool quick) {
  return 2 * int(2 * sweep_values(quick).size() + resolutions(quick).size());
}

// The seed's study: both modes over density, coverage and resolution.
std::vector<Sample> run_sweeps(Renderer& renderer, const Scene& base, const BenchOptions& options,
                               Progress& progress) {
  std::printf("%-10s %-8s %7s %8s %11s %10s %8s\n", "sweep", "mode", "density", "coverage",
              "resolution", "gpu ms", "fps");
  std::vector<Sample> samples;
  auto record = [&](const Scene& scene, const std::string& sweep) {
    samples.push_back(measure(renderer, scene, sweep, options.frames));
    const Sample& s = samples.back();
    progress.clear();
    std::printf("%-10s %-8s %7.3f %8.3f %5dx%-5d %10.1f %8.3f\n", s.sweep.c_str(),
                to_string(s.mode), s.density, s.coverage, s.width, s.height, s.gpu_ms, s.fps());
    std::fflush(stdout);
    progress.advance();
  };
  for (MarchMode mode : {MarchMode::Default, MarchMode::Baseline}) {
    Scene scene = base;
    scene.quality.mode = mode;
    for (float d : sweep_values(options.quick)) {
      Scene s = scene;
      s.clouds.density = d;
      record(s, "density");
    }
    for (float c : sweep_values(options.quick)) {
      Scene s = scene;
      s.clouds.coverage = c;
      record(s, "coverage");
    }
    for (auto [w, h] : resolutions(options.quick)) {
      Scene s = scene;
      s.output.width = w;
      s.output.height = h;
      record(s, "resolution");
    }
  }
  return samples;
}

// A study run alone (--ablation, --impostors): its image `image_name` in --out-dir, checked
// before anything is rendered, its figures to --json.
template <typename Study>
int run_study(const BenchOptions& options, const char* image_name, Study study) {
  namespace fs = std::filesystem;
  const std::string image = (fs::path(options.out_dir) / image_name).string();
  std::error_code ec;
  fs::create_directories(options.out_dir, ec);
  check_output_path(image, "--out-dir");
  if (!options.json.empty()) {
    check_output_file(options.json, "--json", true);
    check_distinct_outputs({{"--out-dir", image}, {"--json", options.json}});
  }
  const nlohmann::json result = study(image);
  if (!options.json.empty()) write_text_output(options.json, result.dump(2) + "\n");
  return 0;
}

}  // namespace

int run_bench(const BenchOptions& options) {
  const Scene base = resolve_scene(options.scene);
  namespace fs = std::filesystem;
  RendererOptions renderer_options{options.device, options.validation, options.verbose, {}};
  renderer_options.feature_variants = !options.full_shaders;
  if (options.ablation)  // seed 002's ablation alone
    return run_study(options, "ablation.png", [&](const std::string& image) {
      Renderer renderer(renderer_options);
      return run_ablation(renderer, ablation_scene(base), std::max(options.frames, 1), image);
    });
  if (options.impostors)  // seed 003's particle clouds and impostors alone
    return run_study(options, "impostors.png", [&](const std::string& image) {
      return run_impostor_bench(renderer_options, impostor_bench_scene(base),
                                std::max(options.frames, 2), image);
    });
  const std::string csv = (fs::path(options.out_dir) / "bench.csv").string();
  const std::string json = (fs::path(options.out_dir) / "bench.json").string();
  // The figures scripts/plot_bench.py draws; removed before it runs, so that those left
  // match bench.json (a trace is drawn only when the JSON has frame times).
  const std::string png = (fs::path(options.out_dir) / "bench.png").string();
  const std::string trace_png = (fs::path(options.out_dir) / "bench_frame_times.png").string();
  // The folder first: --json may name a file in it.
  std::error_code ec;
  if (!options.realtime_only) fs::create_directories(options.out_dir, ec);
  if (!options.json.empty()) check_output_file(options.json, "--json", true);
  if (!options.realtime_only) {
    for (const std::string& p : {csv, json}) check_output_file(p, "--out-dir");
    for (const std::string& p : {png, trace_png}) check_output_path(p, "--out-dir");
    if (!options.json.empty())
      check_distinct_outputs({{"--out-dir", csv},
                              {"--out-dir", json},
                              {"--out-dir", png},
                              {"--out-dir", trace_png},
                              {"--json", options.json}});
  }

  Renderer renderer(renderer_options);
  std::printf("nephele bench on %s, scene %dx%d\n", renderer.device_name().c_str(),
              base.output.width, base.output.height);
  renderer.render(base);  // builds the noise and weather textures

  RealtimeSettings settings;
  settings.errors = !options.no_error;
  if (options.quick) {
    settings.static_frames = settings.moving_frames = 8;
    settings.error_frames = 1;
    settings.still_flight_frames = 3;
  }
  // One step a measured frame of the real-time part (its error frames print a line each: the
  // bar makes way for them) and one a configuration of the sweeps.
  const int timed_steps = std::max(settings.static_frames, settings.moving_frames);
  Progress progress("bench",
                    timed_steps + settings.error_frames +
                        (options.realtime_only ? 0 : sweep_count(options.quick)),
                    progress_wanted(options.progress, options.quiet, options.verbose));
  settings.on_step = [&progress, timed_steps, steps = 0]() mutable {
    progress.advance();
    if (++steps > timed_steps) progress.clear();
  };
  const nlohmann::json realtime = measure_realtime(renderer, renderer_options, base, settings);
  progress.clear();
  print_realtime(realtime);
  if (!options.json.empty()) write_text_output(options.json, realtime.dump(2) + "\n");
  if (options.realtime_only) return 0;

  const std::vector<Sample> samples = run_sweeps(renderer, base, options, progress);
  progress.finish();
  nlohmann::json summary = realtime;
  summary["frames_per_point"] = options.frames;
  summary["sweeps"] = to_json(samples);
  write_text_output(csv, to_csv(samples));
  write_text_output(json, summary.dump(2) + "\n");
  std::printf("%s\n%s\n", csv.c_str(), json.c_str());
  for (const std::string& p : {png, trace_png}) fs::remove(p, ec);
  draw_plots(json, options.out_dir);
  return 0;
}

}  // namespace nephele::cli

// `nephele bench`: seed 000's frame-rate study (section 4) — frames per second against cloud
// density and coverage over their whole ranges and against resolution 640x360 ... 3840x2160 —
// for the default march and the seed's algorithm as written (`baseline`), in one run, so
// speed-ups are ratios measured on the same machine at the same time.
#include "bench.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "nephele/error.h"
#include "nephele/renderer.h"
#include "plot.h"
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

// Mean GPU time of `frames` frames (the device's timestamps; wall time alongside).
Sample measure(Renderer& renderer, Scene scene, const std::string& sweep, int frames) {
  double gpu = 0.0, wall = 0.0;
  for (int i = 0; i < frames; ++i) {
    const FrameStats stats = renderer.render(scene).stats;
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

PlotSpec panel(const std::vector<Sample>& samples, const std::string& sweep,
               const std::string& title, const std::string& x_label) {
  PlotSpec spec;
  spec.title = title;
  spec.x_label = x_label;
  spec.y_label = "frames per second";
  spec.log_y = true;
  spec.width = 640;
  spec.height = 440;
  for (MarchMode mode : {MarchMode::Default, MarchMode::Baseline}) {
    PlotSeries series{to_string(mode), {}, {}};
    for (const Sample& s : samples) {
      if (s.sweep != sweep || s.mode != mode) continue;
      series.x.push_back(sweep == "density"    ? s.density
                         : sweep == "coverage" ? s.coverage
                                               : s.width * s.height * 1e-6);
      series.y.push_back(s.fps());
    }
    spec.series.push_back(series);
  }
  return spec;
}

}  // namespace

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

int run_bench(const BenchOptions& options) {
  const Scene base = resolve_scene(options.scene);
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(options.out_dir, ec);
  const std::string csv = (fs::path(options.out_dir) / "bench.csv").string();
  const std::string json = (fs::path(options.out_dir) / "bench.json").string();
  const std::string png = (fs::path(options.out_dir) / "bench.png").string();
  for (const std::string& p : {csv, json}) check_writable_file(p, "--out-dir");
  check_output_path(png, "--out-dir");

  Renderer renderer({options.device, options.validation, options.verbose});
  std::printf("nephele bench on %s, scene %dx%d, %d frame(s) per point\n",
              renderer.device_name().c_str(), base.output.width, base.output.height,
              options.frames);
  std::printf("%-10s %-8s %7s %8s %11s %10s %8s\n", "sweep", "mode", "density", "coverage",
              "resolution", "gpu ms", "fps");
  std::vector<Sample> samples;
  auto record = [&](const Scene& scene, const std::string& sweep) {
    samples.push_back(measure(renderer, scene, sweep, options.frames));
    const Sample& s = samples.back();
    std::printf("%-10s %-8s %7.3f %8.3f %5dx%-5d %10.1f %8.3f\n", s.sweep.c_str(),
                to_string(s.mode), s.density, s.coverage, s.width, s.height, s.gpu_ms, s.fps());
    std::fflush(stdout);
  };

  for (MarchMode mode : {MarchMode::Default, MarchMode::Baseline}) {
    Scene scene = base;
    scene.quality.mode = mode;
    renderer.render(scene);  // warm-up: builds the noise and weather textures, the sky LUT
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

  // Headline: the scene as given, both modes, and their ratio.
  nlohmann::json summary;
  summary["device"] = renderer.device_name();
  summary["width"] = base.output.width;
  summary["height"] = base.output.height;
  summary["frames_per_point"] = options.frames;
  for (MarchMode mode : {MarchMode::Default, MarchMode::Baseline}) {
    Scene s = base;
    s.quality.mode = mode;
    const Sample m = measure(renderer, s, "scene", options.frames);
    summary[std::string(to_string(mode)) + "_ms"] = m.gpu_ms;
    summary[std::string(to_string(mode)) + "_fps"] = m.fps();
  }
  summary["speedup_vs_baseline"] =
      summary["baseline_ms"].get<double>() / summary["default_ms"].get<double>();

  write_text_file(csv, to_csv(samples));
  write_text_file(json, summary.dump(2) + "\n");
  write_plot_grid_png({panel(samples, "density", "FPS vs cloud density", "density"),
                       panel(samples, "coverage", "FPS vs coverage", "coverage"),
                       panel(samples, "resolution", "FPS vs resolution", "megapixels")},
                      3, png);
  std::printf("scene %dx%d: default %.1f ms (%.2f fps), baseline %.1f ms (%.2f fps), "
              "speed-up %.2fx\n",
              base.output.width, base.output.height, summary["default_ms"].get<double>(),
              summary["default_fps"].get<double>(), summary["baseline_ms"].get<double>(),
              summary["baseline_fps"].get<double>(), summary["speedup_vs_baseline"].get<double>());
  std::printf("%s\n%s\n%s\n", csv.c_str(), json.c_str(), png.c_str());
  return 0;
}

}  // namespace nephele::cli

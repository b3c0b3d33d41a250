#include "validate.h"

#include <toml++/toml.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "label.h"
#include "nephele/error.h"
#include "nephele/exposure.h"
#include "nephele/image.h"
#include "nephele/image_compare.h"
#include "nephele/output_file.h"
#include "nephele/renderer.h"
#include "nephele/scene_io.h"
#include "nephele_embedded.h"
#include "progress.h"
#include "render/frame_params.h"
#include "render/glsl.h"
#include "render_command.h"

namespace nephele_cli_data {  // defined by the generated embedded_cli_data.cpp
extern const EmbeddedFile kFiles[];
extern const size_t kFileCount;
}  // namespace nephele_cli_data

namespace nephele::cli {

namespace fs = std::filesystem;

namespace {

int int_key(const toml::table& t, const char* key, int fallback, int lo, int hi,
            const std::string& where) {
  const toml::node* node = t.get(key);
  if (!node) return fallback;
  const auto value = node->value<int64_t>();
  if (!value || *value < lo || *value > hi)
    throw InputError(where + key + ": must be an integer in [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "]");
  return int(*value);
}

std::string string_key(const toml::table& t, const char* key, const std::string& where) {
  const auto value = t.get(key) ? t.get(key)->value<std::string>() : std::nullopt;
  if (!value || value->empty()) throw InputError(where + key + ": must be a non-empty string");
  return *value;
}

// An image tone-mapped for the side-by-side picture: exposed, then the ACES fit and sRGB in
// write_image (exposure 1).
void paste(Image& canvas, const Image& image, int x0, int y0, int scale, float exposure) {
  for (int y = 0; y < image.height * scale; ++y)
    for (int x = 0; x < image.width * scale; ++x)
      canvas.at(x0 + x, y0 + y) =
          glm::vec4(glm::vec3(image.at(x / scale, y / scale)) * exposure, 1.0f);
}

// A relative error in units of the tolerance as a colour: black 0, red at the tolerance, white
// at 4 times it and above.
glm::vec4 error_colour(float e) {
  const glm::vec3 c = e <= 1.0f ? glm::vec3(std::max(e, 0.0f), 0.0f, 0.0f)
                                : glm::mix(glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(1.0f),
                                           std::min((e - 1.0f) / 3.0f, 1.0f));
  // Values the tone map shows as themselves, near enough: display-referred, exposure 1.
  return glm::vec4(c * 2.0f, 1.0f);
}

// Blocks without light in the reference (a black background, where any light counts 100%):
// dark grey, off the error scale.
constexpr glm::vec4 kUnlitBlock(0.12f, 0.12f, 0.12f, 1.0f);

// The blocks' relative errors as colours (error_colour); those without light kUnlitBlock.
Image error_colours(const Image& map, double tolerance) {
  Image out(map.width, map.height);
  for (size_t i = 0; i < map.pixels.size(); ++i)
    out.pixels[i] =
        map.pixels[i].a > 0.5f ? error_colour(float(map.pixels[i].r / tolerance)) : kUnlitBlock;
  return out;
}

// A percentage as the legend and the summary write it: 15%, 0.1%, 2.5%.
std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g%%", 100.0 * fraction);
  return text;
}

// Rows of pixels under the images for the error map's scale (kLegendHeight at scale 1).
constexpr int kLegendHeight = 26;

// The error map's scale under it, from x0 to x1 at row y: the colours from 0 to 4 times the
// tolerance with ticks at 0, the tolerance, twice and 4 times it, labelled in per cent (a label
// that would overlap one already drawn is left out, the tolerance's last), and "block error"
// to its left where there is room.
void draw_error_legend(Image& canvas, int x0, int x1, int y, double tolerance) {
  const int bar_h = 8, tick_h = 3;
  const int length = std::max(x1 - x0, 2);
  for (int x = x0; x < x1; ++x) {
    const glm::vec4 c = error_colour(4.0f * float(x - x0) / float(length - 1));
    for (int dy = 0; dy < bar_h; ++dy) canvas.at(x, y + dy) = c;
  }
  const glm::vec4 white(50.0f, 50.0f, 50.0f, 1.0f);  // white after tone mapping (draw_label's)
  struct Tick {
    double times;
    std::string text;
  };
  const Tick ticks[] = {{0.0, "0"},
                        {4.0, percent(4.0 * tolerance) + "+"},
                        {1.0, percent(tolerance)},
                        {2.0, percent(2.0 * tolerance)}};
  std::vector<std::pair<int, int>> drawn;  // the labels' spans
  for (const Tick& t : ticks) {
    const int tx = x0 + int(std::lround(t.times / 4.0 * (length - 1)));
    for (int dy = 0; dy < tick_h; ++dy) canvas.at(tx, y + bar_h + dy) = white;
    const int w = label_width(t.text, 1);
    const int lx = std::clamp(tx - w / 2, x0, std::max(x0, x1 - w));
    const bool overlaps = std::any_of(drawn.begin(), drawn.end(), [&](const auto& span) {
      return lx < span.second + 2 && span.first < lx + w + 2;
    });
    if (overlaps || lx + w > canvas.width) continue;
    draw_label(canvas, lx, y + bar_h + tick_h, t.text, 1);
    drawn.emplace_back(lx, lx + w);
  }
  const std::string title = "block error";
  const int title_w = label_width(title, 1);
  if (x0 - title_w - 2 >= 0) draw_label(canvas, x0 - title_w - 2, y, title, 1);
}

}  // namespace

ValidationSuite parse_validation_suite(const std::string& text, const std::string& source) {
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    std::ostringstream line;
    line << source << ":" << e.source().begin.line << ": " << one_line_for_message(e.description());
    throw InputError(line.str());
  }
  const std::string where = source + ": ";
  ValidationSuite suite;
  suite.width = int_key(root, "width", suite.width, 8, 4096, where);
  suite.height = int_key(root, "height", suite.height, 8, 4096, where);
  suite.block = int_key(root, "block", suite.block, 1, 256, where);
  const toml::array* views = root.get_as<toml::array>("view");
  if (!views || views->empty()) throw InputError(where + "view: needs at least one [[view]]");
  for (size_t i = 0; i < views->size(); ++i) {
    const toml::table* t = views->get(i)->as_table();
    const std::string at = where + "view[" + std::to_string(i) + "].";
    if (!t) throw InputError(at + ": must be a table");
    ValidationView v;
    v.name = string_key(*t, "name", at);
    for (char c : v.name)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'))
        throw InputError(at + "name \"" + v.name + "\": letters, digits, - and _ only");
    for (const ValidationView& other : suite.views)
      if (other.name == v.name) throw InputError(at + "name \"" + v.name + "\": used twice");
    v.description = t->get("description") ? t->get("description")->value_or(std::string()) : "";
    v.scene_toml = string_key(*t, "scene", at);
    const auto tol = t->get("max_mean_error") ? t->get("max_mean_error")->value<double>() : std::nullopt;
    if (!tol || !(*tol > 0.0 && *tol <= 1.0))
      throw InputError(at + "max_mean_error: must be a number in (0, 1]");
    v.max_mean_error = *tol;
    if (const toml::node* b = t->get("max_block_error")) {
      const auto block_tol = b->value<double>();
      if (!block_tol || !(*block_tol > 0.0 && *block_tol <= 100.0))
        throw InputError(at + "max_block_error: must be a number in (0, 100] (or left out: none)");
      v.max_block_error = *block_tol;
    }
    suite.views.push_back(v);
  }
  if (const toml::table* sky = root.get_as<toml::table>("sky")) {
    const std::string at = where + "sky.";
    const toml::array* elevations = sky->get_as<toml::array>("sun_elevations_deg");
    if (!elevations || elevations->empty())
      throw InputError(at + "sun_elevations_deg: must be a non-empty array of numbers in [0, 90]");
    for (const toml::node& e : *elevations) {
      const auto value = e.value<double>();
      if (!value || *value < 0.0 || *value > 90.0)
        throw InputError(at + "sun_elevations_deg: must be a non-empty array of numbers in [0, 90]");
      suite.sky.sun_elevations_deg.push_back(*value);
    }
    const auto fraction = [&](const char* key, double& out) {
      const toml::node* node = sky->get(key);
      if (!node) return;
      const auto value = node->value<double>();
      if (!value || !(*value > 0.0 && *value <= 1.0))
        throw InputError(at + key + ": must be a number in (0, 1]");
      out = *value;
    };
    fraction("max_pattern_mean", suite.sky.max_pattern_mean);
    fraction("max_pattern_horizon", suite.sky.max_pattern_horizon);
    fraction("max_colour_ratio", suite.sky.max_colour_ratio);
    fraction("max_zenith_jump", suite.sky.max_zenith_jump);
  }
  return suite;
}

ValidationSuite default_validation_suite() {
  const EmbeddedFile* file =
      find_embedded(nephele_cli_data::kFiles, nephele_cli_data::kFileCount, "validation.toml");
  if (!file) throw RuntimeError("validation.toml is not embedded in this build");
  return parse_validation_suite(std::string(reinterpret_cast<const char*>(file->data), file->size),
                                "validation.toml");
}

void add_validate_flags(CLI::App& cmd, ValidateOptions& options) {
  cmd.add_option("--suite", options.suite,
                 "suite of views and tolerances (TOML, as data/validation.toml); default: the one "
                 "nephele ships");
  cmd.add_option("--views", options.views, "comma-separated names of the views to run (default: all)");
  cmd.add_flag("--sky", options.sky,
               "the clear sky against the path-traced atmosphere instead: its pattern and colour "
               "at each sun elevation of the suite's [sky] table, and the zenith's continuity");
  cmd.add_option("--width", options.width, "image width (pixels; default: the suite's)");
  cmd.add_option("--height", options.height, "image height (pixels; default: the suite's)");
  cmd.add_option("--spp", options.spp, "the reference's samples per pixel, [3, 1000000]")
      ->capture_default_str();
  cmd.add_option("--time-limit", options.time_limit_s,
                 "stop each view's reference after this many seconds (0 = none); samples "
                 "still in flight a tenth of it later are left out")
      ->capture_default_str();
  cmd.add_option(
      "--references", options.references,
      "folder of references (NAME.exr with a variance layer; with --sky "
      "sky_ELEVATION_VIEW.exr): read when there (one of another size is refused), else path traced "
      "and written there");
  cmd.add_option("--out", options.out_dir,
                 "folder for each view's images (NAME.png: fast | reference | block errors; "
                 "NAME_fast.exr) and results.md, results.json")
      ->capture_default_str();
  cmd.add_option("--json", options.json, "also write the results as JSON here");
  add_device_flags(cmd, options.device, options.verbose, options.validation);
  add_progress_flags(cmd, options.progress, options.quiet);
}

namespace {

// The pixels within a pixel and a half of the sun's disk (as the camera's rays see it): left
// out of a view's comparison. At the suite's size the disk is a fraction of a pixel, which the
// reference integrates over the pixel and the fast mode samples at the pixel's centre; the
// sun's pixel of the backlit sunset outweighed the rest of the view 60-fold. The disk itself
// is checked by the clear sky's and the sun's own tests.
Image without_sun_disk(const Image& image, const Scene& scene, size_t* excluded) {
  const gpu::FrameParams f = make_frame_params(scene, 0);
  const float pitch_rad = 2.0f * f.camera_pos_m.w / float(image.height);
  const float reach_rad =
      std::acos(std::min(f.sun_dir.w, 1.0f)) + 1.5f * std::sqrt(2.0f) * pitch_rad;
  Image out = image;
  size_t n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const glm::vec3 dir = glsl::camera_ray(
          glm::vec3(f.camera_forward), glm::vec3(f.camera_right), glm::vec3(f.camera_up),
          f.camera_pos_m.w, f.camera_forward.w, float(x), float(y), float(image.width),
          float(image.height), glm::vec2(f.camera_right.w, f.camera_up.w));
      if (glm::dot(dir, glm::vec3(f.sun_dir)) < std::cos(reach_rad)) continue;
      out.pixels[size_t(y) * size_t(image.width) + size_t(x)] = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
      ++n;
    }
  if (excluded) *excluded = n;
  return out;
}

glm::dvec3 mean_rgb(const Image& image) {
  glm::dvec3 sum(0.0);
  for (const glm::vec4& p : image.pixels) sum += glm::dvec3(p);
  return sum / double(image.pixels.size());
}

double rgb_luminance(glm::dvec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// The largest relative luminance step between neighbouring pixels.
double largest_step(const Image& image) {
  double worst = 0.0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const double l = luminance(image.at(x, y));
      if (x + 1 < image.width)
        worst = std::max(worst, std::abs(luminance(image.at(x + 1, y)) - l) / std::max(l, 1e-30));
      if (y + 1 < image.height)
        worst = std::max(worst, std::abs(luminance(image.at(x, y + 1)) - l) / std::max(l, 1e-30));
    }
  return worst;
}

// Writes NAME.md (the table, then `notes` and the summary line) and NAME.json (and --json),
// prints the same; the exit status: 0 when every case passed, 1 when one did not or the
// validation layer spoke. `summary` says what passed or failed ("FAILED: ..." or "passed:
// ..."); the validation layer's messages, when there are any, fail it whatever it says.
int finish(const ValidateOptions& options, const Renderer& renderer, const std::string& name,
           const std::string& table, const std::string& notes, std::string summary,
           nlohmann::json& results, bool pass) {
  const int messages = options.validation ? renderer.validation_messages() : 0;
  if (messages > 0)
    summary =
        "FAILED: " + std::to_string(messages) + " Vulkan validation messages (" + summary + ")";
  summary =
      std::string(name == "sky" ? "nephele validate --sky: " : "nephele validate: ") + summary;
  results["pass"] = pass;
  results["summary"] = summary;
  const std::string text = table + "\n" + notes + (notes.empty() ? "" : "\n") + summary + "\n";
  write_file_atomically((fs::path(options.out_dir) / (name + ".md")).string(), text);
  write_file_atomically((fs::path(options.out_dir) / (name + ".json")).string(), results.dump(2) + "\n");
  if (!options.json.empty()) write_file_atomically(options.json, results.dump(2) + "\n");
  std::cout << text << std::flush;
  if (messages > 0) {
    std::fprintf(stderr, "nephele: %d Vulkan validation messages\n", messages);
    return 1;
  }
  return pass ? 0 : 1;
}

// "1 view", "6 views".
std::string count_of(size_t n, const char* noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

// Refuses a --references folder's NAME.exr, `held`, of another size than the views': tracing
// the view again would write over it (a shipped reference of 40 x 25 replaced by one of a few
// seconds at another --width). `sized`: the views' size comes from --width and --height.
void refuse_other_size(const ValidateOptions& options, const std::string& name, const Image& held,
                       int width, int height, bool sized) {
  if (held.width == width && held.height == height) return;
  throw InputError("--references \"" + options.references + "\": " + name + ".exr is " +
                   std::to_string(held.width) + "x" + std::to_string(held.height) +
                   ", the views are " + std::to_string(width) + "x" + std::to_string(height) +
                   (sized ? ": pass --width " + std::to_string(held.width) + " --height " +
                                std::to_string(held.height) + ", or another folder"
                          : ": pass another folder") +
                   " to trace new ones into");
}

// The same for every view, before anything is rendered or written.
void check_reference_sizes(const ValidateOptions& options, const std::vector<std::string>& names,
                           int width, int height) {
  if (options.references.empty()) return;
  for (const std::string& name : names) {
    const fs::path file = fs::path(options.references) / (name + ".exr");
    if (fs::exists(file))
      refuse_other_size(options, name, read_exr_layer(file.string(), ""), width, height, true);
  }
}

// The reference of view `name`: the --references folder's NAME.exr when it holds one (its
// samples per pixel from the header's nephele.spp; no time spent; one of another size is
// refused, refuse_other_size), else path traced and written there (or to the output folder as
// NAME_reference.exr).
ReferenceImage reference_for(Renderer& renderer, const Scene& scene,
                             const ValidateOptions& options, const std::string& name, bool show) {
  ReferenceImage reference;
  const std::string cached =
      options.references.empty() ? "" : (fs::path(options.references) / (name + ".exr")).string();
  if (!cached.empty() && fs::exists(cached)) {
    reference.mean = read_exr_layer(cached, "");
    refuse_other_size(options, name, reference.mean, scene.output.width, scene.output.height,
                      !options.sky);
    reference.variance = read_exr_layer(cached, "variance");
    for (const auto& [key, value] : read_exr_attributes(cached))
      if (key == "nephele.spp") reference.spp = std::atoi(value.c_str());
    return reference;
  }
  std::unique_ptr<Progress> bar;
  ReferenceOptions ro;
  ro.spp = options.spp;
  ro.time_limit_s = options.time_limit_s;
  ro.seed = scene.noise_seed;
  if (show)
    ro.progress = [&](std::string_view, int done, int total) {
      if (!bar) bar = std::make_unique<Progress>(name, total, true);
      bar->step(done);
    };
  reference = renderer.render_reference(scene, ro);
  bar.reset();
  const std::string path =
      cached.empty() ? (fs::path(options.out_dir) / (name + "_reference.exr")).string() : cached;
  ExrAttributes attributes;
  attributes.floats.push_back({"nephele.spp", float(reference.spp)});
  write_exr_layers({{"", &reference.mean, 4, {}}, {"variance", &reference.variance, 3, {}}}, path,
                   ExrPixels::kFloat, attributes);
  return reference;
}

// `validate --sky`: the clear sky of the fast mode against the path-traced atmosphere.
int run_validate_sky(const ValidateOptions& options, const ValidationSuite& suite) {
  const SkyTargets& targets = suite.sky;
  if (targets.sun_elevations_deg.empty())
    throw InputError("--sky: the suite has no [sky] table (see data/validation.toml)");
  fs::create_directories(options.out_dir);
  if (!options.references.empty()) fs::create_directories(options.references);
  Renderer renderer({options.device, options.validation, options.verbose, {}});
  struct View {
    const char* name;
    double relative_azimuth_deg;  // from the sun's azimuth
    double elevation_deg;         // < 0: 20 deg above the sun (below it above 70 deg)
    bool horizon;
  };
  const View views[] = {{"zenith", 0.0, 90.0, false},
                        {"horizon-away", 180.0, 1.0, true},
                        {"horizon-side", 90.0, 1.0, true},
                        {"horizon-near", 30.0, 1.0, true},
                        {"towards-sun", 0.0, -1.0, false}};
  nlohmann::json results;
  results["device"] = renderer.device_name();
  std::ostringstream table;
  table << "| sun elevation | pattern mean | worst at 1 deg | worst colour ratio | zenith jump | "
           "zenith fast / reference | |\n|---:|---:|---:|---:|---:|---:|---|\n";
  bool all_pass = true;
  std::string missed;  // the sun elevations that miss a target, and why
  int misses = 0;
  const bool show = progress_wanted(options.progress, options.quiet, options.verbose);
  Progress progress("sky", int(targets.sun_elevations_deg.size() * std::size(views)), show);
  for (double sun_deg : targets.sun_elevations_deg) {
    Scene base = load_preset("clear");
    base.time.clear();
    base.sun.from_time = false;
    base.sun.direction = sun_direction_from_angles(sun_deg, 180.0);
    base.sun.disk_angular_radius_deg = 0.0f;  // the sky, not the disk (in view at 90 deg)
    base.output.width = 16;
    base.output.height = 16;
    base.camera.position_m = glm::vec3(0.0f, 0.0f, 2.0f);
    base.camera.fov_deg = 2.0f;
    glm::dvec3 zenith_fast(0.0), zenith_reference(0.0);
    double pattern_sum = 0.0, worst_horizon = 0.0, worst_colour = 0.0;
    int patterns = 0;
    nlohmann::json per_view;
    for (const View& v : views) {
      Scene s = base;
      const double elevation = v.elevation_deg >= 0.0 ? v.elevation_deg
                               : sun_deg <= 70.0     ? sun_deg + 20.0
                                                     : sun_deg - 20.0;
      s.camera.view_dir = sun_direction_from_angles(elevation, 180.0 + v.relative_azimuth_deg);
      validate_scene(s);
      const glm::dvec3 fast = mean_rgb(renderer.render(s).color);
      char name[64];
      std::snprintf(name, sizeof name, "sky_%g_%s", sun_deg, v.name);
      const ReferenceImage reference = reference_for(renderer, s, options, name, false);
      const glm::dvec3 ref = mean_rgb(reference.mean);
      if (std::string(v.name) == "zenith") {
        zenith_fast = fast;
        zenith_reference = ref;
      }
      const double pattern = (rgb_luminance(fast) / rgb_luminance(zenith_fast)) /
                                 (rgb_luminance(ref) / rgb_luminance(zenith_reference)) - 1.0;
      const double blue = (fast.b / fast.r) / (ref.b / ref.r) - 1.0;
      const double green = (fast.g / fast.r) / (ref.g / ref.r) - 1.0;
      worst_colour = std::max({worst_colour, std::abs(blue), std::abs(green)});
      if (std::string(v.name) != "zenith") {
        pattern_sum += std::abs(pattern);
        ++patterns;
      }
      if (v.horizon) worst_horizon = std::max(worst_horizon, std::abs(pattern));
      per_view[v.name] = {{"elevation_deg", elevation},
                          {"fast_rgb", {fast.r, fast.g, fast.b}},
                          {"reference_rgb", {ref.r, ref.g, ref.b}},
                          {"pattern_error", pattern},
                          {"blue_red_error", blue},
                          {"green_red_error", green},
                          {"reference_spp", reference.spp}};
      progress.advance();
    }
    // The zenith's neighbourhood in the fast mode: a seam would be a step between two pixels.
    Scene z = base;
    z.camera.view_dir = glm::vec3(0.0f, 0.0f, 1.0f);
    z.camera.fov_deg = 10.0f;
    z.output.width = 64;
    z.output.height = 64;
    const double jump = largest_step(renderer.render(z).color);
    const double pattern_mean = pattern_sum / std::max(patterns, 1);
    const double zenith_ratio = rgb_luminance(zenith_fast) / rgb_luminance(zenith_reference);
    const bool pass = pattern_mean <= targets.max_pattern_mean &&
                      worst_horizon <= targets.max_pattern_horizon &&
                      worst_colour <= targets.max_colour_ratio && jump <= targets.max_zenith_jump;
    all_pass = all_pass && pass;
    if (!pass) {
      char what[200];
      std::snprintf(what, sizeof what, "%s%g deg (", missed.empty() ? "" : ", ", sun_deg);
      std::string reasons;
      const auto reason = [&](bool miss, const char* name, double value, double target) {
        if (miss)
          reasons += (reasons.empty() ? "" : ", ") + std::string(name) + " " + percent(value) +
                     " > " + percent(target);
      };
      reason(!(pattern_mean <= targets.max_pattern_mean), "pattern", pattern_mean,
             targets.max_pattern_mean);
      reason(!(worst_horizon <= targets.max_pattern_horizon), "at 1 deg", worst_horizon,
             targets.max_pattern_horizon);
      reason(!(worst_colour <= targets.max_colour_ratio), "colour", worst_colour,
             targets.max_colour_ratio);
      reason(!(jump <= targets.max_zenith_jump), "zenith jump", jump, targets.max_zenith_jump);
      missed += what + reasons + ")";
      ++misses;
    }
    char row[300];
    std::snprintf(row, sizeof row, "| %.0f deg | %.1f%% | %.1f%% | %.1f%% | %.2f%% | %.3f | %s |\n",
                  sun_deg, 100.0 * pattern_mean, 100.0 * worst_horizon, 100.0 * worst_colour,
                  100.0 * jump, zenith_ratio, pass ? "pass" : "**miss**");
    table << row;
    progress.clear();
    if (!options.quiet) std::fprintf(stderr, "%s", row);
    char key[32];
    std::snprintf(key, sizeof key, "%.1f", sun_deg);
    results["sun_elevations"][key] = {{"views", per_view},
                                      {"pattern_mean", pattern_mean},
                                      {"worst_horizon_pattern", worst_horizon},
                                      {"worst_colour_ratio", worst_colour},
                                      {"zenith_jump", jump},
                                      {"zenith_fast_over_reference", zenith_ratio},
                                      {"pass", pass}};
  }
  progress.finish();
  results["targets"] = {{"max_pattern_mean", targets.max_pattern_mean},
                        {"max_pattern_horizon", targets.max_pattern_horizon},
                        {"max_colour_ratio", targets.max_colour_ratio},
                        {"max_zenith_jump", targets.max_zenith_jump}};
  const size_t n = targets.sun_elevations_deg.size();
  const std::string summary =
      all_pass ? "passed: " + std::string(n == 1 ? "" : "all ") + count_of(n, "sun elevation") +
                     " within the targets (pattern " + percent(targets.max_pattern_mean) +
                     ", at 1 deg " + percent(targets.max_pattern_horizon) + ", colour " +
                     percent(targets.max_colour_ratio) + ", zenith jump " +
                     percent(targets.max_zenith_jump) + ")"
               : "FAILED: " + std::to_string(misses) + " of " + std::to_string(n) +
                     " sun elevations" + " miss a target: " + missed;
  return finish(options, renderer, "sky", table.str(), "", summary, results, all_pass);
}

}  // namespace

int run_validate(const ValidateOptions& options) {
  // Its reports and --json may not replace the suite it reads (--references, read and written
  // by design, is the one folder that holds inputs).
  if (!options.json.empty()) check_output_file(options.json, "--json", true);
  NamedPaths reports = {{"--json", options.json}};
  for (const char* report : {"results.md", "results.json", "sky.md", "sky.json"})
    reports.emplace_back("--out", (fs::path(options.out_dir) / report).string());
  check_outputs_not_inputs(reports, {{"--suite", options.suite}});
  ValidationSuite suite;
  if (options.suite.empty()) {
    suite = default_validation_suite();
  } else {
    std::ifstream in(options.suite, std::ios::binary);
    if (!in) throw InputError("--suite \"" + options.suite + "\": cannot be read");
    std::stringstream text;
    text << in.rdbuf();
    suite = parse_validation_suite(text.str(), options.suite);
  }
  if (options.spp < 3 || options.spp > 1000000)
    throw InputError("--spp " + std::to_string(options.spp) + ": must be in [3, 1000000]");
  if (options.sky) {
    if (!options.views.empty()) throw InputError("--sky and --views cannot be combined");
    return run_validate_sky(options, suite);
  }
  if (options.width < 0 || options.width > 4096 || options.height < 0 || options.height > 4096)
    throw InputError("--width, --height: must be in [8, 4096] (0: the suite's)");
  if (options.width > 0) suite.width = std::max(options.width, 8);
  if (options.height > 0) suite.height = std::max(options.height, 8);
  if (!(options.time_limit_s >= 0.0 && std::isfinite(options.time_limit_s)))
    throw InputError("--time-limit: must be a finite number of seconds, at least 0 (0 = none)");
  // The views asked for, in the suite's order; each name must exist.
  std::vector<ValidationView> views;
  if (options.views.empty()) {
    views = suite.views;
  } else {
    std::stringstream names(options.views);
    std::string name;
    while (std::getline(names, name, ',')) {
      const auto it = std::find_if(suite.views.begin(), suite.views.end(),
                                   [&](const ValidationView& v) { return v.name == name; });
      if (it == suite.views.end()) {
        std::string all;
        for (const ValidationView& v : suite.views) all += (all.empty() ? "" : ", ") + v.name;
        throw InputError("--views \"" + name + "\": no such view (the suite has " + all + ")");
      }
      views.push_back(*it);
    }
  }
  // Every scene parsed and checked before anything is rendered; a file a view names (a lab's
  // grid, a weather map) relative to the suite's file.
  const std::string suite_dir =
      options.suite.empty() ? std::string() : fs::path(options.suite).parent_path().string();
  std::vector<Scene> scenes;
  for (const ValidationView& v : views) {
    scenes.push_back(parse_scene_toml(v.scene_toml, "view " + v.name, suite_dir));
    scenes.back().output.width = suite.width;
    scenes.back().output.height = suite.height;
    validate_scene(scenes.back());
  }
  std::vector<std::string> names;
  for (const ValidationView& v : views) names.push_back(v.name);
  check_reference_sizes(options, names, suite.width, suite.height);
  fs::create_directories(options.out_dir);
  if (!options.references.empty()) fs::create_directories(options.references);

  Renderer renderer({options.device, options.validation, options.verbose, {}});
  const bool show = progress_wanted(options.progress, options.quiet, options.verbose);
  nlohmann::json results;
  results["device"] = renderer.device_name();
  results["width"] = suite.width;
  results["height"] = suite.height;
  results["block"] = suite.block;
  std::ostringstream table;
  table
      << "| view | mean error | tolerance | bias | p95 block | worst lit block | reference noise | "
         "spp | fast ms | reference s | "
         "|\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
  bool all_pass = true;
  size_t misses = 0;
  const ValidationView* worst = nullptr;  // the miss furthest over its tolerance
  double worst_error = 0.0, worst_ratio = 0.0;
  bool worst_is_block = false;
  for (size_t i = 0; i < views.size(); ++i) {
    const ValidationView& view = views[i];
    const Scene& scene = scenes[i];
    const Frame fast = renderer.render(scene);
    const ReferenceImage reference = reference_for(renderer, scene, options, view.name, show);
    size_t sun_pixels = 0;
    const BlockLuminanceError e =
        block_luminance_error(without_sun_disk(fast.color, scene, &sun_pixels),
                              without_sun_disk(reference.mean, scene, nullptr),
                              without_sun_disk(reference.variance, scene, nullptr), suite.block);
    // The mean within its tolerance, and every lit block within its own where the view has one.
    const double mean_ratio = e.mean_error / view.max_mean_error;
    const double block_ratio =
        view.max_block_error > 0.0 ? e.max_lit_error / view.max_block_error : 0.0;
    const bool pass = mean_ratio <= 1.0 && block_ratio <= 1.0;
    all_pass = all_pass && pass;
    if (!pass) {
      ++misses;
      // NaN (no comparison holds) counts as the worst.
      const double ratio = std::max(mean_ratio, block_ratio);
      if (!worst || !(ratio <= worst_ratio) || std::isnan(mean_ratio)) {
        worst = &view;
        worst_is_block = block_ratio > mean_ratio;
        worst_error = worst_is_block ? e.max_lit_error : e.mean_error;
        worst_ratio = std::isnan(mean_ratio) ? mean_ratio : ratio;
      }
    }

    // fast | reference | block errors, each at twice the size or more, so that its label fits
    // over it. Both exposed as the scene's camera would expose the reference.
    const float exposure = still_exposure(scene.output, reference.mean);
    // Red at the tolerance each block is held to: the view's block tolerance where it has one.
    const double map_tolerance =
        view.max_block_error > 0.0 ? view.max_block_error : view.max_mean_error;
    char labels[3][200];
    std::snprintf(labels[0], sizeof labels[0], "%s: fast", view.name.c_str());
    std::snprintf(labels[1], sizeof labels[1], "reference, %d spp", reference.spp);
    std::snprintf(labels[2], sizeof labels[2], "%dx%d error %.1f%% (red: %s)", suite.block,
                  suite.block, 100.0 * e.mean_error, percent(map_tolerance).c_str());
    int widest = 0;
    for (const char* l : labels) widest = std::max(widest, label_width(l, 1));
    const int s = std::max(2, (widest + 4 + suite.width - 1) / suite.width);
    const int w = suite.width * s, h = suite.height * s, gap = 4;
    Image side(3 * w + 2 * gap, h + kLegendHeight);
    for (glm::vec4& p : side.pixels) p = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    paste(side, fast.color, 0, 0, s, exposure);
    paste(side, reference.mean, w + gap, 0, s, exposure);
    const Image colours = error_colours(e.map, map_tolerance);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        side.at(2 * (w + gap) + x, y) =
            colours.at(std::min(x / (suite.block * s), colours.width - 1),
                       std::min(y / (suite.block * s), colours.height - 1));
    for (int k = 0; k < 3; ++k) draw_label(side, k * (w + gap), 0, labels[k], 1);
    // The map's scale under it (at least 120 pixels long, room for its labels).
    const int legend_x1 = 3 * w + 2 * gap;
    draw_error_legend(side, std::max(0, std::min(2 * (w + gap), legend_x1 - 120)), legend_x1, h + 2,
                      map_tolerance);
    write_image(side, (fs::path(options.out_dir) / (view.name + ".png")).string(), 1.0f);
    write_image(fast.color, (fs::path(options.out_dir) / (view.name + "_fast.exr")).string(), 1.0f,
                ExrPixels::kFloat);

    char row[400];
    std::snprintf(
        row, sizeof row,
        "| %s | %.1f%% | %s | %+.1f%% | %.1f%% | %.1f%%%s | %.2f%% | %d | %.0f | %.0f | %s |\n",
        view.name.c_str(), 100.0 * e.mean_error, percent(view.max_mean_error).c_str(),
        100.0 * e.mean_bias, 100.0 * e.p95_error, 100.0 * e.max_lit_error,
        view.max_block_error > 0.0 ? (" (" + percent(view.max_block_error) + ")").c_str() : "",
        100.0 * e.reference_noise, reference.spp, fast.stats.wall_ms, reference.seconds,
        pass ? "pass" : "**miss**");
    table << row;
    if (!options.quiet) std::fprintf(stderr, "%s", row);
    if (reference.cut_loops > 0)
      std::fprintf(stderr,
                   "nephele: warning: %s: %lld of the reference's tracking walks were cut at "
                   "2^24 tentative collisions: it is biased\n",
                   view.name.c_str(), reference.cut_loops);
    if (reference.abandoned > 0 && !options.quiet)
      std::fprintf(stderr,
                   "nephele: %s: the time limit left out %lld samples still in flight a tenth "
                   "of it later (of %lld taken)\n",
                   view.name.c_str(), reference.abandoned,
                   (long long)(reference.spp) * scene.output.width * scene.output.height);
    results["views"][view.name] = {{"description", view.description},
                                   {"mean_error", e.mean_error},
                                   {"max_mean_error", view.max_mean_error},
                                   {"mean_bias", e.mean_bias},
                                   {"p95_block_error", e.p95_error},
                                   {"max_block_error", e.max_error},
                                   {"max_lit_block_error", e.max_lit_error},
                                   {"max_lit_block_tolerance", view.max_block_error},
                                   {"reference_noise", e.reference_noise},
                                   {"reference_spp", reference.spp},
                                   {"reference_cut_loops", reference.cut_loops},
                                   {"reference_s", reference.seconds},
                                   {"sun_pixels_excluded", sun_pixels},
                                   {"fast_ms", fast.stats.wall_ms},
                                   {"pass", pass}};
  }
  // One tolerance for all: "over 15%"; else each view's own (block tolerances count as such).
  const bool one_tolerance = std::all_of(views.begin(), views.end(), [&](const ValidationView& v) {
    return v.max_mean_error == views.front().max_mean_error && v.max_block_error == 0.0;
  });
  const std::string tolerance =
      one_tolerance ? percent(views.front().max_mean_error)
                    : std::string(views.size() == 1 ? "its tolerance" : "their tolerances");
  std::string summary;
  if (all_pass)
    summary = "passed: " + std::string(views.size() == 1 ? "" : "all ") +
              count_of(views.size(), "view") + " within " + tolerance;
  else
    summary = "FAILED: " + std::to_string(misses) + " of " + std::to_string(views.size()) +
              " views over " + (one_tolerance ? tolerance : std::string("their tolerances")) +
              " (worst: " + worst->name + (worst_is_block ? " block " : " ") +
              percent(worst_error) + " > " +
              percent(worst_is_block ? worst->max_block_error : worst->max_mean_error) + ")";
  const std::string block = std::to_string(suite.block) + "x" + std::to_string(suite.block);
  const std::string notes =
      "Error maps (right in " + (fs::path(options.out_dir) / "NAME.png").string() + "): each " +
      block + " block's luminance error against the reference, black 0, red at the view's " +
      "block tolerance (its mean's where it has none), white at 4 times it or more (the scale " +
      "under the map); dark grey where the reference has no light.\n";
  return finish(options, renderer, "results", table.str(), notes, summary, results, all_pass);
}

}  // namespace nephele::cli

// nephele — the renderer: Vulkan compute passes behind a plain C++ interface.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "nephele/image.h"
#include "nephele/scene.h"
#include "nephele/sky.h"

namespace nephele {

class CloudQuery;

// Progress of long work, called on the calling thread: `stage` ("noise": the noise textures
// made for a seed, about 3 s on a CPU; "clouds": a still image marched in bands of rows),
// `done` of `total` steps.
using ProgressCallback = std::function<void(std::string_view stage, int done, int total)>;

struct RendererOptions {
  std::string device;       // substring of the device name to pick; empty = best available
  bool validation = false;  // enable VK_LAYER_KHRONOS_validation; messages are counted
  bool verbose = false;     // print device choice and pass timings to stderr
  // When set, the noise textures and still images (render(), FrameOptions::still) are made in
  // several submissions, each reported when done. The images are the same.
  ProgressCallback progress;
  // Renderer: a still with more pixels than this, or a side longer than the device's largest
  // image, renders in tiles (render(), render_layers()): the same image, drawn a window at a
  // time; 0 = 3840 x 2160 (kDefaultMaxTilePixels), else at least 4096 (64 x 64).
  int64_t max_tile_pixels = 0;
  // Each pass is compiled for the features a frame uses (the sky model, voxel clouds, the
  // cloud lighting, keyframes, shafts, terrain, cirrus, particles), so that a feature a scene
  // does not use costs nothing: a CPU device runs both sides of every branch. A new set of
  // features compiles its variant on first use. False runs every pass's full shader: the same
  // image, slower; for comparison (nephele bench).
  bool feature_variants = true;
};

constexpr int64_t kDefaultMaxTilePixels = int64_t(3840) * 2160;

struct PassTiming {
  std::string name;
  double ms = 0.0;
};

// A voxel cloud on the device (the sparse bricks of render/modules/voxel_clouds/voxel_clouds.h).
struct VoxelCloudMemory {
  std::string source;        // its file, or "preset:NAME:SEED"
  int dims[3] = {0, 0, 0};   // its grid (voxels)
  double voxel_m = 0.0;      // the voxel's edge in the scene (m)
  size_t stored_bricks = 0;  // of total_bricks, those near its surface, stored
  size_t total_bricks = 0;
  size_t bytes = 0;          // its bricks and page table on the device
  size_t dense_bytes = 0;    // what the same grid would take stored whole (RG16F)
};

// A frame's particle clouds (issue 22; scene.h, ParticleCloudParams): the CPU's work and the
// impostors and their atlas.
struct ParticleCloudStats {
  size_t particles = 0;  // in the field
  size_t drawn = 0;      // drawn one by one (the rest are in impostors)
  int clouds = 0;
  int relit_clouds = 0;  // by the CPU lighting this frame
  int impostors = 0;     // clouds drawn as impostors
  int impostor_updates = 0;  // drawn into the atlas this frame
  int layer_width = 0, layer_height = 0;  // the particle layer's pixels (layer_resolution)
  int impostors_waiting = 0;  // far clouds drawn particle by particle, their images not yet drawn
  // The impostor images' resolution, of impostor_resolution: below 1 while the atlas is short
  // of room (render/modules/impostors/impostors.h).
  double impostor_resolution_scale = 1.0;
  double generate_ms = 0.0, lighting_ms = 0.0, sort_ms = 0.0;  // host wall time
  // The atlas (particles/atlas.h, AtlasStats): shares of its texels, defragmentations per
  // second, downsized images, and the manager's time per operation.
  double atlas_occupancy = 0.0, atlas_wasted = 0.0, atlas_fragmentation = 0.0;
  double atlas_defragmentations_per_s = 0.0;
  int atlas_defragmentations = 0, atlas_downsized = 0, atlas_failed = 0;
  double atlas_mean_op_us = 0.0, atlas_max_op_us = 0.0;
};

struct FrameStats {
  std::string device;            // name of the Vulkan device used
  int width = 0;
  int height = 0;
  double frame_ms = 0.0;         // GPU time of the frame's passes (timestamps)
  double wall_ms = 0.0;          // host wall-clock time of render()
  double mean_luminance = 0.0;   // mean relative luminance of the linear HDR image
  // What an exposure meter reads of the HDR image, measured on the device for every frame
  // (frame API included): the log-average luminance (cd/m^2) over 64 x 64 pixels spread over
  // it, as nephele/exposure.h's metered_luminance reads a whole image; 0 when unknown. A live
  // display exposes the next frame by it (exposure.h, live_ev100).
  double metered_luminance = 0.0;
  double cloud_cover_fraction = 0.0;  // share of above-horizon pixels with cloud T < 0.5
  // Still images (render()): the share of the whole sky dome above the observer (the upper
  // hemisphere, wherever the camera looks, 4096 directions of equal solid angle) with cloud
  // T < 0.5, as an observer reports cloud cover; sky_cover_oktas() turns it into oktas.
  std::optional<double> sky_cover_fraction;
  std::vector<PassTiming> passes;
  SkyPosition sun;                     // the frame's sun (distance 0 without a time)
  std::optional<Ephemeris> ephemeris;  // sun, moon and sidereal time when the scene has a time
  std::vector<VoxelCloudMemory> voxel_clouds;
  size_t voxel_bytes = 0;  // the voxel clouds' textures on the device (atlas and page tables)
  std::optional<ParticleCloudStats> particle_clouds;  // when the scene has particle clouds
};

// Cloud cover in oktas (eighths of the sky, WMO code 2700) from the covered share of the sky:
// 0 only when no cloud at all (under 1/100), 8 only when overcast (over 99/100), otherwise the
// nearest eighth, at least 1 and at most 7.
int sky_cover_oktas(double fraction);

// A frame's statistics as JSON text, an object (keys sorted, indented by 2, a newline at the
// end): `nephele render --stats-json` writes it, nephele.render(stats=True) in Python reads it.
// Keys: image (`image`, the file the frame was written to, when not empty), device, width,
// height, frame_ms, wall_ms, mean_luminance (cd/m^2), ev100 (`ev100`: the exposure the image
// was written or shown with), cloud_cover_fraction, sky_cover_fraction and sky_cover_oktas
// (still images), sun_elevation_deg and sun_azimuth_deg, the moon's elevation, azimuth and
// illuminated fraction (with a date), passes_ms (each pass's total), voxel_clouds and
// voxel_bytes (with voxel clouds), particle_clouds (with particle clouds). Non-finite numbers
// are null.
std::string frame_stats_json(const FrameStats& stats, double ev100, const std::string& image = {});

struct Frame {
  Image color;          // linear HDR radiance (rgb), a = 1
  Image clouds;         // per pixel: rgb in-scattered cloud radiance, a = cloud transmittance
  FrameStats stats;
};

// Renderer::render_layers: a still and its layers for compositing (film output). The image is
// the layers' "over", exactly: color = clouds.rgb + (1 - clouds.a) sky, within float rounding.
struct FilmLayers {
  Frame frame;  // as render() returns it: color is the image (cd/m^2)
  // Everything behind the clouds: the sky with the sun, moon and stars, the ground (under the
  // clouds' shadows), the cirrus seen from below; a = 1.
  Image sky;
  // What lies in front of it, premultiplied: the clouds' light with the haze of the air in
  // front of them (aerial perspective), and the cirrus seen from above; a = 1 - their
  // transmittance.
  Image clouds;
  // r (= g = b): the clouds' distance from the camera along the view ray (m), weighted by the
  // opacity each sample added; 0 where the clouds are clear (a < 0.001). a = 1.
  Image clouds_depth_m;
};

// Renderer::cloud_profile: per altitude bin, from the bottom of the lowest cloud layer to the
// top of the highest, the mean density field (sigma_t / clouds.extinction_per_m) and the share
// of the region in cloud.
struct CloudProfile {
  std::vector<float> altitude_m;  // each bin's middle, above the ground
  std::vector<float> density;     // mean density field
  std::vector<float> cloud_fraction;
};

// Whether the path tracer's null collisions use the grid's bricks as a majorant grid (empty
// bricks crossed in one step) or one majorant for the whole box. Both are unbiased; kAuto takes
// the grid when under a quarter of the bricks are stored (on a CPU device each brick's edge
// costs a step: a cumulus with half its bricks stored was 1.5x slower with the grid).
enum class MajorantGrid { kAuto, kBricks, kNone };

// Renderer::render_reference: how long to trace.
struct ReferenceOptions {
  int spp = 64;               // samples per pixel, [1, 1000000]
  double time_limit_s = 0.0;  // stop once this much time has passed (0: none), at a pass's end,
                              // and leave out what is still in flight a tenth of it later
  uint32_t seed = 1;          // the same seed, scene and spp give the same image
  ProgressCallback progress;  // "reference", samples per pixel done, of spp
  // The lab's brick grid (kAuto: where under a quarter of the bricks are stored); on the
  // planet, the noise clouds' grid (path_majorant.h) unless kNone.
  MajorantGrid majorant_grid = MajorantGrid::kAuto;
  // Scatterings after the first, [0, kMaxReferenceBounces] (0: single scattering); -1: the
  // lab's lab.max_bounces, or all that matter on the planet (Russian roulette ends paths).
  int max_bounces = -1;
  // How many invocations of each dispatch share a pixel's samples, [0, 64]; 0: enough for
  // 2^18 invocations on a GPU at any image size (1, 3, 9 or 27), 1 on a CPU device, whose cores
  // an image's pixels already keep busy. Any value gives the same estimate.
  int invocations_per_pixel = 0;
  // Iterations an invocation runs a pass (paths carry over between passes; an iteration is a
  // tentative collision and what follows it), [0, 65536]; 0: from 64, doubled while a pass
  // takes under a quarter of a second, to 2048 on a CPU device (whose loop limit is 65535
  // iterations a batch of lanes, in all its loops) or 16384 on a GPU. Any value gives the
  // same image.
  int iterations_per_pass = 0;
  // Whether a pass undoes an iteration the device's loop limit cut short: -1 (auto) on a CPU
  // device, whose loop limit can end a pass early (path_trace.comp), and not on a GPU, which
  // has none (path_trace_gpu.comp: NVIDIA's driver 580 cannot compile the undo); 0 or 1 to
  // choose. The two give the same image where the limit cuts no pass (on a CPU device 0 would
  // otherwise bias it).
  int undo_cut_iteration = -1;
};

constexpr int kMaxReferenceBounces = 1024;

// A path-traced image: the mean radiance per pixel and the variance of that mean.
struct ReferenceImage {
  Image mean;      // radiance (W m^-2 sr^-1 for a sun irradiance in W/m^2); a = 1
  Image variance;  // rgb: the variance of each pixel's mean (the sample variance / spp)
  int spp = 0;     // samples per pixel taken
  // Tracking walks cut at 2^24 tentative collisions (a guard against a walk that never ends):
  // 0 in every test; where it is not, the image is biased. (Lavapipe's loop limit, 65535
  // iterations an invocation's batch in all its loops, cuts nothing: the paths carry over from
  // one pass to the next, and a pass the limit ends early keeps its work up to the iteration
  // it cut.)
  long long cut_loops = 0;
  // Tentative collisions where the medium's extinction exceeded its majorant: 0 when the
  // majorants are right (a test of them; any would bias the image).
  long long majorant_violations = 0;
  // Samples left out at a time limit: each invocation finishes the sample it is on for at most
  // a tenth of the limit more, and those still in flight then are not counted (a pixel's mean
  // is over the samples it finished, which favours short paths by at most this many over the
  // samples taken).
  long long abandoned = 0;
  double seconds = 0.0;
};

class Renderer {
 public:
  explicit Renderer(const RendererOptions& options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Validates the scene (throws InputError), then renders a still image: every cloud pixel is
  // marched, at full resolution. Noise and weather textures are cached and rebuilt only when their parameters
  // change. The frame also starts the history that render_next() continues from.
  Frame render(const Scene& scene);

  // render() and the film layers of the same still (FilmLayers), each composed again over the
  // same clouds: a few compose passes more than render().
  FilmLayers render_layers(const Scene& scene);

  // How render() draws this scene's still: one frame, or tiles (RendererOptions::
  // max_tile_pixels) of at most tile_width x tile_height pixels.
  struct Tiling {
    int columns = 1, rows = 1;
    int tile_width = 0, tile_height = 0;
  };
  Tiling tiling(const Scene& scene) const;

  // Renders the next frame of an animation (the scene's camera, time and sun may change from
  // call to call): marches one cloud pixel of every quality.march_stride^2 block and
  // reprojects the others from the previous frame, following the camera's and the wind's
  // motion; where that fails (screen edges, disocclusion) the marched samples are
  // interpolated. The history restarts when anything else in the scene changes, the sun
  // moves by more than 0.5 deg, the camera jumps by more than 1 km or crosses the cloud
  // layer's bottom or top. With read_back false the images stay on the device (Frame's
  // images are empty; timings are filled): what a viewer or a benchmark needs.
  Frame render_next(const Scene& scene, bool read_back = true);

  // The cloud density field averaged per altitude over a square of the ground centred below
  // the camera, one weather-map tile (clouds.weather_period_m) on a side: how the clouds are
  // distributed in height (each cloud type's vertical profile). Validates the scene.
  // The cloud field for queries from the CPU (nephele/cloud_query.h): the noise textures of
  // scene.noise_seed read back once (made first if this renderer has not made them).
  CloudQuery cloud_query(const Scene& scene);
  CloudProfile cloud_profile(const Scene& scene);

  // The reference path tracer (unbiased: delta and ratio tracking, next-event estimation
  // towards the lights, the phase functions sampled). Of the scene's lab when it has one
  // (Scene::lab: a density grid in vacuum), else of what the fast mode renders: the
  // atmosphere (Rayleigh, Mie, ozone; all orders), the noise and voxel clouds, the Lambertian
  // ground, the sun and the moon (no cirrus, no stars, no moon disk; conditions off).
  // Progressive: options.spp samples per pixel (on the planet rounded up to a multiple of 3:
  // each path carries one colour channel), or fewer when options.time_limit_s runs out.
  // Throws InputError for an invalid scene, one the tracer cannot render (cirrus,
  // conditions), or options out of range.
  ReferenceImage render_reference(const Scene& scene, const ReferenceOptions& options = {});

  const std::string& device_name() const;
  // Number of validation-layer messages (warnings and errors) seen so far.
  int validation_messages() const;

 private:
  Frame render_frame(const Scene& scene, bool still, bool read_back, bool sky_cover = true);
  FilmLayers render_tiles(const Scene& scene, const Tiling& tiling, bool layers);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nephele

// nephele — voxel clouds: the procedural presets of `nephele make-cloud`: clusters of
// metaballs shaped like the kind of cloud, eroded at their surface by Curly-Alligator noise.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "nephele/error.h"
#include "nephele_embedded.h"
#include "voxel/common.h"
#include "voxel/level_set.h"
#include "voxel/voxel_grid.h"

namespace nephele_data {
extern const EmbeddedFile kFiles[];
extern const size_t kFileCount;
}  // namespace nephele_data

namespace nephele::voxel {
namespace {

// splitmix64: the same numbers for the same seed on every platform (std's distributions are
// not specified bit for bit).
class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  float uniform(float lo, float hi) { return lo + (hi - lo) * float(next() >> 40) / 16777216.0f; }

 private:
  uint64_t state_;
};

struct Ball {
  glm::vec3 centre_m;
  float radius_m;
};

// A cloud's shape: metaballs blended by a polynomial smooth minimum of their distances, so
// the field stays a distance (m) and the erosion skin a thickness; an optional flattened
// ellipsoid (the anvil); cut flat at the base (z = 0) and at the top (the tropopause).
struct Shape {
  std::vector<Ball> balls;
  float blend_m = 0.0f;
  bool has_anvil = false;
  glm::vec3 anvil_centre_m{0.0f}, anvil_radii_m{1.0f};
  float top_m = 1e30f;
  float skin_m = 100.0f;  // the erosion's depth
  float noise_frequency_per_m = 0.01f;

  // The distance to the sides and top, without the flat base (which is not eroded).
  float side_distance(glm::vec3 p) const {
    float d = 1e30f;
    const float k = blend_m;
    const auto smin = [k](float a, float b) {
      const float h = std::max(k - std::fabs(a - b), 0.0f) / k;
      return std::min(a, b) - h * h * k * 0.25f;
    };
    for (const Ball& b : balls) d = smin(d, glm::length(p - b.centre_m) - b.radius_m);
    if (has_anvil) {
      // An ellipsoid's distance, nearly (Quilez's bound k0 (k0 - 1) / k1): a scaled sphere's
      // would thin the skin along the long axes and erode the anvil to half its width.
      const glm::vec3 q = p - anvil_centre_m;
      const float k0 = glm::length(q / anvil_radii_m);
      const float k1 = glm::length(q / (anvil_radii_m * anvil_radii_m));
      d = smin(d, k1 > 0.0f ? k0 * (k0 - 1.0f) / k1 : -anvil_radii_m.z);
    }
    return std::max(d, p.z - top_m);
  }

  // Bounds of the shape (the blend grows it by at most blend / 4).
  void bounds(glm::vec3& lo, glm::vec3& hi) const {
    lo = glm::vec3(1e30f);
    hi = glm::vec3(-1e30f);
    for (const Ball& b : balls) {
      lo = glm::min(lo, b.centre_m - b.radius_m);
      hi = glm::max(hi, b.centre_m + b.radius_m);
    }
    if (has_anvil) {
      lo = glm::min(lo, anvil_centre_m - anvil_radii_m);
      hi = glm::max(hi, anvil_centre_m + anvil_radii_m);
    }
    lo -= 0.25f * blend_m;
    hi += 0.25f * blend_m;
    lo.z = 0.0f;
    hi.z = std::min(hi.z, top_m);
  }
};

// A rising tower of metaballs: levels from the base to `top_m`, narrowing from `base_radius_m`
// to `top_radius_m`, leaning downwind, with bulges on its flanks (the cauliflower turrets).
void add_tower(Shape& shape, Random& rng, glm::vec2 axis_m, float top_m, float base_radius_m,
               float top_radius_m, int levels, glm::vec2 lean_m) {
  for (int l = 0; l < levels; ++l) {
    const float t = levels == 1 ? 1.0f : float(l) / float(levels - 1);
    const float r = (base_radius_m + (top_radius_m - base_radius_m) * t) * rng.uniform(0.85f, 1.1f);
    // The lowest ball's centre sits low so the base cut leaves a wide flat bottom; the highest
    // reaches the top.
    const float z = 0.35f * base_radius_m + (top_m - r - 0.35f * base_radius_m) * t;
    const glm::vec2 xy =
        axis_m + lean_m * t + glm::vec2(rng.uniform(-0.2f, 0.2f), rng.uniform(-0.2f, 0.2f)) * r;
    shape.balls.push_back({glm::vec3(xy, z), r});
    const int bulges = 4 + int(rng.next() % 3);
    for (int b = 0; b < bulges; ++b) {
      const float angle = rng.uniform(0.0f, 6.2831853f);
      const float up = rng.uniform(-0.2f, 0.6f);
      const glm::vec3 dir = glm::normalize(glm::vec3(std::cos(angle), std::sin(angle), up));
      const float br = r * rng.uniform(0.3f, 0.55f);
      shape.balls.push_back({glm::vec3(xy, z) + dir * (r * 0.75f), br});
    }
  }
}

Shape make_shape(CloudPreset preset, uint32_t seed) {
  Random rng(0x6E657068656C65ull ^ (uint64_t(seed) << 8) ^ uint64_t(preset));
  Shape s;
  const float wind = rng.uniform(0.0f, 6.2831853f);
  const glm::vec2 downwind(std::cos(wind), std::sin(wind));
  switch (preset) {
    case CloudPreset::Cumulus: {
      // ~1 km wide and tall: a dome on a flat base with a few lower cells beside it.
      s.blend_m = 120.0f;
      add_tower(s, rng, glm::vec2(0.0f), 1000.0f, 420.0f, 220.0f, 4, downwind * 60.0f);
      const int cells = 2 + int(rng.next() % 3);
      for (int c = 0; c < cells; ++c) {
        const float a = rng.uniform(0.0f, 6.2831853f);
        add_tower(s, rng, 300.0f * glm::vec2(std::cos(a), std::sin(a)), rng.uniform(450.0f, 700.0f),
                  220.0f, 140.0f, 2, glm::vec2(0.0f));
      }
      s.skin_m = 80.0f;
      break;
    }
    case CloudPreset::CumulusCongestus: {
      // ~2 km wide, ~3 km tall: a main tower and younger towers around it.
      s.blend_m = 200.0f;
      add_tower(s, rng, glm::vec2(0.0f), 3000.0f, 620.0f, 450.0f, 7, downwind * 200.0f);
      const int towers = 2 + int(rng.next() % 2);
      for (int c = 0; c < towers; ++c) {
        const float a = rng.uniform(0.0f, 6.2831853f);
        add_tower(s, rng, rng.uniform(450.0f, 600.0f) * glm::vec2(std::cos(a), std::sin(a)),
                  rng.uniform(1400.0f, 2400.0f), 420.0f, 320.0f, 4, downwind * 100.0f);
      }
      s.skin_m = 150.0f;
      break;
    }
    case CloudPreset::Cumulonimbus: {
      // ~9 km tall: a broad tower into a flat anvil at the tropopause, spread downwind to
      // ~6 km across, with lower cells feeding it.
      s.blend_m = 700.0f;
      add_tower(s, rng, glm::vec2(0.0f), 8600.0f, 1500.0f, 1000.0f, 8, downwind * 400.0f);
      const int cells = 2 + int(rng.next() % 3);
      for (int c = 0; c < cells; ++c) {
        const float a = rng.uniform(0.0f, 6.2831853f);
        add_tower(s, rng, rng.uniform(1300.0f, 1700.0f) * glm::vec2(std::cos(a), std::sin(a)),
                  rng.uniform(2500.0f, 4500.0f), 800.0f, 500.0f, 3, glm::vec2(0.0f));
      }
      s.has_anvil = true;
      const glm::vec2 anvil_xy = downwind * 900.0f;
      s.anvil_centre_m = glm::vec3(anvil_xy, 8200.0f);
      s.anvil_radii_m = glm::vec3(3000.0f, 3000.0f, 1000.0f);
      s.top_m = 9000.0f;
      s.skin_m = 300.0f;
      break;
    }
    case CloudPreset::CumulusMesh:  // baked from the mesh, made in make_cloud
    case CloudPreset::Cube:
      break;
  }
  // Billows about as wide as the skin is deep.
  s.noise_frequency_per_m = 1.0f / (1.3f * s.skin_m);
  return s;
}

float smoothstep(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

}  // namespace

CloudPreset parse_cloud_preset(const std::string& name, const std::string& parameter) {
  std::string allowed;
  for (size_t i = 0; i < std::size(kCloudPresetNames); ++i) {
    if (name == kCloudPresetNames[i]) return CloudPreset(i);
    allowed += (i ? ", " : "") + std::string(kCloudPresetNames[i]);
  }
  throw InputError(parameter + " " + shorten_for_message(name) + ": must be one of " + allowed);
}

const char* cloud_preset_name(CloudPreset preset) {
  return kCloudPresetNames[size_t(preset)].data();
}

// A cube of kCubeM, density 1, in max_dim voxels a side with kPad empty ones around it: its
// faces lie on voxel boundaries.
VoxelGrid make_cube(int max_dim) {
  constexpr float kCubeM = 1000.0f;
  constexpr int kPad = 2;
  const int inner = max_dim - 2 * kPad;
  VoxelGrid grid;
  grid.dims = glm::ivec3(max_dim);
  grid.voxel_m = kCubeM / float(inner);
  grid.origin_m =
      glm::vec3(-0.5f * float(max_dim), -0.5f * float(max_dim), -float(kPad)) * grid.voxel_m;
  grid.density.assign(size_t(max_dim) * max_dim * max_dim, 0.0f);
  for (int k = kPad; k < kPad + inner; ++k)
    for (int j = kPad; j < kPad + inner; ++j)
      for (int i = kPad; i < kPad + inner; ++i) grid.density[grid.index(i, j, k)] = 1.0f;
  compute_sdf_from_density(grid);
  return grid;
}

VoxelGrid make_cloud(CloudPreset preset, uint32_t seed, int max_dim) {
  check_max_dim(max_dim);
  if (preset == CloudPreset::Cube) return make_cube(max_dim);
  if (preset == CloudPreset::CumulusMesh) {
    const EmbeddedFile* mesh =
        find_embedded(nephele_data::kFiles, nephele_data::kFileCount, "cumulus.obj");
    return voxelize_mesh_text(std::string(reinterpret_cast<const char*>(mesh->data), mesh->size),
                              "cumulus.obj", max_dim);
  }
  const Shape shape = make_shape(preset, seed);
  glm::vec3 lo, hi;
  shape.bounds(lo, hi);
  constexpr int kPad = 2;
  VoxelGrid grid;
  fit_grid(hi - lo, kPad, max_dim, grid);
  // The anchor is the base's centre: z = 0 is the cloud base.
  const glm::vec3 anchor(0.5f * (lo.x + hi.x), 0.5f * (lo.y + hi.y), 0.0f);
  const glm::vec3 centre_of_box = 0.5f * (lo + hi) - anchor;
  grid.origin_m = centre_of_box - 0.5f * glm::vec3(grid.dims) * grid.voxel_m;
  grid.origin_m.z = -kPad * grid.voxel_m;
  grid.density.assign(size_t(grid.dims.x) * grid.dims.y * grid.dims.z, 0.0f);
  // The seed moves the noise too, so two seeds differ in their billows as well.
  Random rng(seed * 0x2545F4914F6CDD1Dull + 1);
  const glm::vec3 noise_offset(rng.uniform(-5e4f, 5e4f), rng.uniform(-5e4f, 5e4f),
                               rng.uniform(-5e4f, 5e4f));
  tbb::parallel_for(0, grid.dims.z, [&](int k) {
    for (int j = 0; j < grid.dims.y; ++j)
      for (int i = 0; i < grid.dims.x; ++i) {
        const glm::vec3 p = grid.origin_m + (glm::vec3(i, j, k) + 0.5f) * grid.voxel_m + anchor;
        if (p.z <= 0.0f) continue;
        const float d = shape.side_distance(p);
        if (d >= 0.0f) continue;
        // 1 deep inside, falling to 0 at the surface over the skin; the noise eats into it
        // where it is low (remap erosion), leaving its cells' bumps standing out.
        const float inside = std::min(-d / shape.skin_m, 1.0f);
        float density = 1.0f;
        if (inside < 1.0f) {
          const float n = curly_alligator(p + noise_offset, shape.noise_frequency_per_m);
          const float erosion = 0.8f * (1.0f - n);
          density = std::clamp((inside - erosion) / (1.0f - erosion), 0.0f, 1.0f);
        }
        // A crisp, flat base: condensation starts at one height.
        density *= smoothstep(0.0f, 0.15f * shape.skin_m, p.z);
        grid.density[grid.index(i, j, k)] = density;
      }
  });
  compute_sdf_from_density(grid);
  return grid;
}

}  // namespace nephele::voxel

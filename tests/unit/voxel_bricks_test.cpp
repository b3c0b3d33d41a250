// The voxel clouds' sparse storage (voxel/bricks.h) and the sphere tracer's rules
// (shaders/common/voxel_inc.glsl) on an analytic cloud.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/glsl.h"
#include "voxel/bricks.h"

namespace {

using nephele::voxel::BrickPool;
using nephele::voxel::VoxelGrid;

// A ball of radius r (voxels) in a grid of n^3 voxels of 10 m: density 1 inside, its exact
// signed distance (m).
VoxelGrid ball(int n, float r) {
  VoxelGrid g;
  g.dims = glm::ivec3(n);
  g.voxel_m = 10.0f;
  g.origin_m = glm::vec3(-0.5f * n * g.voxel_m, -0.5f * n * g.voxel_m, 0.0f);
  g.density.resize(size_t(n) * n * n);
  g.sdf_m.resize(g.density.size());
  const glm::vec3 c(0.5f * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const float d = glm::length(glm::vec3(i, j, k) + 0.5f - c) - r;
        g.density[g.index(i, j, k)] = d < 0.0f ? 1.0f : 0.0f;
        g.sdf_m[g.index(i, j, k)] = d * g.voxel_m;
      }
  return g;
}

float exact_sdf_voxels(glm::vec3 u, int n, float r) { return glm::length(u - glm::vec3(0.5f * n)) - r; }

TEST(VoxelBricks, StoresOnlyTheBricksNearTheSurface) {
  const VoxelGrid g = ball(64, 12.0f);
  const BrickPool pool = nephele::voxel::pack_bricks({&g});
  const auto& c = pool.clouds[0];
  EXPECT_EQ(c.bricks, glm::ivec3(8));
  // The ball and a shell of a brick around it: a fraction of the 512 bricks.
  EXPECT_GT(c.stored_bricks, 20u);
  EXPECT_LT(c.stored_bricks, 200u);
  EXPECT_LT(c.bytes, size_t(64 * 64 * 64) * 4 / 2);
}

TEST(VoxelBricks, SamplingMatchesTheGridAndEmptyBricksBoundTheDistance) {
  const int n = 64;
  const float r = 12.0f;
  const VoxelGrid g = ball(n, r);
  const BrickPool pool = nephele::voxel::pack_bricks({&g});
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coord(0.5f, n - 0.5f);
  int stored = 0, empty = 0;
  for (int s = 0; s < 20000; ++s) {
    const glm::vec3 u(coord(rng), coord(rng), coord(rng));
    const glm::vec2 v = nephele::voxel::sample_bricks(pool, 0, u);
    const float exact = exact_sdf_voxels(u, n, r);
    if (v.x == 0.0f && v.y >= nephele::voxel::kStoredBrickSdfVoxels) {
      ++empty;  // an empty brick: a bound that never overestimates by a voxel
      EXPECT_LE(v.y, exact + 1.0f) << u.x << " " << u.y << " " << u.z;
    } else {
      ++stored;  // trilinear between voxel centres: within a voxel of the exact distance
      EXPECT_NEAR(v.y, exact, 1.0f) << u.x << " " << u.y << " " << u.z;
    }
  }
  EXPECT_GT(stored, 500);
  EXPECT_GT(empty, 1000);
}

// Sphere tracing with voxel_sphere_step never steps over the ball that a fine fixed-step march
// finds: over random rays, many grazing it, the tracer stops (at density > 0, as the clouds
// pass does) with the sample before the hit no later than where the fine march first finds the
// cloud (density 1/2: the binary ball's surface; it may stop earlier, in the filtered density's
// fringe), so stepping back from the hit refines the right surface, in a tenth of the fine
// march's steps.
TEST(VoxelBricks, SphereTracingNeverSkipsWhatAFineMarchFinds) {
  const int n = 64;
  const float r = 12.0f;
  const VoxelGrid g = ball(n, r);
  const BrickPool pool = nephele::voxel::pack_bricks({&g});
  const glm::vec3 centre(0.5f * n);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const float fine = 0.05f;      // the reference march's step (voxels)
  const float min_step = 0.5f;   // the tracer's shortest step (voxels), as the march's sampling
  int hits = 0, grazing = 0;
  long traced_steps = 0, reference_steps = 0;
  for (int ray = 0; ray < 2000; ++ray) {
    // From a point on the box's boundary region towards a point near the ball's rim.
    glm::vec3 from(unit(rng), unit(rng), unit(rng));
    from = centre + glm::normalize(from) * (0.5f * n - 1.0f);
    glm::vec3 target(unit(rng), unit(rng), unit(rng));
    target = centre + glm::normalize(target) * (r + 1.5f * unit(rng));
    const glm::vec3 dir = glm::normalize(target - from);
    const float length = glm::length(target - from) + r;
    auto density = [&](float t) { return nephele::voxel::sample_bricks(pool, 0, from + dir * t).x; };
    float reference = -1.0f;
    for (float t = 0.0f; t < length; t += fine)
      if (density(t) >= 0.5f) {
        reference = t;
        break;
      }
    // The shader's tracer: its shortest step doubles while the ray runs along the surface
    // (voxel_min_step_m), up to a coarse step of six.
    float traced = -1.0f, before = 0.0f;  // the hit, and the sample before it
    int steps = 0, slow = 0;
    for (float t = 0.0f; t < length;) {
      if (density(t) > 0.0f) {
        traced = t;
        break;
      }
      before = t;
      const float sdf = nephele::voxel::sample_bricks(pool, 0, from + dir * t).y;
      const float shortest = nephele::glsl::voxel_min_step_m(min_step, 6.0f * min_step, slow);
      slow = sdf - 1.0f < shortest ? slow + 1 : 0;
      t += nephele::glsl::voxel_sphere_step(sdf, 1.0f, shortest);
      ++steps;
    }
    if (reference < 0.0f) continue;  // missed, or only the fringe: either may stop there
    ++hits;
    // A grazing ray: its closest approach to the centre within a voxel of the rim.
    const float closest = glm::length(glm::cross(centre - from, dir));
    if (closest > r - 2.0f) ++grazing;
    ASSERT_GE(traced, 0.0f) << "ray " << ray << " skipped the ball (closest approach " << closest << ")";
    // The march steps back to the sample before the hit and refines: it lies before the surface.
    EXPECT_LE(before, reference + fine) << "ray " << ray;
    traced_steps += steps;
    reference_steps += int(reference / fine);
  }
  EXPECT_GT(hits, 500);
  EXPECT_GT(grazing, 50);
  EXPECT_LT(traced_steps * 10, reference_steps);
}

TEST(VoxelBricks, TheShortestStepDoublesAlongASurfaceUpToTheCoarseStep) {
  namespace g = nephele::glsl;
  EXPECT_FLOAT_EQ(g::voxel_min_step_m(10.0f, 60.0f, 0), 10.0f);
  EXPECT_FLOAT_EQ(g::voxel_min_step_m(10.0f, 60.0f, 1), 20.0f);
  EXPECT_FLOAT_EQ(g::voxel_min_step_m(10.0f, 60.0f, 2), 40.0f);
  EXPECT_FLOAT_EQ(g::voxel_min_step_m(10.0f, 60.0f, 3), 60.0f);
  EXPECT_FLOAT_EQ(g::voxel_min_step_m(10.0f, 60.0f, 1000), 60.0f);
}

TEST(VoxelSdfCone, VisibilityFollowsTheSeedsFormula) {
  namespace g = nephele::glsl;
  // Passing an occluder 10 m away 200 m along the ray with tan = 0.1: 10 / 20 of the cone open.
  EXPECT_FLOAT_EQ(g::sdf_cone_visibility(1.0f, 10.0f, 200.0f, 0.1f), 0.5f);
  EXPECT_FLOAT_EQ(g::sdf_cone_visibility(0.3f, 10.0f, 200.0f, 0.1f), 0.3f);  // the least so far
  EXPECT_FLOAT_EQ(g::sdf_cone_visibility(1.0f, 50.0f, 200.0f, 0.1f), 1.0f);
  EXPECT_FLOAT_EQ(g::sdf_cone_visibility(1.0f, -1.0f, 200.0f, 0.1f), 0.0f);  // inside: dark
  // A wider cone (larger LightTangent) gives the same occluder a softer, darker penumbra.
  EXPECT_LT(g::sdf_cone_visibility(1.0f, 10.0f, 200.0f, 0.2f), 0.5f);
}

TEST(VoxelBox, DistanceIsZeroInsideAndEuclideanOutside) {
  namespace g = nephele::glsl;
  const glm::vec3 dims(10, 20, 30);
  EXPECT_FLOAT_EQ(g::voxel_box_distance(glm::vec3(5, 5, 5), dims), 0.0f);
  EXPECT_FLOAT_EQ(g::voxel_box_distance(glm::vec3(13, 5, 5), dims), 3.0f);
  EXPECT_FLOAT_EQ(g::voxel_box_distance(glm::vec3(-3, -4, 5), dims), 5.0f);
}

}  // namespace

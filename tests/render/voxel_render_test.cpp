// Voxel clouds rendered among the noise clouds (render/modules/voxel_clouds.h).
#include <gtest/gtest.h>

#include <cstdlib>

#include "nephele/image.h"
#include "render_fixture.h"

namespace {

using nephele::Scene;

// A cumulus preset 6 km north of the camera, its base at 1.2 km, seen from the ground at noon
// under a thin noise layer.
Scene voxel_scene(int width = 160, int height = 96) {
  Scene s;
  s.output.width = width;
  s.output.height = height;
  s.camera.position_m = {0.0f, 0.0f, 2.0f};
  s.camera.view_dir = {0.0f, 1.0f, 0.12f};
  s.camera.fov_deg = 60.0f;
  s.sun.direction = {0.3f, -0.5f, 0.8f};
  s.clouds.coverage = 0.3f;
  nephele::VoxelCloudParams c;
  c.preset = "cumulus";
  c.seed = 3;
  c.position_m = {0.0f, 6000.0f, 1200.0f};
  c.resolution = 64;
  s.voxel_clouds.push_back(c);
  return s;
}

class VoxelRender : public RenderTest {};

TEST_F(VoxelRender, DevLook) {
  if (!std::getenv("NEPHELE_DEV_LOOK")) GTEST_SKIP();
  Scene s = voxel_scene(480, 288);
  if (const char* d = std::getenv("NEPHELE_DEV_DIST")) s.voxel_clouds[0].position_m.y = std::atof(d);
  s.camera.view_dir = {0.0f, 1.0f, 0.25f};
  for (int mode = 0; mode < 4; ++mode) {
    s.quality.voxel_march = mode & 1 ? nephele::VoxelMarch::ThreePhase : nephele::VoxelMarch::Plain;
    s.quality.voxel_shadow = mode & 2 ? nephele::VoxelShadow::SdfCone : nephele::VoxelShadow::LightMarch;
    const nephele::Frame f = render(s);
    nephele::write_image(f.color, "/tmp/vox_" + std::to_string(mode) + ".png", s.output.exposure);
    std::printf("mode %d: %.1f ms, mean luminance %.4f, voxel bytes %zu\n", mode, f.stats.frame_ms,
                f.stats.mean_luminance, f.stats.voxel_bytes);
  }
}

}  // namespace

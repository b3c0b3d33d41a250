// The frame API (nephele/frame.h) as a host uses it: the test owns the Vulkan instance, device,
// queue, command buffers and fences, with validation and synchronisation validation on, and
// keeps two frames in flight.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "nephele/error.h"
#include "nephele/exposure.h"
#include "nephele/frame.h"
#include "nephele/image.h"
#include "nephele/renderer.h"
#include "nephele/scene_io.h"
#include "render/modules/cloud_diffusion/cloud_diffusion.h"
#include "render/modules/light_volume/light_volume.h"
#include "support/vulkan_host.h"

namespace {

using nephele_test::Host;
using nephele_test::Readback;

nephele::Scene small_scene() {
  nephele::Scene scene = nephele::load_preset("default");
  scene.output.width = 40;
  scene.output.height = 28;
  scene.output.tonemap = nephele::ToneMap::Agx;  // the display follows the scene's tone map
  return scene;
}

TEST(FrameApi, TwoFramesInFlightOnTheHostsDeviceWithSynchronisationValidation) {
  Host host;
  ASSERT_NE(host.vk.device, VK_NULL_HANDLE) << "no Vulkan device with validation";
  nephele::Scene scene = small_scene();
  const int frames = 6;
  nephele::FrameImages last;
  VkDeviceSize bytes = VkDeviceSize(scene.output.width) * scene.output.height * 4;
  Readback display(host.vk, bytes);
  {
    nephele::FrameRenderer sky(host.vk);
    ASSERT_EQ(sky.frames_in_flight(), 2);
    EXPECT_FALSE(sky.completed_stats().has_value());
    for (int i = 0; i < frames; ++i) {
      const int slot = i % sky.frames_in_flight();
      VkCommandBuffer cmd = host.begin(slot);
      scene.time_s += 0.1f;
      scene.camera.position_m.x += 5.0f;
      // Every other frame with the host's lighting and shadow map: their passes and read-backs
      // under synchronisation validation too.
      nephele::FrameOptions options;
      options.lighting.enabled = i % 2 == 0;
      options.lighting.shadow_map_size = 32;
      last = sky.record_frame(cmd, scene, options);
      EXPECT_EQ(last.cloud_shadow != VK_NULL_HANDLE, options.lighting.enabled);
      EXPECT_EQ(last.slot, slot);
      if (i == frames - 1) {  // the host copies the display image after the frame's barrier
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {last.width, last.height, 1};
        vkCmdCopyImageToBuffer(cmd, last.display, VK_IMAGE_LAYOUT_GENERAL, display.buffer, 1,
                               &region);
        VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0,
                             1, &to_host, 0, nullptr, 0, nullptr);
      }
      host.submit(slot);
      if (i >= 2) {  // the slot reused: the frame two before is collected
        ASSERT_TRUE(sky.completed_stats().has_value()) << "frame " << i;
        EXPECT_GT(sky.completed_stats()->passes.size(), 4u);
        EXPECT_EQ(sky.completed_stats()->width, scene.output.width);
        // The frame collected is two before: lit when this one is.
        EXPECT_EQ(sky.completed_lighting().has_value(), options.lighting.enabled) << "frame " << i;
        if (sky.completed_lighting()) EXPECT_GT(sky.completed_lighting()->sky_irradiance_lux({0, 0, 1}).g, 100.0f);
      }
    }
    vkWaitForFences(host.vk.device, 2, host.fence, VK_TRUE, UINT64_MAX);

    // The display image the host copied is the HDR image as the PNG writer encodes it.
    const nephele::Frame frame = sky.read_back();
    ASSERT_EQ(frame.color.width, scene.output.width);
    const std::vector<unsigned char> expected =
        nephele::tonemap_srgb8(frame.color, float(nephele::exposure_from_ev100(scene.output.ev100)),
                               scene.output.tonemap);
    const auto* got = static_cast<const unsigned char*>(display.mapped);
    int worst = 0;
    for (size_t i = 0; i < expected.size(); ++i)
      worst = std::max(worst, std::abs(int(got[i]) - int(expected[i])));
    EXPECT_LE(worst, 1) << "display image against tonemap_srgb8 of the HDR image";

    // An invalid scene records nothing and throws; the last valid one keeps rendering.
    nephele::Scene bad = scene;
    bad.clouds.coverage = 1.5f;
    VkCommandBuffer cmd = host.begin(0);
    EXPECT_THROW(sky.record_frame(cmd, bad), nephele::InputError);
    sky.record_frame(cmd, scene);
    host.submit(0);
    vkDeviceWaitIdle(host.vk.device);
  }
  EXPECT_EQ(host.messages, 0);
}

// A paused view (FrameOptions::reuse_settled): once the same scene has been recorded for
// 2 x march_stride^2 frames (every pixel marched twice), the last frame's images are handed out
// again and nothing is recorded; any change (here the camera) renders again, and settles again.
TEST(FrameApi, APausedViewReusesItsSettledFrame) {
  Host host;
  ASSERT_NE(host.vk.device, VK_NULL_HANDLE) << "no Vulkan device with validation";
  nephele::Scene scene = small_scene();
  scene.quality.march_stride = 2;  // settled after 8 frames
  {
    nephele::FrameRenderer sky(host.vk);
    nephele::FrameOptions options;
    options.reuse_settled = true;
    std::vector<bool> reused;
    nephele::FrameImages last;
    for (int i = 0; i < 22; ++i) {
      if (i == 11) scene.camera.position_m.x += 5.0f;
      const int slot = i % sky.frames_in_flight();
      VkCommandBuffer cmd = host.begin(slot);
      const nephele::FrameImages images = sky.record_frame(cmd, scene, options);
      host.submit(slot);
      vkWaitForFences(host.vk.device, 1, &host.fence[slot], VK_TRUE, UINT64_MAX);
      reused.push_back(images.reused);
      if (images.reused) {  // the last frame's images, as they were
        EXPECT_EQ(images.slot, last.slot) << "frame " << i;
        EXPECT_EQ(images.display, last.display) << "frame " << i;
      }
      last = images;
    }
    // Frames 0-7 and, after the change at 11, 11-18 are recorded.
    for (int i = 0; i < 22; ++i)
      EXPECT_EQ(reused[size_t(i)], (i >= 8 && i < 11) || i >= 19) << "frame " << i;
    // A still, or the host's lighting, is always recorded.
    VkCommandBuffer cmd = host.begin(0);
    options.lighting.enabled = true;
    options.lighting.shadow_map_size = 32;
    EXPECT_FALSE(sky.record_frame(cmd, scene, options).reused);
    host.submit(0);
    vkDeviceWaitIdle(host.vk.device);
  }
  EXPECT_EQ(host.messages, 0);
}

// A paused view waits for the lighting it is building: after an edit of the clouds with the
// diffusion light, the light volume and then the field are rebuilt over frames (48 after an
// edit), and no frame is reused before they are done, although the scene is unchanged for
// longer than the 8 frames that settle it; 8 frames after, it settles.
TEST(FrameApi, APausedViewWaitsForTheLightingItBuilds) {
  Host host;
  ASSERT_NE(host.vk.device, VK_NULL_HANDLE) << "no Vulkan device with validation";
  nephele::Scene scene = small_scene();
  scene.quality.march_stride = 2;  // settled after 8 frames
  scene.clouds.optics = "droplets";
  scene.clouds.lighting = "diffusion";
  const int built = nephele::kLightVolumeEditFrames + 2 * nephele::kDiffusionEditFrames;
  {
    nephele::FrameRenderer sky(host.vk);
    nephele::FrameOptions options;
    options.reuse_settled = true;
    std::vector<bool> reused;
    for (int i = 0; i < 12 + built + 10; ++i) {
      if (i == 12) scene.clouds.coverage += 0.1f;  // an edit, once the view has settled
      const int slot = i % sky.frames_in_flight();
      VkCommandBuffer cmd = host.begin(slot);
      reused.push_back(sky.record_frame(cmd, scene, options).reused);
      host.submit(slot);
      vkWaitForFences(host.vk.device, 1, &host.fence[slot], VK_TRUE, UINT64_MAX);
    }
    EXPECT_TRUE(reused[11]);  // settled before the edit
    for (int i = 12; i < 12 + built; ++i) EXPECT_FALSE(reused[size_t(i)]) << "frame " << i;
    EXPECT_TRUE(reused.back());  // and after its lighting is built
  }
  EXPECT_EQ(host.messages, 0);
}

// The check above can fail: the same host reports a hazard of its own (two writes to one
// buffer with no barrier between them).
TEST(FrameApi, SynchronisationValidationSeesAHazard) {
  Host host;
  ASSERT_NE(host.vk.device, VK_NULL_HANDLE);
  Readback target(host.vk, 256);
  VkCommandBuffer cmd = host.begin(0);
  vkCmdFillBuffer(cmd, target.buffer, 0, 256, 1u);
  vkCmdFillBuffer(cmd, target.buffer, 0, 256, 2u);
  host.submit(0);
  vkDeviceWaitIdle(host.vk.device);
  EXPECT_GT(host.messages, 0);
}

// A still with a progress callback is marched in bands of rows, each reported; the image is the
// one made in a single submission.
TEST(FrameApi, StillsReportProgressAndGiveTheSameImage) {
  nephele::Scene scene = small_scene();
  scene.output.height = 40;  // 2 bands of 16 rows and the rest
  std::vector<std::string> calls;
  nephele::RendererOptions options;
  options.validation = true;
  options.progress = [&](std::string_view stage, int done, int total) {
    calls.push_back(std::string(stage) + " " + std::to_string(done) + "/" + std::to_string(total));
  };
  nephele::Renderer with(options);
  const nephele::Frame banded = with.render(scene);
  const std::vector<std::string> expected = {"noise 0/3",  "noise 1/3",  "noise 2/3",
                                             "noise 3/3",  "clouds 0/3", "clouds 1/3",
                                             "clouds 2/3", "clouds 3/3"};
  EXPECT_EQ(calls, expected);
  nephele::Renderer without({"", true, false, {}});
  const nephele::Frame whole = without.render(scene);
  EXPECT_EQ(banded.color.pixels, whole.color.pixels);
  bool clouds_timed = false;
  for (const nephele::PassTiming& p : banded.stats.passes) clouds_timed |= p.name == "clouds";
  EXPECT_TRUE(clouds_timed);
  EXPECT_EQ(with.validation_messages(), 0);
}

// A scene refused late (its terrain mesh passes validation, which reads no OBJ, but does not
// parse) leaves the renderer as it was: the next frame is the one a fresh renderer makes.
TEST(FrameApi, AFrameRefusedLateLeavesTheRendererAsItWas) {
  std::filesystem::create_directories(NEPHELE_TEST_OUTPUT_DIR);
  const std::string mesh = std::string(NEPHELE_TEST_OUTPUT_DIR) + "/not_a_mesh.obj";
  std::ofstream(mesh) << "this is not a mesh\n";
  nephele::Scene good = small_scene();
  nephele::Scene bad = good;
  bad.terrain.file = mesh;
  nephele::RendererOptions options;
  options.validation = true;
  nephele::Renderer refused_first(options);
  EXPECT_THROW(refused_first.render(bad), nephele::InputError);
  const nephele::Frame after = refused_first.render(good);
  nephele::Renderer fresh(options);
  const nephele::Frame expected = fresh.render(good);
  double worst = 0.0;
  for (size_t i = 0; i < expected.color.pixels.size(); ++i)
    worst = std::max(worst, double(std::abs(nephele::luminance(after.color.pixels[i]) -
                                            nephele::luminance(expected.color.pixels[i]))) /
                                std::max(double(nephele::luminance(expected.color.pixels[i])), 1.0));
  EXPECT_LT(worst, 1e-3) << "the frame after a refused one differs from a fresh renderer's";
  EXPECT_EQ(refused_first.validation_messages() + fresh.validation_messages(), 0);
}

TEST(FrameApi, RefusesNullHandlesAndCommandBuffers) {
  nephele::HostVulkan none;
  try {
    nephele::FrameRenderer sky(none);
    FAIL() << "null handles accepted";
  } catch (const nephele::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("HostVulkan"), std::string::npos) << e.what();
  }
}

// A device without what nephele needs is refused in one line naming what it lacks; the host's
// own device (lavapipe here) has it all.
TEST(FrameApi, RefusesADeviceWithoutTheVersionOrFormatsItNeeds) {
  using nephele::gpu::device_problem;
  const auto everything = [](VkFormat) { return VkFormatFeatureFlags(~0u); };
  EXPECT_EQ(device_problem("dev", VK_API_VERSION_1_3, everything), "");
  const std::string old = device_problem("HostVulkan.physical_device 'old'", VK_API_VERSION_1_1, everything);
  EXPECT_NE(old.find("Vulkan 1.1"), std::string::npos) << old;
  EXPECT_NE(old.find("needs Vulkan 1.2"), std::string::npos) << old;
  const std::string no_filter = device_problem("dev", VK_API_VERSION_1_2, [](VkFormat f) {
    return f == VK_FORMAT_R32_SFLOAT ? VkFormatFeatureFlags(VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT |
                                                            VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT)
                                     : VkFormatFeatureFlags(~0u);
  });
  EXPECT_NE(no_filter.find("VK_FORMAT_R32_SFLOAT"), std::string::npos) << no_filter;
  EXPECT_EQ(no_filter.find('\n'), std::string::npos);

  Host host;
  ASSERT_NE(host.vk.device, VK_NULL_HANDLE);
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(host.vk.physical_device, &props);
  EXPECT_EQ(device_problem("lavapipe", props.apiVersion,
                           [&](VkFormat format) {
                             VkFormatProperties p;
                             vkGetPhysicalDeviceFormatProperties(host.vk.physical_device, format, &p);
                             return p.optimalTilingFeatures;
                           }),
            "");
}

}  // namespace

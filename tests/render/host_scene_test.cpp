// The host's geometry in the frame (nephele::HostScene, issue 25): a host owns the device
// (validation and synchronisation validation on), puts a depth buffer and a colour image of its
// own scene into the frame, and nephele hides its sky behind that geometry, covers it with the
// clouds in front of it and fogs it with the air.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>
#include <string>

#include "nephele/error.h"
#include "nephele/frame.h"
#include "nephele/image.h"
#include "nephele/scene_io.h"
#include "support/vulkan_host.h"

namespace {

using nephele_test::Host;
using nephele_test::HostImage;
using nephele_test::Readback;

// The host's scene: per pixel the distance of its geometry along the view ray (m; 0 none) and
// its radiance (cd/m^2).
struct Geometry {
  std::function<float(int x, int y)> distance_m;
  std::function<glm::vec3(int x, int y)> radiance;
};

struct DepthSetup {
  VkFormat format = VK_FORMAT_D32_SFLOAT;
  bool reversed = false;
  float near_m = 1.0f, far_m = 100000.0f;
};

glm::mat4 projection_for(const nephele::Scene& scene, const DepthSetup& depth) {
  const float fov = glm::radians(nephele::vertical_fov_deg(scene));
  const float aspect = float(scene.output.width) / float(scene.output.height);
  return depth.reversed ? glm::perspectiveRH_ZO(fov, aspect, depth.far_m, depth.near_m)
                        : glm::perspectiveRH_ZO(fov, aspect, depth.near_m, depth.far_m);
}

// The depth texel a point `distance_m` along pixel (x, y)'s ray has under `projection`.
float depth_of(const glm::mat4& projection, const nephele::Scene& scene, int x, int y,
               float distance_m) {
  const glm::vec2 ndc =
      (glm::vec2(x, y) + 0.5f) / glm::vec2(scene.output.width, scene.output.height) * 2.0f - 1.0f;
  const glm::vec4 far_point = glm::inverse(projection) * glm::vec4(ndc, 0.5f, 1.0f);
  const glm::vec3 dir = glm::normalize(glm::vec3(far_point) / far_point.w);
  const glm::vec4 clip = projection * glm::vec4(dir * distance_m, 1.0f);
  return clip.z / clip.w;
}

int depth_bytes(VkFormat format) {
  return format == VK_FORMAT_D16_UNORM ? 2 : 4;
}

// The host's images of `geometry`, uploaded and left in TRANSFER_SRC_OPTIMAL.
struct HostTargets {
  HostTargets(Host& host, const nephele::Scene& scene, const Geometry& geometry,
              const DepthSetup& setup)
      : width(uint32_t(scene.output.width)),
        height(uint32_t(scene.output.height)),
        depth(host.vk, width, height, setup.format,
              VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT),
        color(host.vk, width, height, VK_FORMAT_R16G16B16A16_SFLOAT,
              VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT),
        depth_texels(host.vk, VkDeviceSize(width) * height * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT),
        color_texels(host.vk, VkDeviceSize(width) * height * 8, VK_BUFFER_USAGE_TRANSFER_SRC_BIT) {
    const glm::mat4 projection = projection_for(scene, setup);
    auto* d32 = static_cast<float*>(depth_texels.mapped);
    auto* d24 = static_cast<uint32_t*>(depth_texels.mapped);
    auto* d16 = static_cast<uint16_t*>(depth_texels.mapped);
    auto* rgba = static_cast<uint32_t*>(color_texels.mapped);
    for (int y = 0; y < int(height); ++y)
      for (int x = 0; x < int(width); ++x) {
        const size_t i = size_t(y) * width + size_t(x);
        const float d = geometry.distance_m(x, y);
        const float z = d > 0.0f ? glm::clamp(depth_of(projection, scene, x, y, d), 0.0f, 1.0f)
                                 : (setup.reversed ? 0.0f : 1.0f);
        if (setup.format == VK_FORMAT_D16_UNORM)
          d16[i] = uint16_t(std::lround(z * 65535.0f));
        else if (setup.format == VK_FORMAT_X8_D24_UNORM_PACK32)
          d24[i] = uint32_t(std::lround(z * 16777215.0));
        else
          d32[i] = z;
        const glm::vec3 c = geometry.radiance(x, y);
        rgba[2 * i] = glm::packHalf2x16(glm::vec2(c.r, c.g));
        rgba[2 * i + 1] = glm::packHalf2x16(glm::vec2(c.b, 1.0f));
      }
    VkCommandBuffer cmd = host.begin(0);
    depth.record_upload(cmd, depth_texels.buffer, VK_IMAGE_ASPECT_DEPTH_BIT, width, height,
                        VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    color.record_upload(cmd, color_texels.buffer, VK_IMAGE_ASPECT_COLOR_BIT, width, height,
                        VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    host.submit(0);
    vkDeviceWaitIdle(host.vk.device);
    scene_info.depth = depth.image;
    scene_info.depth_format = setup.format;
    scene_info.color = color.image;
    scene_info.width = width;
    scene_info.height = height;
    scene_info.projection = projection;
    scene_info.reversed_z = setup.reversed;
  }
  uint32_t width, height;
  HostImage depth, color;
  Readback depth_texels, color_texels;
  nephele::HostScene scene_info;
};

// One still frame of `scene` recorded on the host's device, with the host's scene or without.
nephele::Frame render(Host& host, nephele::FrameRenderer& sky, const nephele::Scene& scene,
                      const nephele::HostScene* host_scene) {
  nephele::FrameOptions options;
  options.still = true;
  options.host_scene = host_scene;
  VkCommandBuffer cmd = host.begin(0);
  sky.record_frame(cmd, scene, options);
  host.submit(0);
  vkDeviceWaitIdle(host.vk.device);
  return sky.read_back();
}

float luminance(const glm::vec4& c) {
  return nephele::luminance(c);
}

nephele::Scene small(const std::string& preset, glm::vec3 view_dir) {
  nephele::Scene scene = nephele::load_preset(preset);
  scene.output.width = 48;
  scene.output.height = 32;
  scene.camera.view_dir = view_dir;
  return scene;
}

TEST(HostScene, HidesTheSkyBehindTheHostsGeometryAndKeepsItsLightNearby) {
  Host host;
  ASSERT_NE(host.vk.device, VK_NULL_HANDLE);
  {
    nephele::FrameRenderer sky(host.vk);
    const nephele::Scene scene = small("default", {0.0f, 1.0f, 0.1f});
    const int h = scene.output.height;
    // A wall 200 m away over the image's lower half, 1000 cd/m^2 grey, and the same wall black
    // (the air's light alone); the sky above.
    const auto lower_half = [&](int, int y) { return y >= h / 2 ? 200.0f : 0.0f; };
    HostTargets grey(host, scene, {lower_half, [](int, int) { return glm::vec3(1000.0f); }}, {});
    HostTargets black(host, scene, {lower_half, [](int, int) { return glm::vec3(0.0f); }}, {});
    const nephele::Frame without = render(host, sky, scene, nullptr);
    const nephele::Frame with = render(host, sky, scene, &grey.scene_info);
    const nephele::Frame air = render(host, sky, scene, &black.scene_info);
    const float horizon_sky = luminance(without.color.at(scene.output.width / 2, h / 2 - 3));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < scene.output.width; ++x) {
        const float got = luminance(with.color.at(x, y)),
                    sky_only = luminance(without.color.at(x, y));
        if (y >= h / 2) {
          // 200 m of air: the wall's light through it (transmittance 0.99 to 1), the air's own
          // light added (under 1% of the horizon's), no sun, sky or ground behind it.
          const float air_light = luminance(air.color.at(x, y));
          EXPECT_GT(got - air_light, 990.0f)
              << x << "," << y << " (without the wall: " << sky_only << ")";
          EXPECT_LT(got - air_light, 1000.5f) << x << "," << y;
          EXPECT_GT(air_light, 0.0f);
          EXPECT_LT(air_light, 0.01f * horizon_sky) << x << "," << y;
        } else if (y < h / 2 - 2) {
          EXPECT_NEAR(got, sky_only, 0.01f * sky_only) << x << "," << y;
        }
      }
  }
  EXPECT_EQ(host.messages, 0);
}

TEST(HostScene, CloudsInFrontCoverTheGeometryAndGeometryInFrontCoversTheClouds) {
  Host host;
  ASSERT_NE(host.vk.device, VK_NULL_HANDLE);
  {
    nephele::FrameRenderer sky(host.vk);
    // Under an overcast deck, looking up at it: the deck is 1 to 3 km away along the rays.
    const nephele::Scene scene = small("overcast", {0.0f, 1.0f, 1.5f});
    const nephele::Frame without = render(host, sky, scene, nullptr);
    const glm::vec3 bright(5.0e4f);  // half floats reach 65504
    const Geometry far_wall{[](int, int) { return 40000.0f; }, [&](int, int) { return bright; }};
    const Geometry near_wall{[](int, int) { return 100.0f; }, [&](int, int) { return bright; }};
    HostTargets far_targets(host, scene, far_wall, {});
    const nephele::Frame behind = render(host, sky, scene, &far_targets.scene_info);
    HostTargets near_targets(host, scene, near_wall, {});
    const nephele::Frame in_front = render(host, sky, scene, &near_targets.scene_info);
    int opaque = 0;
    for (size_t i = 0; i < without.color.pixels.size(); ++i) {
      const float cloud_transmittance = without.clouds.pixels[i].a;
      const float sky_only = luminance(without.color.pixels[i]);
      if (cloud_transmittance < 0.01f) {
        ++opaque;
        // The deck hides the wall behind it: the clouds' image, with the wall 25 times
        // brighter than it behind them.
        EXPECT_NEAR(luminance(behind.color.pixels[i]), sky_only, 0.03f * sky_only) << i;
      }
      // The wall in front hides the deck.
      EXPECT_NEAR(luminance(in_front.color.pixels[i]), bright.x, 0.03f * bright.x) << i;
    }
    EXPECT_GT(opaque, int(without.color.pixels.size() / 2))
        << "the overcast deck should fill the view";
  }
  EXPECT_EQ(host.messages, 0);
}

TEST(HostScene, TheAirFogsFarGeometryAsTheAerialPerspective) {
  Host host;
  ASSERT_NE(host.vk.device, VK_NULL_HANDLE);
  {
    nephele::FrameRenderer sky(host.vk);
    // Looking 45 degrees up: the image's lower half sees 10 to 45 degrees above the horizon.
    const nephele::Scene scene = small("clear", {0.0f, 1.0f, 1.0f});
    const int w = scene.output.width, h = scene.output.height;
    // Black walls across the image's lower half: 500 m away on the left, 30 km on the right.
    const Geometry walls{[&](int x, int y) {
                           return y < h / 2 ? 0.0f : x < w / 2 ? 500.0f : 30000.0f;
                         },
                         [](int, int) { return glm::vec3(0.0f); }};
    HostTargets targets(host, scene, walls, {});
    const nephele::Frame without = render(host, sky, scene, nullptr);
    const nephele::Frame frame = render(host, sky, scene, &targets.scene_info);
    double near_share = 0.0, far_share = 0.0;
    for (int y = h / 2; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float air = luminance(frame.color.at(x, y)),
                    sky_only = luminance(without.color.at(x, y));
        (x < w / 2 ? near_share : far_share) += air / sky_only / (w / 2 * (h - h / 2));
        // 500 m of air in front of black: a few percent of the sky's light; 30 km: most of it
        // (the air's scale height is 8 km), never more than all.
        if (x < w / 2) {
          EXPECT_GT(air, 0.005f * sky_only) << x << "," << y;
          EXPECT_LT(air, 0.05f * sky_only) << x << "," << y;
        } else {
          EXPECT_GT(air, 0.5f * sky_only) << x << "," << y;
          EXPECT_LT(air, sky_only) << x << "," << y;
        }
      }
    std::printf(
        "the air's light in front of black, share of the sky's: %.3f at 500 m, %.3f at 30 km\n",
        near_share, far_share);
  }
  EXPECT_EQ(host.messages, 0);
}

TEST(HostScene, EveryDepthFormatAndReversedDepthGiveTheSameFrame) {
  Host host;
  ASSERT_NE(host.vk.device, VK_NULL_HANDLE);
  {
    nephele::FrameRenderer sky(host.vk);
    const nephele::Scene scene = small("default", {0.0f, 1.0f, 0.1f});
    const int h = scene.output.height;
    const Geometry wall{[&](int x, int y) { return y >= h / 2 ? 300.0f + 40.0f * float(x) : 0.0f; },
                        [](int x, int) { return glm::vec3(50.0f * float(x), 800.0f, 300.0f); }};
    HostTargets reference_targets(host, scene, wall, {});
    const nephele::Frame reference = render(host, sky, scene, &reference_targets.scene_info);
    const DepthSetup setups[] = {{VK_FORMAT_D32_SFLOAT, true, 1.0f, 100000.0f},
                                 {VK_FORMAT_X8_D24_UNORM_PACK32, false, 10.0f, 5000.0f},
                                 {VK_FORMAT_D16_UNORM, false, 100.0f, 5000.0f}};
    for (const DepthSetup& setup : setups) {
      HostTargets targets(host, scene, wall, setup);
      const nephele::Frame frame = render(host, sky, scene, &targets.scene_info);
      for (size_t i = 0; i < frame.color.pixels.size(); ++i)
        EXPECT_NEAR(luminance(frame.color.pixels[i]), luminance(reference.color.pixels[i]),
                    0.01f * luminance(reference.color.pixels[i]) + 1e-3f)
            << "format " << int(setup.format) << " reversed " << setup.reversed << " pixel " << i;
    }
  }
  EXPECT_EQ(host.messages, 0);
}

TEST(HostScene, MisuseIsRefusedNamingTheFieldAndRecordsNothing) {
  Host host;
  ASSERT_NE(host.vk.device, VK_NULL_HANDLE);
  {
    nephele::FrameRenderer sky(host.vk);
    const nephele::Scene scene = small("default", {0.0f, 1.0f, 0.1f});
    const Geometry wall{[](int, int) { return 100.0f; },
                        [](int, int) { return glm::vec3(2000.0f); }};
    HostTargets targets(host, scene, wall, {});
    struct Case {
      std::string field;
      std::function<void(nephele::HostScene&)> spoil;
    };
    const Case cases[] = {
        {"host_scene.depth", [](nephele::HostScene& s) { s.depth = VK_NULL_HANDLE; }},
        {"host_scene.color", [](nephele::HostScene& s) { s.color = VK_NULL_HANDLE; }},
        {"host_scene.depth_format",
         [](nephele::HostScene& s) { s.depth_format = VK_FORMAT_R32_SFLOAT; }},
        {"host_scene.color_format",
         [](nephele::HostScene& s) { s.color_format = VK_FORMAT_R8G8B8A8_UNORM; }},
        {"host_scene.layout",
         [](nephele::HostScene& s) {
           s.layout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
         }},
        {"host_scene.width x height", [](nephele::HostScene& s) { s.width += 1; }},
        {"host_scene.color_scale", [](nephele::HostScene& s) { s.color_scale = -1.0f; }},
        {"host_scene.projection's vertical field of view",
         [&](nephele::HostScene& s) {
           s.projection = glm::perspectiveRH_ZO(glm::radians(60.0f), 1.5f, 1.0f, 1e5f);
         }},
        {"host_scene.projection's aspect",
         [&](nephele::HostScene& s) {
           s.projection = glm::perspectiveRH_ZO(glm::radians(nephele::vertical_fov_deg(scene)),
                                                1.0f, 1.0f, 1e5f);
         }},
        {"host_scene.projection is not a perspective",
         [](nephele::HostScene& s) { s.projection = glm::mat4(1.0f); }},
        {"host_scene.reversed_z is true", [](nephele::HostScene& s) { s.reversed_z = true; }},
    };
    VkCommandBuffer cmd = host.begin(0);
    for (const Case& c : cases) {
      nephele::HostScene spoilt = targets.scene_info;
      c.spoil(spoilt);
      nephele::FrameOptions options;
      options.host_scene = &spoilt;
      try {
        sky.record_frame(cmd, scene, options);
        ADD_FAILURE() << c.field << ": accepted";
      } catch (const nephele::InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(c.field), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      }
    }
    // Nothing was recorded: the command buffer takes a valid frame and runs clean.
    nephele::FrameOptions options;
    options.host_scene = &targets.scene_info;
    sky.record_frame(cmd, scene, options);
    host.submit(0);
    vkDeviceWaitIdle(host.vk.device);
    EXPECT_NEAR(luminance(sky.read_back().color.at(10, 10)), 2000.0f, 100.0f);
  }
  EXPECT_EQ(host.messages, 0);
}

}  // namespace

// nephele — the frame API, for hosts that own Vulkan (engines, simulators, nephele-view).
//
// The one public header that speaks Vulkan. A host creates a FrameRenderer on its own device
// (or lets nephele make one), and each frame asks it to *record* the frame's passes into a
// command buffer the host owns and submits. Nothing inside record_frame() waits for the device
// except the rare one-off work listed there; with frames in flight the host prepares frame N+1
// on the CPU while the device still renders frame N.
//
//   nephele::FrameRenderer sky(host);                 // host: a HostVulkan of the engine
//   ...every frame, slot = frame % sky.frames_in_flight():
//   wait for fence[slot]; vkResetFences; vkBeginCommandBuffer(cmd[slot], ...);
//   nephele::FrameImages out = sky.record_frame(cmd[slot], scene);
//   ...blit or sample out.display (or out.hdr) into the engine's frame...
//   vkEndCommandBuffer(cmd[slot]); vkQueueSubmit(queue, ..., fence[slot]);
#pragma once

#include <vulkan/vulkan.h>

#include <memory>
#include <optional>

#include <glm/mat4x4.hpp>

#include "nephele/cloud_query.h"
#include "nephele/renderer.h"
#include "nephele/scene.h"

namespace nephele {

// The host's Vulkan objects; they must outlive the FrameRenderer. The device must support
// Vulkan 1.2 and `queue_family` compute and transfer work. nephele submits its own one-off
// work (start-up noise, table rebuilds, uploads) to `queue` from the thread that calls it, and
// waits for it: the host must not use `queue` from another thread during a FrameRenderer call.
struct HostVulkan {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queue_family = 0;
  VkQueue queue = VK_NULL_HANDLE;
};

// The host's own scene, drawn by the host before record_frame() into a depth buffer and a
// linear HDR colour image of the frame's size, from the scene's camera (scene.camera: its
// position, orientation and field of view) and a perspective projection of that field of view.
// nephele composites its sky and clouds with it: the sky, the clouds, the sun, moon and stars
// behind the host's geometry are hidden, the clouds in front of it cover it, and the air
// between the camera and the geometry fogs it (the aerial perspective and the light shafts),
// as the terrain of [terrain] is. The frame's images (FrameImages) then hold the whole frame,
// the host's geometry in it, exposed and tone-mapped with it.
//
// record_frame() copies both images (vkCmdCopyImageToBuffer): they need
// VK_IMAGE_USAGE_TRANSFER_SRC_BIT and must be in `layout` when the command buffer reaches the
// frame's commands. nephele records the barrier from the host's attachment writes (and shader
// and transfer writes) to its copies itself; the images keep their layout.
struct HostScene {
  VkImage depth = VK_NULL_HANDLE;
  // VK_FORMAT_D32_SFLOAT, D32_SFLOAT_S8_UINT, X8_D24_UNORM_PACK32, D24_UNORM_S8_UINT or D16_UNORM.
  VkFormat depth_format = VK_FORMAT_D32_SFLOAT;
  // The geometry's radiance (cd/m^2, times color_scale), linear: the units of FrameImages::hdr.
  // A host lit by the frame's sun and sky lighting in lux (or scaled to it) fits. rgb read.
  VkImage color = VK_NULL_HANDLE;
  VkFormat color_format = VK_FORMAT_R16G16B16A16_SFLOAT;  // or VK_FORMAT_R32G32B32A32_SFLOAT
  float color_scale = 1.0f;
  // Both images': VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL or VK_IMAGE_LAYOUT_GENERAL.
  VkImageLayout layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  uint32_t width = 0, height = 0;  // both images'; must be scene.output's
  // The host's projection (view space in metres to Vulkan clip space, depth in [0, 1]): its
  // field of view and aspect must be the scene camera's (within 1%). Any handedness, a finite
  // or infinite far plane. reversed_z: the far plane at depth 0 (cleared to 0); else at 1.
  glm::mat4 projection{1.0f};
  bool reversed_z = false;
};

// What a host asks of the frame for lighting its own scene (FrameOptions::lighting).
struct HostLightingOptions {
  bool enabled = false;  // HostLighting, the cloud shadow map and the environment; off: none is made
  // The cloud shadow map's square, its side (m, [100, 1e6]) and texels a side ([8, 4096]).
  float shadow_map_extent_m = 20000.0f;
  uint32_t shadow_map_size = 256;
  // The environment cube map's faces, texels a side ([4, 256]).
  uint32_t environment_size = 32;
};

// The light at the camera, for the host to light its own scene as nephele lights its terrain
// (FrameRenderer::completed_lighting()). Directions in ENU (x east, y north, z up); colours
// linear rgb in the renderer's primaries, in lux and cd/m^2, the units of FrameImages::hdr.
struct HostLighting {
  // The sun's and the moon's direction (towards them) and their illuminance on a surface facing
  // them at the camera, after the air and the clouds (0 below the horizon; the moon's 0 without
  // a date and place, scene.time), and the share the clouds pass.
  glm::vec3 sun_direction{0.0f, 0.0f, 1.0f};
  glm::vec3 sun_illuminance_lux{0.0f};
  float sun_cloud_transmittance = 1.0f;
  glm::vec3 moon_direction{0.0f, 0.0f, 1.0f};
  glm::vec3 moon_illuminance_lux{0.0f};
  float moon_cloud_transmittance = 1.0f;
  // The light that reaches the camera's place from every direction but the sun's and the
  // moon's discs (the sky above, the lit ground below), dimmed under the clouds as nephele's
  // terrain's sky light is: nine real spherical-harmonic coefficients of its radiance (cd/m^2),
  // bands 0 to 2 in the order (l, m) = (0, 0), (1, -1), (1, 0), (1, 1), (2, -2), (2, -1), (2, 0),
  // (2, 1), (2, 2), with Y_1,-1 ~ y, Y_1,0 ~ z, Y_1,1 ~ x.
  glm::vec3 sky_radiance_sh[9] = {};
  // The share of the clear sky's light that the clouds let through there (in the coefficients).
  float sky_cloud_share = 1.0f;
  // The irradiance (lux) that light gives a surface facing unit `normal` (Ramamoorthi and
  // Hanrahan 2001: the coefficients convolved with the clamped cosine).
  glm::vec3 sky_irradiance_lux(const glm::vec3& normal) const;
  // The clouds' extinction at the camera (1/m; 0 outside them) and the meteorological
  // visibility there (m): Koschmieder's 3.912 / sigma_t at 550 nm, the air's and the clouds'.
  float cloud_sigma_t_per_m = 0.0f;
  bool inside_cloud = false;
  float visibility_m = 0.0f;
};

struct FrameOptions {
  // true: every cloud pixel is marched at full resolution (as Renderer::render); false: one
  // pixel of each quality.march_stride^2 block, the others reprojected from the history (as
  // Renderer::render_next).
  bool still = false;
  // false: the display image is not made this frame (it keeps what it held), for a host that
  // reads only `hdr` (Renderer reads the HDR image back and tone-maps files itself).
  bool display = true;
  // The host's geometry to composite with (above), or none. With it a still frame is marched
  // in the host's command buffer at once, never in separately submitted bands
  // (RendererOptions::progress), which would run before the host's commands draw its scene.
  const HostScene* host_scene = nullptr;
  HostLightingOptions lighting;
  // true: a frame of a sequence whose scene (every parameter, its time and camera) and options
  // are those of the last frame recorded, once that frame's clouds have settled (its history
  // 2 x quality.march_stride^2 frames old: every pixel marched twice; and none of them built
  // part of the light volume or the diffusion field, which a paused view finishes), records
  // nothing and hands out the last frame's images again (FrameImages::reused): a paused view
  // costs nothing.
  // Never with a host scene or the host's lighting, whose inputs may change while the options
  // do not.
  bool reuse_settled = false;
};

// The images a recorded frame leaves, quality.* and output.* of its scene applied.
// Both stay in VK_IMAGE_LAYOUT_GENERAL. The last command record_frame() records is a memory
// barrier from the compute shader's writes (VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
// VK_ACCESS_SHADER_WRITE_BIT) to the host's reads (VK_PIPELINE_STAGE_TRANSFER_BIT |
// VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
// VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_SHADER_READ_BIT), so commands the host records after
// it in the same command buffer (or submits later on the same queue) may read them. They are
// valid until record_frame() is called again for the same slot (frames_in_flight() calls
// later); a change of the output size may replace them.
struct FrameImages {
  int slot = 0;             // which of the frames in flight this was
  uint32_t width = 0, height = 0;
  VkImage hdr = VK_NULL_HANDLE;  // linear HDR radiance, VK_FORMAT_R32G32B32A32_SFLOAT, a = 1
  VkImageView hdr_view = VK_NULL_HANDLE;
  // Exposed (output.exposure), tone-mapped (ACES fit) and sRGB-encoded, as the PNG writer does:
  // VK_FORMAT_R8G8B8A8_UNORM holding sRGB code values, a = 1. Blit it to a *_UNORM swapchain
  // image, or sample it and write the values unchanged.
  VkImage display = VK_NULL_HANDLE;
  VkImageView display_view = VK_NULL_HANDLE;
  // With FrameOptions::lighting: the cloud shadow map, VK_FORMAT_R32_SFLOAT, the share of the
  // key light (the sun; the moon once it lights the night) that passes the clouds. A point p
  // (ENU, m) below the clouds looks it up at (world_to_cloud_shadow * vec4(p, 1)).xy, texture
  // coordinates in [0, 1]^2 (row 0 north): p carried along the light onto the plane of the
  // clouds' bottom, where z is p's height above that plane (exact below it; above it the
  // clouds between are not known). Clamp to the edge outside (1 there: unknown). Same barrier
  // and lifetime as the images above; when not asked for, VK_NULL_HANDLE.
  VkImage cloud_shadow = VK_NULL_HANDLE;
  VkImageView cloud_shadow_view = VK_NULL_HANDLE;
  glm::mat4 world_to_cloud_shadow{1.0f};
  // With FrameOptions::lighting: a small environment cube map about the camera, the clouds in
  // it (for image-based lighting and reflections): VK_FORMAT_R16G16B16A16_SFLOAT radiance
  // (cd/m^2), its six faces side by side in one 6 N x N image, in the order and with the texel
  // directions of a Vulkan cube map's layers +X, -X, +Y, -Y, +Z, -Z, on ENU axes (x east, y
  // north, z up; a y-up host swaps its axes). Copy each N x N region into a cube image's layer
  // (vkCmdCopyImage). The sun's and the moon's discs are not in it (HostLighting has them).
  VkImage environment = VK_NULL_HANDLE;
  VkImageView environment_view = VK_NULL_HANDLE;
  // The last frame's images handed out again (FrameOptions::reuse_settled): nothing was
  // recorded into the command buffer, and `slot` is the last frame's.
  bool reused = false;
};

class FrameRenderer {
 public:
  // On nephele's own headless Vulkan context (RendererOptions picks the device).
  explicit FrameRenderer(const RendererOptions& options = {});
  // On the host's device: InputError naming what it lacks when it is not Vulkan 1.2 or cannot
  // use nephele's texture formats (filtered storage images). options.device is ignored; options.validation only counts messages
  // of an instance the host created with a debug messenger of its own (it is not added).
  FrameRenderer(const HostVulkan& host, const RendererOptions& options = {});
  // The host must have waited for every command buffer recorded by this renderer.
  ~FrameRenderer();
  FrameRenderer(const FrameRenderer&) = delete;
  FrameRenderer& operator=(const FrameRenderer&) = delete;

  // How many frames may be in flight at once (2): record_frame() call k uses slot
  // k % frames_in_flight(), and before it the host must have waited for the command buffer
  // recorded frames_in_flight() calls earlier (its fence).
  int frames_in_flight() const;

  // Validates `scene` (throws InputError and records nothing when it is invalid, so the host can
  // keep the last valid scene) and records the frame into `cmd`, a primary command buffer in
  // the recording state for a queue of the host's queue family. The host submits it. (Vulkan
  // has no query for a command buffer's state: nephele refuses a null one, and the validation
  // layer reports one that is not recording.)
  // The only host waits inside: the first frame (noise textures, about a second on a CPU), a
  // change of the atmosphere (its tables), of the weather map file, or of the output size.
  // Everything else that is expensive (light volume, evolving weather) is spread over frames.
  FrameImages record_frame(VkCommandBuffer cmd, const Scene& scene, const FrameOptions& options = {});

  // Timings and sky positions of the most recent frame whose results have been collected: the
  // frame recorded frames_in_flight() calls before the last one (collected when its slot is
  // reused). Empty before that. FrameStats::wall_ms is the host time of its record_frame().
  const std::optional<FrameStats>& completed_stats() const;
  // The lighting of the same frame (FrameOptions::lighting), when it asked for it; else empty.
  const std::optional<HostLighting>& completed_lighting() const;

  // Waits until the device is idle and reads the last recorded frame back (linear HDR colour
  // and the cloud buffer, as Renderer::render returns them): for screenshots, not every frame.
  // The host must have submitted the command buffer of the last record_frame().
  Frame read_back();

  // The cloud field for queries from the CPU (nephele/cloud_query.h): the noise textures of
  // scene.noise_seed read back once (a host wait of milliseconds on a GPU; made first, about a
  // second on a CPU, if this renderer has not made them). Not while a frame is being recorded.
  CloudQuery cloud_query(const Scene& scene);

  const std::string& device_name() const;
  int validation_messages() const;

  // The implementation (src/render/frame_renderer_impl.h): opaque to hosts, named for the
  // library's own tests.
  struct Impl;

 private:
  friend class Renderer;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nephele

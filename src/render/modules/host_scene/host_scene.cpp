#include "render/modules/host_scene/host_scene.h"

#include <cmath>
#include <cstdio>
#include <glm/glm.hpp>

#include "nephele/error.h"

namespace nephele {
namespace {

// Bytes a depth texel takes in a copy of the depth aspect, and how host_scene.comp reads it;
// 0 bytes for a format it does not read.
struct DepthFormat {
  int bytes = 0;
  int code = 0;
};
DepthFormat depth_format(VkFormat format) {
  switch (format) {
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
      return {4, gpu::HOST_DEPTH_FLOAT32};
    case VK_FORMAT_X8_D24_UNORM_PACK32:
    case VK_FORMAT_D24_UNORM_S8_UINT:
      return {4, gpu::HOST_DEPTH_UNORM24};
    case VK_FORMAT_D16_UNORM:
      return {2, gpu::HOST_DEPTH_UNORM16};
    default:
      return {};
  }
}

int color_bytes(VkFormat format) {
  return format == VK_FORMAT_R16G16B16A16_SFLOAT   ? 8
         : format == VK_FORMAT_R32G32B32A32_SFLOAT ? 16
                                                   : 0;
}

// The depth `projection` gives a point `distance_m` ahead on its axis (view space looks down
// -z when projection[2][3] is -1, +z when it is 1).
float axis_depth(const glm::mat4& projection, float distance_m) {
  const glm::vec4 clip = projection * glm::vec4(0.0f, 0.0f, projection[2][3] * distance_m, 1.0f);
  return clip.z / clip.w;
}

bool near(float a, float b, float tolerance) {
  return std::abs(a - b) <= tolerance * std::abs(b);
}

}  // namespace

std::string host_scene_problem(const HostScene& host, const Scene& scene) {
  if (host.depth == VK_NULL_HANDLE)
    return "host_scene.depth is VK_NULL_HANDLE; the host's depth image is needed";
  if (host.color == VK_NULL_HANDLE)
    return "host_scene.color is VK_NULL_HANDLE; the host's colour image is needed";
  if (depth_format(host.depth_format).bytes == 0)
    return "host_scene.depth_format " + std::to_string(int(host.depth_format)) +
           " is not read; use VK_FORMAT_D32_SFLOAT, D32_SFLOAT_S8_UINT, X8_D24_UNORM_PACK32, "
           "D24_UNORM_S8_UINT or D16_UNORM";
  if (color_bytes(host.color_format) == 0)
    return "host_scene.color_format " + std::to_string(int(host.color_format)) +
           " is not read; use VK_FORMAT_R16G16B16A16_SFLOAT or VK_FORMAT_R32G32B32A32_SFLOAT";
  if (host.layout != VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL && host.layout != VK_IMAGE_LAYOUT_GENERAL)
    return "host_scene.layout " + std::to_string(int(host.layout)) +
           " cannot be copied from; use VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL or "
           "VK_IMAGE_LAYOUT_GENERAL";
  if (host.width != uint32_t(scene.output.width) || host.height != uint32_t(scene.output.height))
    return "host_scene.width x height " + std::to_string(host.width) + " x " +
           std::to_string(host.height) + " must be the frame's size, output " +
           std::to_string(scene.output.width) + " x " + std::to_string(scene.output.height);
  if (!(host.color_scale >= 0.0f) || !std::isfinite(host.color_scale))
    return "host_scene.color_scale " + number_for_message(host.color_scale) +
           " must be finite and >= 0";
  const glm::mat4& p = host.projection;
  if (std::abs(p[2][3]) != 1.0f || p[3][3] != 0.0f || p[0][0] == 0.0f || p[1][1] == 0.0f)
    return "host_scene.projection is not a perspective projection (its w row must be (0, 0, +-1, "
           "0))";
  const double fov_deg = glm::degrees(2.0 * std::atan(1.0 / std::abs(double(p[1][1]))));
  const double scene_fov_deg = vertical_fov_deg(scene);
  if (!near(float(fov_deg), float(scene_fov_deg), 0.01f))
    return "host_scene.projection's vertical field of view " + number_for_message(fov_deg) +
           " deg must be the scene camera's, " + number_for_message(scene_fov_deg) +
           " deg (within 1%)";
  const double aspect = std::abs(double(p[1][1]) / double(p[0][0]));
  const double scene_aspect = double(scene.output.width) / double(scene.output.height);
  if (!near(float(aspect), float(scene_aspect), 0.01f))
    return "host_scene.projection's aspect " + number_for_message(aspect) +
           " must be the frame's, " + number_for_message(scene_aspect) + " (within 1%)";
  const bool reversed = axis_depth(p, 10000.0f) < axis_depth(p, 10.0f);
  if (reversed != host.reversed_z)
    return std::string("host_scene.reversed_z is ") + (host.reversed_z ? "true" : "false") +
           " but the projection puts farther points at " + (reversed ? "smaller" : "larger") +
           " depths";
  return {};
}

HostSceneModule::HostSceneModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx),
      set_(set),
      texels_(ctx, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT) {
  set_.bind_buffer(gpu::kHostScene, texels_, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
}

bool HostSceneModule::prepare(const HostScene* host, gpu::FrameParams& params) {
  if (!host) return false;
  const DepthFormat depth = depth_format(host->depth_format);
  const VkDeviceSize pixels = VkDeviceSize(host->width) * host->height;
  color_offset_ = (pixels * VkDeviceSize(depth.bytes) + 15) / 16 * 16;
  const VkDeviceSize bytes = color_offset_ + pixels * VkDeviceSize(color_bytes(host->color_format));
  if (texels_.size() < bytes) {
    ctx_.wait_queue_idle();  // a frame in flight may still read the old one
    texels_ = gpu::Buffer(ctx_, bytes,
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    set_.bind_buffer(gpu::kHostScene, texels_, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  }
  host_ = *host;
  params.host_inverse_projection = glm::inverse(host->projection);
  params.host_scene =
      glm::vec4(1.0f, host->reversed_z ? 1.0f : 0.0f, float(depth.code),
                float(host->color_format == VK_FORMAT_R32G32B32A32_SFLOAT ? gpu::HOST_COLOR_FLOAT4
                                                                          : gpu::HOST_COLOR_HALF4));
  params.host_layout = glm::vec4(float(color_offset_ / 4), host->color_scale, 0.0f, 0.0f);
  return true;
}

void HostSceneModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  timer.begin(cmd, "host_copy");
  // The host's writes (its attachments, or shaders and copies) and this buffer's last reads
  // before the copies.
  VkMemoryBarrier before{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  before.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  before.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  VkPipelineStageFlags src = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
  if (ctx_.has_graphics()) {
    before.srcAccessMask |=
        VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    src |= VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
           VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT |
           VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
  }
  vkCmdPipelineBarrier(cmd, src, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &before, 0, nullptr, 0,
                       nullptr);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
  region.imageExtent = {host_.width, host_.height, 1};
  vkCmdCopyImageToBuffer(cmd, host_.depth, host_.layout, texels_.handle(), 1, &region);
  region.bufferOffset = color_offset_;
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  vkCmdCopyImageToBuffer(cmd, host_.color, host_.layout, texels_.handle(), 1, &region);
  VkMemoryBarrier after{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  after.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  after.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0,
                       1, &after, 0, nullptr, 0, nullptr);
  timer.end(cmd);
  if (!kernel_) kernel_ = std::make_unique<gpu::Kernel>(ctx_, set_, "host_scene.comp.spv");
  gpu::dispatch(cmd, *kernel_, timer, "host_scene", host_.width, host_.height, 1, 8, 8, 1);
}

void HostSceneModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  if (frame.params.host_scene.x > 0.0f)
    graph.add_pass("host_scene", {"terrain", FrameGraph::kView}, {"terrain"},
                   [timer = frame.timer, this](VkCommandBuffer cmd) { record(cmd, timer()); });
}

void HostSceneModule::prepare(const FramePrepare& frame, FramePlan& plan) {
  plan.host_scene = prepare(frame.options ? frame.options->host_scene : nullptr, frame.params);
}

}  // namespace nephele

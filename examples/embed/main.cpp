// nephele-embed: a host that draws its own scene - a mountain, a mesh with its own pipeline and
// depth buffer - and has nephele put the sky and the clouds around it through the frame API
// (nephele/frame.h), as an engine or an image generator would:
//
//   each frame, in one command buffer of the host's:
//     1. the host draws its mountain into its HDR colour image and its (reversed) depth buffer,
//        lit by the light nephele measured (HostLighting: the sun, the sky's spherical
//        harmonics) and shadowed by nephele's cloud shadow map;
//     2. FrameRenderer::record_frame composites: the sky and the clouds behind the mountain are
//        hidden, the clouds in front of it cover it, the air between fogs it; then exposure and
//        tone mapping of the whole frame;
//     3. the host blits nephele's display image into its swapchain image and presents it.
//
// Built against the installed package (examples/embed/CMakeLists.txt: find_package(nephele)).
//   nephele-embed [--size WxH] [--frames N] [--preset NAME] [--coverage C] [--no-mountain]
//                 [--screenshot FILE.png] [--mask FILE.png] [--validation]
// --frames 0 (the default) runs until the window is closed. --screenshot writes the last
// frame as presented; --mask writes where the mountain is (white). Exit status 1 when Vulkan's
// validation layer (--validation) reported anything.
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <stb/stb_image_write.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "host_vulkan.h"
#include "nephele/error.h"
#include "nephele/frame.h"
#include "nephele/scene_io.h"

namespace {

using embed::check;

struct Options {
  uint32_t width = 960, height = 540;
  int frames = 0;
  std::string preset = "default";
  float coverage = -1.0f;  // < 0: the preset's
  bool mountain = true;
  std::string screenshot, mask;
  bool validation = false;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--size") {
      const std::string v = value();
      if (std::sscanf(v.c_str(), "%ux%u", &o.width, &o.height) != 2 || o.width < 16 ||
          o.height < 16)
        throw std::invalid_argument("--size '" + v + "': WIDTHxHEIGHT, each at least 16");
    } else if (a == "--frames") {
      o.frames = std::stoi(value());
    } else if (a == "--preset") {
      o.preset = value();
    } else if (a == "--coverage") {
      o.coverage = std::stof(value());
    } else if (a == "--no-mountain") {
      o.mountain = false;
    } else if (a == "--screenshot") {
      o.screenshot = value();
    } else if (a == "--mask") {
      o.mask = value();
    } else if (a == "--validation") {
      o.validation = true;
    } else {
      throw std::invalid_argument("unknown argument '" + a + "'");
    }
  }
  return o;
}

// The host's own scene: a mountain 3.8 km high, 8 km ahead of the camera (its summit in the
// default cloud layer), on a 12 km square about its summit; x, y from the summit (m).
float mountain_height_m(float x, float y) {
  const float d = glm::length(glm::vec2(x, y));
  const float ridges = 1.0f + 0.15f * std::sin(x / 430.0f) * std::cos(y / 610.0f) +
                       0.08f * std::sin((x + y) / 170.0f);
  return std::max(3800.0f * std::exp(-(d * d) / (2400.0f * 2400.0f)) * ridges - 40.0f, 0.0f);
}

struct Vertex {
  glm::vec3 position;  // from the camera (ENU, m)
  glm::vec3 normal;
};

struct Mesh {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
};

Mesh mountain_mesh(const nephele::CameraParams& camera) {
  glm::vec2 ahead = glm::vec2(camera.view_dir);
  ahead = glm::length(ahead) > 1e-3f ? glm::normalize(ahead) : glm::vec2(0.0f, 1.0f);
  const glm::vec2 summit = glm::vec2(camera.position_m) + 8000.0f * ahead;
  const int n = 192;
  const float extent = 12000.0f, step = extent / float(n - 1);
  Mesh mesh;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float x = -0.5f * extent + float(i) * step, y = -0.5f * extent + float(j) * step;
      const float h = mountain_height_m(x, y);
      const glm::vec3 normal = glm::normalize(
          glm::vec3(mountain_height_m(x - 10.0f, y) - mountain_height_m(x + 10.0f, y),
                    mountain_height_m(x, y - 10.0f) - mountain_height_m(x, y + 10.0f), 20.0f));
      mesh.vertices.push_back({glm::vec3(summit + glm::vec2(x, y), h) - camera.position_m, normal});
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const uint32_t a = uint32_t(j * n + i), b = a + 1, c = a + uint32_t(n), d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
    }
  return mesh;
}

// The terrain shaders' uniform block (terrain.vert/.frag).
struct FrameUniforms {
  glm::mat4 view_projection;
  glm::mat4 world_to_cloud_shadow;
  glm::vec4 camera_m;
  glm::vec4 sun_direction;
  glm::vec4 sun_lux;
  glm::vec4 sky_sh[9];
};

constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

// The host's render pass: colour and depth cleared (depth to 0: reversed depth), left in
// TRANSFER_SRC_OPTIMAL for nephele to copy, with the dependencies that order its writes after
// the last frame's copies and before this frame's.
VkRenderPass make_render_pass(VkDevice device) {
  VkAttachmentDescription attachments[2] = {};
  for (int i = 0; i < 2; ++i) {
    attachments[i].format = i == 0 ? kColorFormat : kDepthFormat;
    attachments[i].samples = VK_SAMPLE_COUNT_1_BIT;
    attachments[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    attachments[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachments[i].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachments[i].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachments[i].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    attachments[i].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  }
  VkAttachmentReference color{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkAttachmentReference depth{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &color;
  subpass.pDepthStencilAttachment = &depth;
  const VkPipelineStageFlags attachment_stages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                                 VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                                 VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  VkSubpassDependency dependencies[2] = {};
  dependencies[0] = {
      VK_SUBPASS_EXTERNAL,
      0,
      VK_PIPELINE_STAGE_TRANSFER_BIT,
      attachment_stages,
      0,
      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
      0};
  dependencies[1] = {
      0,
      VK_SUBPASS_EXTERNAL,
      attachment_stages,
      VK_PIPELINE_STAGE_TRANSFER_BIT,
      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
      VK_ACCESS_TRANSFER_READ_BIT,
      0};
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 2;
  info.pAttachments = attachments;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = dependencies;
  VkRenderPass pass = VK_NULL_HANDLE;
  check(vkCreateRenderPass(device, &info, nullptr, &pass), "vkCreateRenderPass");
  return pass;
}

VkPipeline make_pipeline(const embed::HostVulkan& vk, VkRenderPass pass, VkPipelineLayout layout) {
  const std::string dir = EMBED_SHADER_DIR;
  VkShaderModule vert = vk.load_shader(dir + "/terrain.vert.spv"),
                 frag = vk.load_shader(dir + "/terrain.frag.spv");
  VkPipelineShaderStageCreateInfo stages[2] = {
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vert;
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = frag;
  stages[1].pName = "main";
  VkVertexInputBindingDescription binding{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
  VkVertexInputAttributeDescription attributes[2] = {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
      {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)}};
  VkPipelineVertexInputStateCreateInfo input{
      VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  input.vertexBindingDescriptionCount = 1;
  input.pVertexBindingDescriptions = &binding;
  input.vertexAttributeDescriptionCount = 2;
  input.pVertexAttributeDescriptions = attributes;
  VkPipelineInputAssemblyStateCreateInfo assembly{
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{
      VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{
      VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = VK_TRUE;
  depth.depthWriteEnable = VK_TRUE;
  depth.depthCompareOp = VK_COMPARE_OP_GREATER;  // reversed depth: nearer is larger
  VkPipelineColorBlendAttachmentState blend{};
  blend.colorWriteMask = 0xf;
  VkPipelineColorBlendStateCreateInfo blending{
      VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blending.attachmentCount = 1;
  blending.pAttachments = &blend;
  const VkDynamicState dynamic_states[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamic_states;
  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blending;
  info.pDynamicState = &dynamic;
  info.layout = layout;
  info.renderPass = pass;
  VkPipeline pipeline = VK_NULL_HANDLE;
  check(vkCreateGraphicsPipelines(vk.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
        "vkCreateGraphicsPipelines");
  vkDestroyShaderModule(vk.device, vert, nullptr);
  vkDestroyShaderModule(vk.device, frag, nullptr);
  return pipeline;
}

void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                   VkAccessFlags src_access, VkAccessFlags dst_access, VkPipelineStageFlags src,
                   VkPipelineStageFlags dst) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = src_access;
  b.dstAccessMask = dst_access;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, src, dst, 0, 0, nullptr, 0, nullptr, 1, &b);
}

void write_png(const std::string& path, uint32_t width, uint32_t height,
               const unsigned char* rgba) {
  if (!stbi_write_png(path.c_str(), int(width), int(height), 4, rgba, int(width) * 4))
    throw std::runtime_error("cannot write '" + path + "'");
}

int run(const Options& o) {
  nephele::Scene scene = nephele::load_preset(o.preset);  // an InputError names a bad preset
  scene.output.width = int(o.width);
  scene.output.height = int(o.height);
  if (o.coverage >= 0.0f) scene.clouds.coverage = o.coverage;
  nephele::validate_scene(scene);

  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  GLFWwindow* window =
      glfwCreateWindow(int(o.width), int(o.height), "nephele-embed", nullptr, nullptr);
  if (!window) throw std::runtime_error("GLFW: cannot open a window (is there a display?)");
  int status = 0;
  {
    embed::HostVulkan vk(window, o.validation);
    if (vk.extent.width != o.width || vk.extent.height != o.height)
      throw std::runtime_error("the window is " + std::to_string(vk.extent.width) + " x " +
                               std::to_string(vk.extent.height) + ", not the size asked for");
    std::printf("nephele-embed: %s, %u x %u\n", vk.device_name.c_str(), o.width, o.height);
    nephele::FrameRenderer sky(
        nephele::HostVulkan{vk.instance, vk.physical_device, vk.device, vk.queue_family, vk.queue});
    const int slots = sky.frames_in_flight();
    const size_t slot_count = size_t(slots);

    // The host's targets, pass, pipeline and mesh.
    embed::Image color =
        vk.make_image(o.width, o.height, kColorFormat,
                      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                      VK_IMAGE_ASPECT_COLOR_BIT);
    embed::Image depth =
        vk.make_image(o.width, o.height, kDepthFormat,
                      VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                      VK_IMAGE_ASPECT_DEPTH_BIT);
    VkRenderPass pass = make_render_pass(vk.device);
    VkImageView views[2] = {color.view, depth.view};
    VkFramebufferCreateInfo fb_info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fb_info.renderPass = pass;
    fb_info.attachmentCount = 2;
    fb_info.pAttachments = views;
    fb_info.width = o.width;
    fb_info.height = o.height;
    fb_info.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    check(vkCreateFramebuffer(vk.device, &fb_info, nullptr, &framebuffer), "vkCreateFramebuffer");
    VkDescriptorSetLayoutBinding bindings[2] = {
        {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
         VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr}};
    VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    set_info.bindingCount = 2;
    set_info.pBindings = bindings;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    check(vkCreateDescriptorSetLayout(vk.device, &set_info, nullptr, &set_layout),
          "vkCreateDescriptorSetLayout");
    VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layout_info.setLayoutCount = 1;
    layout_info.pSetLayouts = &set_layout;
    VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
    check(vkCreatePipelineLayout(vk.device, &layout_info, nullptr, &pipeline_layout),
          "vkCreatePipelineLayout");
    VkPipeline pipeline = make_pipeline(vk, pass, pipeline_layout);
    VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, uint32_t(slots)},
                                     {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, uint32_t(slots)}};
    VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool_info.maxSets = uint32_t(slots);
    pool_info.poolSizeCount = 2;
    pool_info.pPoolSizes = sizes;
    VkDescriptorPool descriptor_pool = VK_NULL_HANDLE;
    check(vkCreateDescriptorPool(vk.device, &pool_info, nullptr, &descriptor_pool),
          "vkCreateDescriptorPool");
    std::vector<VkDescriptorSetLayout> layouts(slot_count, set_layout);
    std::vector<VkDescriptorSet> sets(slot_count);
    VkDescriptorSetAllocateInfo set_alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    set_alloc.descriptorPool = descriptor_pool;
    set_alloc.descriptorSetCount = uint32_t(slots);
    set_alloc.pSetLayouts = layouts.data();
    check(vkAllocateDescriptorSets(vk.device, &set_alloc, sets.data()), "vkAllocateDescriptorSets");
    VkSamplerCreateInfo sampler_info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sampler_info.magFilter = sampler_info.minFilter = VK_FILTER_LINEAR;
    sampler_info.addressModeU = sampler_info.addressModeV = sampler_info.addressModeW =
        VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    VkSampler sampler = VK_NULL_HANDLE;
    check(vkCreateSampler(vk.device, &sampler_info, nullptr, &sampler), "vkCreateSampler");

    const Mesh mesh = mountain_mesh(scene.camera);
    embed::Buffer vertices =
        vk.make_buffer(mesh.vertices.size() * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    embed::Buffer indices =
        vk.make_buffer(mesh.indices.size() * 4, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    std::memcpy(vertices.mapped, mesh.vertices.data(), mesh.vertices.size() * sizeof(Vertex));
    std::memcpy(indices.mapped, mesh.indices.data(), mesh.indices.size() * 4);
    std::vector<embed::Buffer> uniforms;
    for (int s = 0; s < slots; ++s)
      uniforms.push_back(vk.make_buffer(sizeof(FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT));
    const VkDeviceSize pixels = VkDeviceSize(o.width) * o.height;
    embed::Buffer screenshot = vk.make_buffer(pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    embed::Buffer depth_texels = vk.make_buffer(pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);

    VkCommandPoolCreateInfo cmd_pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    cmd_pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    cmd_pool_info.queueFamilyIndex = vk.queue_family;
    VkCommandPool cmd_pool = VK_NULL_HANDLE;
    check(vkCreateCommandPool(vk.device, &cmd_pool_info, nullptr, &cmd_pool),
          "vkCreateCommandPool");
    std::vector<VkCommandBuffer> cmds(slot_count);
    VkCommandBufferAllocateInfo cmd_alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cmd_alloc.commandPool = cmd_pool;
    cmd_alloc.commandBufferCount = uint32_t(slots);
    check(vkAllocateCommandBuffers(vk.device, &cmd_alloc, cmds.data()), "vkAllocateCommandBuffers");
    std::vector<VkFence> fences(slot_count);
    std::vector<VkSemaphore> acquired(slot_count), finished(vk.swapchain_images.size());
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fence_info.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    VkSemaphoreCreateInfo semaphore_info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    for (int s = 0; s < slots; ++s) {
      check(vkCreateFence(vk.device, &fence_info, nullptr, &fences[size_t(s)]), "vkCreateFence");
      check(vkCreateSemaphore(vk.device, &semaphore_info, nullptr, &acquired[size_t(s)]),
            "vkCreateSemaphore");
    }
    for (VkSemaphore& f : finished)
      check(vkCreateSemaphore(vk.device, &semaphore_info, nullptr, &f), "vkCreateSemaphore");

    // The host's camera is the scene's: its view, and a reversed-depth projection (far at 0)
    // with the scene's field of view, y down as Vulkan's clip space has it.
    const nephele::CameraParams& camera = scene.camera;
    const glm::mat4 view =
        glm::lookAt(glm::vec3(0.0f), camera.view_dir, glm::vec3(0.0f, 0.0f, 1.0f));
    glm::mat4 projection = glm::perspectiveRH_ZO(glm::radians(nephele::vertical_fov_deg(scene)),
                                                 float(o.width) / float(o.height), 100000.0f, 1.0f);
    projection[1][1] *= -1.0f;
    nephele::HostScene host_scene;
    host_scene.depth = depth.image;
    host_scene.depth_format = kDepthFormat;
    host_scene.color = color.image;
    host_scene.color_format = kColorFormat;
    host_scene.width = o.width;
    host_scene.height = o.height;
    host_scene.projection = projection;
    host_scene.reversed_z = true;
    nephele::FrameOptions frame_options;
    frame_options.host_scene = &host_scene;
    frame_options.lighting.enabled = true;
    frame_options.lighting.shadow_map_extent_m = 24000.0f;

    // nephele's light arrives frames_in_flight() frames late (it is read back when the slot
    // comes round again); the first frames are nephele's alone, until it has arrived.
    std::optional<nephele::FrameImages> last;
    int frame = 0;
    const auto begin = [&](int slot) {
      check(vkWaitForFences(vk.device, 1, &fences[size_t(slot)], VK_TRUE, UINT64_MAX),
            "vkWaitForFences");
      check(vkResetFences(vk.device, 1, &fences[size_t(slot)]), "vkResetFences");
      check(vkResetCommandBuffer(cmds[size_t(slot)], 0), "vkResetCommandBuffer");
      VkCommandBufferBeginInfo begin_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
      begin_info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
      check(vkBeginCommandBuffer(cmds[size_t(slot)], &begin_info), "vkBeginCommandBuffer");
      return cmds[size_t(slot)];
    };
    while (!sky.completed_lighting()) {
      const int slot = frame++ % slots;
      VkCommandBuffer cmd = begin(slot);
      nephele::FrameOptions sky_only = frame_options;
      sky_only.host_scene = nullptr;
      last = sky.record_frame(cmd, scene, sky_only);
      check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
      VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
      submit.commandBufferCount = 1;
      submit.pCommandBuffers = &cmd;
      check(vkQueueSubmit(vk.queue, 1, &submit, fences[size_t(slot)]), "vkQueueSubmit");
    }

    for (int shown = 0; !glfwWindowShouldClose(window) && (o.frames == 0 || shown < o.frames);
         ++shown) {
      glfwPollEvents();
      const bool final_frame = o.frames > 0 && shown == o.frames - 1;
      const int slot = frame++ % slots;
      VkCommandBuffer cmd = begin(slot);
      scene.time_s += 1.0f / 30.0f;  // the clouds drift and grow

      // nephele's light: the sun above the clouds (the shadow map adds theirs per point), the
      // sky's harmonics, the shadow map of the last frame recorded.
      const nephele::HostLighting& light = *sky.completed_lighting();
      FrameUniforms u{};
      u.view_projection = projection * view;
      u.world_to_cloud_shadow = last->world_to_cloud_shadow;
      u.camera_m = glm::vec4(camera.position_m, 0.0f);
      u.sun_direction = glm::vec4(light.sun_direction, 0.0f);
      u.sun_lux = glm::vec4(
          light.sun_illuminance_lux / std::max(light.sun_cloud_transmittance, 1e-3f), 0.0f);
      for (int k = 0; k < 9; ++k) u.sky_sh[k] = glm::vec4(light.sky_radiance_sh[k], 0.0f);
      std::memcpy(uniforms[size_t(slot)].mapped, &u, sizeof u);
      VkDescriptorBufferInfo ubo{uniforms[size_t(slot)].buffer, 0, sizeof(FrameUniforms)};
      VkDescriptorImageInfo shadow{sampler, last->cloud_shadow_view, VK_IMAGE_LAYOUT_GENERAL};
      VkWriteDescriptorSet writes[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET},
                                        {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
      writes[0].dstSet = writes[1].dstSet = sets[size_t(slot)];
      writes[0].dstBinding = 0;
      writes[0].descriptorCount = 1;
      writes[0].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
      writes[0].pBufferInfo = &ubo;
      writes[1].dstBinding = 1;
      writes[1].descriptorCount = 1;
      writes[1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
      writes[1].pImageInfo = &shadow;
      vkUpdateDescriptorSets(vk.device, 2, writes, 0, nullptr);

      // 1. The host's scene.
      VkClearValue clears[2] = {};  // colour 0; depth 0, the far plane of reversed depth
      VkRenderPassBeginInfo pass_begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
      pass_begin.renderPass = pass;
      pass_begin.framebuffer = framebuffer;
      pass_begin.renderArea = {{0, 0}, {o.width, o.height}};
      pass_begin.clearValueCount = 2;
      pass_begin.pClearValues = clears;
      vkCmdBeginRenderPass(cmd, &pass_begin, VK_SUBPASS_CONTENTS_INLINE);
      if (o.mountain) {
        VkViewport viewport{0.0f, 0.0f, float(o.width), float(o.height), 0.0f, 1.0f};
        VkRect2D scissor{{0, 0}, {o.width, o.height}};
        vkCmdSetViewport(cmd, 0, 1, &viewport);
        vkCmdSetScissor(cmd, 0, 1, &scissor);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout, 0, 1,
                                &sets[size_t(slot)], 0, nullptr);
        VkDeviceSize offset = 0;
        vkCmdBindVertexBuffers(cmd, 0, 1, &vertices.buffer, &offset);
        vkCmdBindIndexBuffer(cmd, indices.buffer, 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, uint32_t(mesh.indices.size()), 1, 0, 0, 0);
      }
      vkCmdEndRenderPass(cmd);

      // 2. nephele's sky and clouds around it.
      last = sky.record_frame(cmd, scene, frame_options);

      // 3. Into the swapchain.
      uint32_t index = 0;
      check(vkAcquireNextImageKHR(vk.device, vk.swapchain, UINT64_MAX, acquired[size_t(slot)],
                                  VK_NULL_HANDLE, &index),
            "vkAcquireNextImageKHR");
      VkImage target = vk.swapchain_images[index];
      image_barrier(cmd, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                    VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_PIPELINE_STAGE_TRANSFER_BIT);
      VkImageBlit blit{};
      blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      blit.srcOffsets[1] = blit.dstOffsets[1] = {int32_t(o.width), int32_t(o.height), 1};
      vkCmdBlitImage(cmd, last->display, VK_IMAGE_LAYOUT_GENERAL, target,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
      image_barrier(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_ACCESS_TRANSFER_WRITE_BIT, 0,
                    VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT);
      if (final_frame) {  // what is presented, and where the mountain is
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {o.width, o.height, 1};
        vkCmdCopyImageToBuffer(cmd, last->display, VK_IMAGE_LAYOUT_GENERAL, screenshot.buffer, 1,
                               &region);
        region.imageSubresource.aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT;
        vkCmdCopyImageToBuffer(cmd, depth.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               depth_texels.buffer, 1, &region);
        VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                             &to_host, 0, nullptr, 0, nullptr);
      }
      check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
      const VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
      VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
      submit.waitSemaphoreCount = 1;
      submit.pWaitSemaphores = &acquired[size_t(slot)];
      submit.pWaitDstStageMask = &wait_stage;
      submit.commandBufferCount = 1;
      submit.pCommandBuffers = &cmd;
      submit.signalSemaphoreCount = 1;
      submit.pSignalSemaphores = &finished[index];
      check(vkQueueSubmit(vk.queue, 1, &submit, fences[size_t(slot)]), "vkQueueSubmit");
      VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
      present.waitSemaphoreCount = 1;
      present.pWaitSemaphores = &finished[index];
      present.swapchainCount = 1;
      present.pSwapchains = &vk.swapchain;
      present.pImageIndices = &index;
      check(vkQueuePresentKHR(vk.queue, &present), "vkQueuePresentKHR");
      if (final_frame) {
        check(vkWaitForFences(vk.device, 1, &fences[size_t(slot)], VK_TRUE, UINT64_MAX),
              "vkWaitForFences");
        if (!o.screenshot.empty())
          write_png(o.screenshot, o.width, o.height,
                    static_cast<unsigned char*>(screenshot.mapped));
        if (!o.mask.empty()) {
          std::vector<unsigned char> mask(pixels * 4, 255);
          const auto* d = static_cast<const float*>(depth_texels.mapped);
          for (size_t i = 0; i < pixels; ++i)
            mask[4 * i] = mask[4 * i + 1] = mask[4 * i + 2] = d[i] > 0.0f ? 255 : 0;
          write_png(o.mask, o.width, o.height, mask.data());
        }
        const nephele::HostLighting& l = *sky.completed_lighting();
        std::printf(
            "nephele-embed: %d frames; sun %.0f lux at the camera (clouds pass %.2f), sky %.0f lux "
            "on the "
            "ground, visibility %.0f m\n",
            frame, l.sun_illuminance_lux.g, l.sun_cloud_transmittance,
            l.sky_irradiance_lux(glm::vec3(0.0f, 0.0f, 1.0f)).g, l.visibility_m);
      }
    }

    check(vkDeviceWaitIdle(vk.device), "vkDeviceWaitIdle");
    for (VkSemaphore s : acquired) vkDestroySemaphore(vk.device, s, nullptr);
    for (VkSemaphore s : finished) vkDestroySemaphore(vk.device, s, nullptr);
    for (VkFence f : fences) vkDestroyFence(vk.device, f, nullptr);
    vkDestroyCommandPool(vk.device, cmd_pool, nullptr);
    for (embed::Buffer& b : uniforms) vk.destroy(b);
    vk.destroy(screenshot);
    vk.destroy(depth_texels);
    vk.destroy(vertices);
    vk.destroy(indices);
    vkDestroySampler(vk.device, sampler, nullptr);
    vkDestroyDescriptorPool(vk.device, descriptor_pool, nullptr);
    vkDestroyPipeline(vk.device, pipeline, nullptr);
    vkDestroyPipelineLayout(vk.device, pipeline_layout, nullptr);
    vkDestroyDescriptorSetLayout(vk.device, set_layout, nullptr);
    vkDestroyFramebuffer(vk.device, framebuffer, nullptr);
    vkDestroyRenderPass(vk.device, pass, nullptr);
    vk.destroy(color);
    vk.destroy(depth);
    if (vk.validation_messages() > 0) {
      std::fprintf(stderr, "nephele-embed: %d validation messages\n", vk.validation_messages());
      status = 1;
    }
  }  // nephele's renderer is gone before the device (HostVulkan's destructor)
  glfwDestroyWindow(window);
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  if (!glfwInit()) {
    std::fprintf(stderr, "nephele-embed: GLFW cannot start (is there a display?)\n");
    return 2;
  }
  int status = 2;
  try {
    status = run(parse(argc, argv));
  } catch (const nephele::InputError& e) {
    std::fprintf(stderr, "nephele-embed: %s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nephele-embed: %s\n", e.what());
  }
  glfwTerminate();
  return status;
}

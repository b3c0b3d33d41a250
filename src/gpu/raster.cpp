#include "gpu/raster.h"

#include <utility>

#include "gpu/vk_check.h"

namespace nephele::gpu {

DepthTarget::DepthTarget(Context& ctx, uint32_t width, uint32_t height)
    : device_(ctx.device()), width_(width), height_(height) {
  // A failure part way (out of memory) frees what was made: no destructor runs for it.
  const UndoOnThrow undo([this] { reset(); });
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = VK_FORMAT_D32_SFLOAT;
  info.extent = {width, height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  create_device_local_image(ctx, info, VK_IMAGE_ASPECT_DEPTH_BIT, image_, memory_, view_);
}

DepthTarget& DepthTarget::operator=(DepthTarget&& other) noexcept {
  if (this != &other) {
    reset();
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    image_ = std::exchange(other.image_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
    width_ = other.width_;
    height_ = other.height_;
  }
  return *this;
}

void DepthTarget::reset() {
  if (device_ == VK_NULL_HANDLE) return;
  vkDestroyImageView(device_, view_, nullptr);
  vkDestroyImage(device_, image_, nullptr);
  vkFreeMemory(device_, memory_, nullptr);
  device_ = VK_NULL_HANDLE;
}

RasterPass::RasterPass(Context& ctx, DescriptorSet& set, const std::vector<VkFormat>& formats,
                       bool clear, const std::vector<RasterShaders>& pipelines, bool with_depth)
    : device_(ctx.device()), attachments_(formats.size()), with_depth_(with_depth) {
  if (!ctx.has_graphics())
    throw RuntimeError("the device's queue on " + ctx.device_name() + " cannot draw (no graphics)");
  std::vector<VkAttachmentDescription> attachments;
  std::vector<VkAttachmentReference> refs;
  for (VkFormat format : formats) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(ctx.physical_device(), format, &props);
    const VkFormatFeatureFlags needed =
        with_depth ? VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT : VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT;
    if (!(props.optimalTilingFeatures & needed))
      throw RuntimeError("Vulkan format " + std::to_string(int(format)) + " cannot be a " +
                         (with_depth ? "" : "blended ") + "colour attachment on " + ctx.device_name());
    VkAttachmentDescription a{};
    a.format = format;
    a.samples = VK_SAMPLE_COUNT_1_BIT;
    a.loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.initialLayout = VK_IMAGE_LAYOUT_GENERAL;
    a.finalLayout = VK_IMAGE_LAYOUT_GENERAL;
    refs.push_back({uint32_t(attachments.size()), VK_IMAGE_LAYOUT_GENERAL});
    attachments.push_back(a);
  }
  const VkAttachmentReference depth_ref{uint32_t(attachments.size()),
                                        VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  if (with_depth) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(ctx.physical_device(), VK_FORMAT_D32_SFLOAT, &props);
    if (!(props.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT))
      throw RuntimeError("Vulkan format D32_SFLOAT cannot be a depth attachment on " + ctx.device_name());
    VkAttachmentDescription a{};
    a.format = VK_FORMAT_D32_SFLOAT;
    a.samples = VK_SAMPLE_COUNT_1_BIT;
    a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    a.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    a.finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    attachments.push_back(a);
  }
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = uint32_t(refs.size());
  subpass.pColorAttachments = refs.data();
  subpass.pDepthStencilAttachment = with_depth ? &depth_ref : nullptr;
  // Before: earlier passes' reads of the targets (compute, fragment) and writes of what the
  // shaders read. After: the targets' writes made visible to the compute and fragment shaders
  // that sample them (an impostor atlas is read by the next raster pass) and to transfers.
  VkSubpassDependency deps[2] = {};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  // With depth, the last pass's depth writes come before this one's clear.
  const VkPipelineStageFlags depth_stages =
      with_depth ? VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT : 0;
  deps[0].srcStageMask = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                         VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |
                         VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | depth_stages;
  deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                         VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | depth_stages;
  deps[0].srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT |
                          VK_ACCESS_HOST_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                          (with_depth ? VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT : 0);
  deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT |
                          (with_depth ? VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                                            VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT
                                      : 0);
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                         VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
  deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT;
  VkRenderPassCreateInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  rp.attachmentCount = uint32_t(attachments.size());
  rp.pAttachments = attachments.data();
  rp.subpassCount = 1;
  rp.pSubpasses = &subpass;
  rp.dependencyCount = 2;
  rp.pDependencies = deps;
  NEPHELE_VK(vkCreateRenderPass(device_, &rp, nullptr, &render_pass_));

  VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                               {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = VK_NULL_HANDLE;
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = VK_NULL_HANDLE;
  stages[1].pName = "main";
  VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  // Premultiplied "over": dst = src + (1 - src.a) dst, in every channel.
  VkPipelineColorBlendAttachmentState blend{};
  blend.blendEnable = with_depth ? VK_FALSE : VK_TRUE;
  blend.srcColorBlendFactor = blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
  blend.dstColorBlendFactor = blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
  blend.colorBlendOp = blend.alphaBlendOp = VK_BLEND_OP_ADD;
  blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                         VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  std::vector<VkPipelineColorBlendAttachmentState> blends(formats.size(), blend);
  VkPipelineColorBlendStateCreateInfo blending{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blending.attachmentCount = uint32_t(blends.size());
  blending.pAttachments = blends.data();
  const VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamic_states;
  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &vertex_input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pColorBlendState = &blending;
  VkPipelineDepthStencilStateCreateInfo depth_state{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth_state.depthTestEnable = VK_TRUE;
  depth_state.depthWriteEnable = VK_TRUE;
  depth_state.depthCompareOp = VK_COMPARE_OP_GREATER;  // reversed: 1 near, 0 infinitely far
  info.pDepthStencilState = with_depth ? &depth_state : nullptr;
  info.pDynamicState = &dynamic;
  info.renderPass = render_pass_;
  for (const RasterShaders& shaders : pipelines) {
    const std::string name = shaders.vert + " + " + shaders.frag;
    interfaces_.push_back(std::make_unique<PassInterface>(
        set, name,
        merge_bindings({reflect_embedded(shaders.vert, VK_SHADER_STAGE_VERTEX_BIT),
                        reflect_embedded(shaders.frag, VK_SHADER_STAGE_FRAGMENT_BIT)},
                       name)));
    info.layout = interfaces_.back()->pipeline_layout();
    stages[0].module = create_shader_module(device_, shaders.vert);
    stages[1].module = create_shader_module(device_, shaders.frag);
    const Specialization spec(shaders.frag_specialization);
    stages[1].pSpecializationInfo = spec.info();
    VkPipeline pipeline = VK_NULL_HANDLE;
    const VkResult result =
        vkCreateGraphicsPipelines(device_, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
    vkDestroyShaderModule(device_, stages[0].module, nullptr);
    vkDestroyShaderModule(device_, stages[1].module, nullptr);
    check(result, ("vkCreateGraphicsPipelines(" + shaders.vert + ", " + shaders.frag + ")").c_str());
    pipelines_.push_back(pipeline);
  }
}

RasterPass::~RasterPass() {
  for (const Cached& c : framebuffers_) vkDestroyFramebuffer(device_, c.framebuffer, nullptr);
  for (VkPipeline pipeline : pipelines_) vkDestroyPipeline(device_, pipeline, nullptr);
  vkDestroyRenderPass(device_, render_pass_, nullptr);
}

VkFramebuffer RasterPass::framebuffer_for(const std::vector<RenderTarget>& targets,
                                          const DepthTarget* depth) {
  std::vector<VkImageView> views;
  for (const RenderTarget& t : targets) views.push_back(t.view);
  if (depth) views.push_back(depth->view());
  const uint32_t w = targets[0].width, h = targets[0].height;
  for (const Cached& c : framebuffers_)
    if (c.views == views && c.width == w && c.height == h) return c.framebuffer;
  VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  info.renderPass = render_pass_;
  info.attachmentCount = uint32_t(views.size());
  info.pAttachments = views.data();
  info.width = w;
  info.height = h;
  info.layers = 1;
  VkFramebuffer framebuffer;
  NEPHELE_VK(vkCreateFramebuffer(device_, &info, nullptr, &framebuffer));
  framebuffers_.push_back({views, w, h, framebuffer});
  return framebuffer;
}

void RasterPass::record(VkCommandBuffer cmd, PassTimer& timer, const std::string& name,
                        const std::vector<RenderTarget>& targets,
                        const std::vector<RasterDraw>& draws, const DepthTarget* depth) {
  if (targets.size() != attachments_) throw RuntimeError("RasterPass: wrong number of targets");
  const uint32_t w = targets[0].width, h = targets[0].height;
  for (const RenderTarget& t : targets)
    if (t.width != w || t.height != h) throw RuntimeError("RasterPass: targets of different sizes");
  if (with_depth_ != (depth != nullptr) || (depth && (depth->width() != w || depth->height() != h)))
    throw RuntimeError("RasterPass: a depth buffer of the targets' size is needed exactly when the pass has depth");
  timer.begin(cmd, name);
  std::vector<VkClearValue> clears(targets.size() + (depth ? 1 : 0));  // depth cleared to 0: far
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = render_pass_;
  begin.framebuffer = framebuffer_for(targets, depth);
  begin.renderArea = {{0, 0}, {w, h}};
  begin.clearValueCount = uint32_t(clears.size());
  begin.pClearValues = clears.data();
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  int bound = -1;
  for (const RasterDraw& draw : draws) {
    const VkRect2D area = draw.area.extent.width > 0 ? draw.area : VkRect2D{{0, 0}, {w, h}};
    if (draw.clear_area) {
      std::vector<VkClearAttachment> attachments(targets.size());
      for (uint32_t i = 0; i < attachments.size(); ++i)
        attachments[i] = {VK_IMAGE_ASPECT_COLOR_BIT, i, VkClearValue{}};
      const VkClearRect rect{area, 0, 1};
      vkCmdClearAttachments(cmd, uint32_t(attachments.size()), attachments.data(), 1, &rect);
    }
    if (draw.vertex_count == 0) continue;
    if (draw.pipeline != bound) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines_.at(size_t(draw.pipeline)));
      interfaces_[size_t(draw.pipeline)]->bind(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS);
      bound = draw.pipeline;
    }
    const VkViewport viewport{float(area.offset.x), float(area.offset.y), float(area.extent.width),
                              float(area.extent.height), 0.0f, 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &area);
    vkCmdPushConstants(cmd, interfaces_[size_t(draw.pipeline)]->pipeline_layout(),
                       kDrawConstantStages, 0, sizeof(DrawConstants),
                       &draw.constants);
    vkCmdDraw(cmd, draw.vertex_count, 1, draw.first_vertex, 0);
  }
  vkCmdEndRenderPass(cmd);
  timer.end(cmd);
}

}  // namespace nephele::gpu

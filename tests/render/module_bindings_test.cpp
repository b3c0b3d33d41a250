// A module's own resources in descriptor set 1, bound by name (gpu/kernel.h, shader_interface.h),
// on a device with the validation layer on: the tests' shaders (tests/shaders/module_set*.comp)
// read a uniform block and an image of set 1 and write set 0's color_rw or a storage block of
// set 1, and the results are read back.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "gpu/kernel.h"
#include "gpu/resources.h"
#include "nephele/error.h"
#include "support/test_shaders.h"

namespace nephele::gpu {
namespace {

constexpr uint32_t kSize = 4;  // the shaders' images are 4 x 4 texels, one group

// A context with the validation layer, a table, and what the shaders read: TestModuleBlock
// (scale, offset) and test_module_map (texel (x, y) = (x, y, x + 4 y, 1)).
struct ModuleFixture {
  Context ctx{ContextOptions{"", true, false}};
  DescriptorSet table{ctx};
  PassTimer timer{ctx, 4};
  Buffer block{ctx, 2 * 4 * sizeof(float), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT};
  Texture map{
      ctx, kSize, kSize, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE};
  const float scale[4] = {2.0f, 3.0f, 0.5f, 1.0f};
  const float offset[4] = {0.25f, -1.0f, 4.0f, 0.0f};

  ModuleFixture() {
    std::memcpy(block.data(), scale, sizeof(scale));
    std::memcpy(static_cast<char*>(block.data()) + sizeof(scale), offset, sizeof(offset));
    Buffer staging(ctx, kSize * kSize * 4 * sizeof(float), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    std::vector<float> texels;
    for (uint32_t y = 0; y < kSize; ++y)
      for (uint32_t x = 0; x < kSize; ++x)
        texels.insert(texels.end(), {float(x), float(y), float(x + kSize * y), 1.0f});
    std::memcpy(staging.data(), texels.data(), texels.size() * sizeof(float));
    ctx.submit_and_wait([&](VkCommandBuffer cmd) { map.record_upload(cmd, staging); });
  }

  // What the shaders write at (x, y), channel c.
  float expected(uint32_t x, uint32_t y, int c) const {
    const float texel[4] = {float(x), float(y), float(x + kSize * y), 1.0f};
    return texel[c] * scale[c] + offset[c];
  }

  // The shader's output read back (4 floats a texel, row by row) against expected(), and no
  // validation message.
  void expect_written(const float* texels) const {
    for (uint32_t y = 0; y < kSize; ++y)
      for (uint32_t x = 0; x < kSize; ++x)
        for (int c = 0; c < 4; ++c)
          EXPECT_EQ(texels[(y * kSize + x) * 4 + c], expected(x, y, c))
              << "texel (" << x << ", " << y << "), channel " << c;
    EXPECT_EQ(ctx.validation_messages(), 0) << "Vulkan validation messages (printed above)";
  }

  // Writes the table into the one-off slot and dispatches `kernel` over the 4 x 4 texels.
  void run(const Kernel& kernel) {
    table.use(DescriptorSet::kOneOff);
    ctx.submit_and_wait([&](VkCommandBuffer cmd) {
      timer.reset(cmd);
      dispatch(cmd, kernel, timer, "module_set", kSize, kSize, 1, kSize, kSize, 1);
    });
  }
};

// Sets 0 and 1 together (bound in one call): the block and the image by name, color_rw by number.
TEST(ModuleBindings, AComputePassReadsSetOneByNameAndWritesSetZero) {
  ModuleFixture f;
  Texture out(f.ctx, kSize, kSize, 1, VK_FORMAT_R32G32B32A32_SFLOAT);
  f.table.bind_storage_image(kColorRw, out);
  f.table.bind_module_buffer("TestModuleBlock", f.block, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  f.table.bind_module_sampled_image("test_module_map", f.map);
  const Kernel kernel(f.ctx, f.table, test_shader("module_set.comp"), "module_set.comp");
  EXPECT_NE(kernel.interface().set(0), VkDescriptorSet(VK_NULL_HANDLE));
  EXPECT_NE(kernel.interface().set(kModuleSet), VkDescriptorSet(VK_NULL_HANDLE));
  f.run(kernel);

  Buffer staging(f.ctx, kSize * kSize * 4 * sizeof(float), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  f.ctx.submit_and_wait([&](VkCommandBuffer cmd) { out.record_download(cmd, staging); });
  const float* texels = static_cast<const float*>(staging.data());
  f.expect_written(texels);
}

// Set 1 alone (set 0's layout empty, set 1 bound by itself), at other numbers than
// module_set.comp's: the names decide, and both pipelines read the same table.
TEST(ModuleBindings, APassWithSetOneAloneBindsItByName) {
  ModuleFixture f;
  Buffer out(f.ctx, kSize * kSize * 4 * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  std::memset(out.data(), 0, out.size());
  f.table.bind_module_buffer("TestModuleBlock", f.block, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  f.table.bind_module_sampled_image("test_module_map", f.map);
  f.table.bind_module_buffer("TestModuleOutBlock", out, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  const Kernel kernel(f.ctx, f.table, test_shader("module_set_only.comp"), "module_set_only.comp");
  EXPECT_EQ(kernel.interface().set(0), VkDescriptorSet(VK_NULL_HANDLE));
  EXPECT_NE(kernel.interface().set(kModuleSet), VkDescriptorSet(VK_NULL_HANDLE));
  f.run(kernel);

  const float* texels = static_cast<const float*>(out.data());
  f.expect_written(texels);
}

// A name bound as another kind of descriptor than the pipeline reads is refused, naming both.
TEST(ModuleBindings, ANameBoundAsAnotherKindOfDescriptorIsRefused) {
  ModuleFixture f;
  Texture out(f.ctx, kSize, kSize, 1, VK_FORMAT_R32G32B32A32_SFLOAT);
  f.table.bind_storage_image(kColorRw, out);
  f.table.bind_module_sampled_image("test_module_map", f.map);
  const Kernel kernel(f.ctx, f.table, test_shader("module_set.comp"), "module_set.comp");
  f.table.bind_module_buffer("TestModuleBlock", f.block, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  try {
    f.table.use(DescriptorSet::kOneOff);
    FAIL() << "no error";
  } catch (const RuntimeError& e) {
    const std::string what = e.what();
    for (const std::string& part : std::vector<std::string>{
             "module_set.comp", "'TestModuleBlock'",
             "descriptor type " + std::to_string(int(VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)),
             "type " + std::to_string(int(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)) + " is bound"})
      EXPECT_NE(what.find(part), std::string::npos) << what;
  }
  EXPECT_THROW(f.table.bind_module_buffer("TestModuleBlock", f.block,
                                          VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER),
               RuntimeError);
  EXPECT_EQ(f.ctx.validation_messages(), 0) << "Vulkan validation messages (printed above)";
}

// A set-1 resource nobody bound is left unwritten, as set 0's are, and the validation layer
// reports a dispatch that reads it. The command buffer is recorded and then discarded unsubmitted
// (the layer checks a set without update-after-bind when the dispatch is recorded), so the device
// never reads the unwritten descriptor.
TEST(ModuleBindings, TheValidationLayerReportsAnUnboundSetOneResource) {
  ModuleFixture f;
  Texture out(f.ctx, kSize, kSize, 1, VK_FORMAT_R32G32B32A32_SFLOAT);
  f.table.bind_storage_image(kColorRw, out);
  f.table.bind_module_sampled_image("test_module_map", f.map);  // TestModuleBlock left unbound
  const Kernel kernel(f.ctx, f.table, test_shader("module_set.comp"), "module_set.comp");
  f.table.use(DescriptorSet::kOneOff);
  ASSERT_EQ(f.ctx.validation_messages(), 0);
  struct Discard {};
  std::printf("A validation message about set 1's unwritten TestModuleBlock is expected:\n");
  std::fflush(stdout);
  try {
    f.ctx.submit_and_wait([&](VkCommandBuffer cmd) {
      f.timer.reset(cmd);
      dispatch(cmd, kernel, f.timer, "unbound", kSize, kSize, 1, kSize, kSize, 1);
      throw Discard{};
    });
  } catch (const Discard&) {
  }
  EXPECT_GT(f.ctx.validation_messages(), 0);
}

}  // namespace
}  // namespace nephele::gpu

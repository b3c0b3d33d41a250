// 2D array textures (gpu/resources.h, the image layers' storage: render/image_layers.h) on a
// device with the validation layer on: each layer holds its own texels through an upload and a
// download, one layer is cleared alone, and each layer is a render target of its own.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "gpu/context.h"
#include "gpu/resources.h"
#include "nephele/error.h"

namespace nephele::gpu {
namespace {

constexpr uint32_t kSize = 4, kLayers = 3;

float texel(uint32_t layer, uint32_t x, uint32_t y, int c) {
  const float values[4] = {float(x), float(y), float(layer + 1), 1.0f};
  return values[c];
}

std::vector<float> download(Context& ctx, const Texture& t) {
  Buffer staging(ctx, kLayers * kSize * kSize * 4 * sizeof(float),
                 VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { t.record_download(cmd, staging); });
  std::vector<float> out(kLayers * kSize * kSize * 4);
  std::memcpy(out.data(), staging.data(), out.size() * sizeof(float));
  return out;
}

TEST(TextureArray, LayersKeepTheirTexelsAndClearAlone) {
  Context ctx{ContextOptions{"", true, false}};
  Texture t(ctx, kSize, kSize, ArrayLayers{kLayers}, VK_FORMAT_R32G32B32A32_SFLOAT, true);
  EXPECT_EQ(t.layers(), kLayers);
  std::vector<float> texels;
  for (uint32_t layer = 0; layer < kLayers; ++layer)
    for (uint32_t y = 0; y < kSize; ++y)
      for (uint32_t x = 0; x < kSize; ++x)
        for (int c = 0; c < 4; ++c) texels.push_back(texel(layer, x, y, c));
  Buffer staging(ctx, texels.size() * sizeof(float), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  std::memcpy(staging.data(), texels.data(), texels.size() * sizeof(float));
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { t.record_upload(cmd, staging); });
  EXPECT_EQ(download(ctx, t), texels);

  ctx.submit_and_wait([&](VkCommandBuffer cmd) { t.record_clear_layer(cmd, 1); });
  const std::vector<float> cleared = download(ctx, t);
  const size_t per_layer = kSize * kSize * 4;
  for (size_t i = 0; i < cleared.size(); ++i)
    EXPECT_EQ(cleared[i], i / per_layer == 1 ? 0.0f : texels[i]) << "value " << i;
}

TEST(TextureArray, EachLayerIsARenderTargetOfItsOwn) {
  Context ctx{ContextOptions{"", true, false}};
  const Texture t(ctx, kSize, 2 * kSize, ArrayLayers{kLayers}, VK_FORMAT_R32G32B32A32_SFLOAT, true);
  const RenderTarget first = t.render_target(0), last = t.render_target(kLayers - 1);
  EXPECT_NE(first.view, VK_NULL_HANDLE);
  EXPECT_NE(first.view, last.view);
  EXPECT_NE(first.view, t.storage_view());  // a 2D view of one layer, not the array's
  EXPECT_EQ(last.width, kSize);
  EXPECT_EQ(last.height, 2 * kSize);
  EXPECT_THROW(t.render_target(kLayers), RuntimeError);
  const Texture plain(ctx, kSize, kSize, 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                      VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 1, true);
  EXPECT_EQ(plain.render_target().view, plain.storage_view());
}

}  // namespace
}  // namespace nephele::gpu

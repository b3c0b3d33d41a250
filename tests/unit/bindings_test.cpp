// The bindings are declared once, in GLSL (shaders/common/bindings_inc.glsl): gpu::Binding is
// generated from it (cmake/bindings_header.cmake), and each pipeline's layout is reflected from
// its SPIR-V (gpu/shader_interface.h). These tests hold the three together, and check the
// reflection of a module's own resources (set 1, by name) on the tests' shaders
// (tests/shaders; the device test is tests/render/module_bindings_test.cpp).
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "gpu/kernel.h"
#include "gpu/shader_interface.h"
#include "nephele/error.h"
#include "nephele_embedded.h"
#include "support/test_shaders.h"

namespace nephele_shaders {
extern const EmbeddedFile kFiles[];
extern const size_t kFileCount;
}  // namespace nephele_shaders

namespace nephele::gpu {
namespace {

struct Declared {
  std::string name;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
};

// Binding number -> its name and descriptor type, from the GLSL declarations.
std::map<uint32_t, Declared> glsl_bindings() {
  std::ifstream in(std::string(NEPHELE_SOURCE_DIR) + "/shaders/common/bindings_inc.glsl");
  std::map<uint32_t, Declared> found;
  const std::regex declaration(
      R"(layout\(([^)]*)\)\s*(?:(?:readonly|writeonly|restrict|coherent)\s+)*(uniform|buffer)\s+(?:(?:readonly|writeonly|restrict|coherent)\s+)*(\w+)\s*(\w*))");
  const std::regex binding(R"(binding\s*=\s*(\d+))");
  std::string line;
  while (std::getline(in, line)) {
    std::smatch m, b;
    if (!std::regex_search(line, m, declaration)) continue;
    const std::string qualifiers = m[1];
    if (!std::regex_search(qualifiers, b, binding)) continue;
    const uint32_t n = uint32_t(std::stoul(b[1]));
    const std::string storage = m[2], type = m[3], variable = m[4];
    Declared d;
    const bool block = type.ends_with("Block");
    d.name = block ? type : variable;
    if (storage == "buffer")
      d.type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    else if (block)
      d.type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    else if (type.find("image") != std::string::npos)
      d.type = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    else
      d.type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    EXPECT_EQ(found.count(n), 0u) << "binding " << n << " declared twice";
    found[n] = d;
  }
  return found;
}

TEST(Bindings, TheEnumIsGeneratedFromTheGlslDeclarations) {
  const std::map<uint32_t, Declared> glsl = glsl_bindings();
  ASSERT_EQ(glsl.size(), size_t(kBindingCount));
  for (uint32_t i = 0; i < kBindingCount; ++i) {
    ASSERT_TRUE(glsl.count(i)) << "binding " << i << " is not declared in bindings_inc.glsl";
    EXPECT_EQ(glsl.at(i).name, binding_name(Binding(i))) << "binding " << i;
  }
  EXPECT_STREQ(binding_name(kBindingCount), "(no such binding)");
  // Spot checks of the names the C++ uses: an image, a sampler, a block.
  EXPECT_STREQ(binding_name(kSkyViewLut), "sky_view_lut");
  EXPECT_STREQ(binding_name(kWeatherMapOut), "weather_map_out");
  EXPECT_STREQ(binding_name(kFrameParams), "FrameParamsBlock");
  EXPECT_EQ(kFrameParams, 0u);
}

// Every embedded shader: the bindings its entry point uses, each of the type bindings_inc.glsl
// declares, and no more storage images or samplers than lavapipe takes a stage (32 each).
TEST(Bindings, EveryShaderUsesDeclaredBindingsWithinTheStageLimits) {
  const std::map<uint32_t, Declared> glsl = glsl_bindings();
  size_t shaders = 0, most_images = 0, most_samplers = 0, fewest = 1000, most = 0;
  for (size_t f = 0; f < nephele_shaders::kFileCount; ++f) {
    const std::string name = nephele_shaders::kFiles[f].name;
    if (!name.ends_with(".spv")) continue;
    const VkShaderStageFlagBits stage =
        name.find(".vert.") != std::string::npos   ? VK_SHADER_STAGE_VERTEX_BIT
        : name.find(".frag.") != std::string::npos ? VK_SHADER_STAGE_FRAGMENT_BIT
                                                    : VK_SHADER_STAGE_COMPUTE_BIT;
    const std::vector<ShaderBinding> bindings = reflect_embedded(name, stage);
    ++shaders;
    size_t images = 0, samplers = 0;
    for (const ShaderBinding& b : bindings) {
      EXPECT_EQ(b.stages, VkShaderStageFlags(stage)) << name;
      if (b.set == kModuleSet) {  // a module's own, by name
        EXPECT_FALSE(b.name.empty()) << name << ", set 1, binding " << b.binding;
        continue;
      }
      ASSERT_EQ(b.set, 0u) << name;
      ASSERT_TRUE(glsl.count(b.binding)) << name << " uses undeclared binding " << b.binding;
      EXPECT_EQ(b.type, glsl.at(b.binding).type) << name << ", binding " << b.binding;
      // The build keeps the names in the optimised SPIR-V (cmake/spv_strip.cpp).
      EXPECT_EQ(b.name, glsl.at(b.binding).name) << name << ", binding " << b.binding;
      images += b.type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
      samplers += b.type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    }
    EXPECT_LE(images, 32u) << name;
    EXPECT_LE(samplers, 32u) << name;
    most_images = std::max(most_images, images);
    most_samplers = std::max(most_samplers, samplers);
    fewest = std::min(fewest, bindings.size());
    most = std::max(most, bindings.size());
  }
  EXPECT_GE(shaders, 40u);
  // No pass sees the whole table any more.
  EXPECT_LT(most, size_t(kBindingCount) / 2);
  std::printf("%zu shaders: %zu to %zu bindings each of %u; at most %zu storage images and %zu "
              "samplers in one\n",
              shaders, fewest, most, unsigned(kBindingCount), most_images, most_samplers);
}

TEST(Bindings, APassSeesExactlyTheBindingsItsShaderUses) {
  // meter.comp reads the frame's parameters and the final image and writes the meter's block.
  const std::vector<ShaderBinding> meter = reflect_embedded("meter.comp.spv", VK_SHADER_STAGE_COMPUTE_BIT);
  std::set<uint32_t> numbers;
  for (const ShaderBinding& b : meter) numbers.insert(b.binding);
  EXPECT_EQ(numbers, (std::set<uint32_t>{kFrameParams, kColorRw, kMeter}));
  // The particles' raster pipeline: what its vertex and fragment shaders use, each binding
  // visible to the stages that use it.
  const std::vector<ShaderBinding> particles =
      merge_bindings({reflect_embedded("particles.vert.spv", VK_SHADER_STAGE_VERTEX_BIT),
                      reflect_embedded("particles.frag.spv", VK_SHADER_STAGE_FRAGMENT_BIT)});
  std::map<uint32_t, VkShaderStageFlags> stages;
  for (const ShaderBinding& b : particles) stages[b.binding] = b.stages;
  ASSERT_TRUE(stages.count(kParticles));
  EXPECT_TRUE(stages.at(kParticles) & VK_SHADER_STAGE_VERTEX_BIT);
  ASSERT_TRUE(stages.count(kParticleTextures));
  EXPECT_EQ(stages.at(kParticleTextures), VkShaderStageFlags(VK_SHADER_STAGE_FRAGMENT_BIT));
  EXPECT_FALSE(stages.count(kBaseNoise));
}

// Compose reads what it blends through a fixed set of samplers: the layers besides the
// volumetric clouds (the surfaces, the particle clouds, those to come) are layers of one
// array (render/image_layers.h), so that a new layer adds none. (base_noise: the cirrus;
// weather_map: where the rain falls over a surface; forecast_cover: both, under a forecast.) The
// media's own samplers are theirs, in set 1, by name.
TEST(Bindings, ComposeReadsItsLayersThroughOneArray) {
  std::set<std::string> samplers, module_samplers;
  for (const ShaderBinding& b : reflect_embedded("compose.comp.spv", VK_SHADER_STAGE_COMPUTE_BIT)) {
    if (b.type != VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER) continue;
    if (b.set == 0)
      samplers.insert(binding_name(Binding(b.binding)));
    else
      module_samplers.insert(b.name);
  }
  EXPECT_EQ(samplers, (std::set<std::string>{
                          "sky_view_lut", "clouds_a", "clouds_b", "transmittance_lut",
                          "aerial_perspective", "reference_sky", "ground_light", "light_shafts",
                          "base_noise", "layers", "weather_map", "forecast_cover"}));
  EXPECT_EQ(module_samplers,
            (std::set<std::string>{"precipitation_froxels", "precipitation_depth"}));
}

TEST(Bindings, ReflectionRefusesWhatIsNotSpirv) {
  const uint32_t words[] = {0xdeadbeef, 1, 2, 3, 4, 5, 6, 7};
  try {
    reflect_spirv(words, 8, VK_SHADER_STAGE_COMPUTE_BIT, "junk.comp.spv");
    FAIL() << "no error";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("junk.comp.spv"), std::string::npos) << e.what();
  }
  EXPECT_THROW(reflect_embedded("no_such.comp.spv", VK_SHADER_STAGE_COMPUTE_BIT), RuntimeError);
  // Two stages using one binding as different kinds of descriptor cannot share a layout.
  EXPECT_THROW(merge_bindings({{{3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_VERTEX_BIT}},
                               {{3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                 VK_SHADER_STAGE_FRAGMENT_BIT}}}),
               RuntimeError);
}

// What a RuntimeError says, or "(no error)".
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const RuntimeError& e) {
    return e.what();
  }
  return "(no error)";
}

std::vector<ShaderBinding> reflect_test_shader(const std::string& name) {
  const std::span<const uint32_t> words = test_shader(name);
  return reflect_spirv(words.data(), words.size(), VK_SHADER_STAGE_COMPUTE_BIT, name);
}

// A module's own resources are in set 1, by the names the shader gives them (a block's name, an
// image's variable name), at the shader's own numbers; set 0's beside them keep theirs.
TEST(Bindings, SetOneResourcesAreReflectedWithTheirNames) {
  const std::vector<ShaderBinding> both = reflect_test_shader("module_set.comp");
  ASSERT_EQ(both.size(), 3u);
  const VkShaderStageFlags compute = VK_SHADER_STAGE_COMPUTE_BIT;
  EXPECT_EQ(both[0].set, 0u);
  EXPECT_EQ(both[0].binding, uint32_t(kColorRw));
  EXPECT_EQ(both[0].type, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
  EXPECT_EQ(both[0].name, "color_rw");
  EXPECT_EQ(both[1].set, kModuleSet);
  EXPECT_EQ(both[1].binding, 0u);
  EXPECT_EQ(both[1].type, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  EXPECT_EQ(both[1].name, "TestModuleBlock");
  EXPECT_EQ(both[2].set, kModuleSet);
  EXPECT_EQ(both[2].binding, 1u);
  EXPECT_EQ(both[2].type, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
  EXPECT_EQ(both[2].name, "test_module_map");
  for (const ShaderBinding& b : both) EXPECT_EQ(b.stages, compute) << b.name;

  // Set 1 alone, with the numbers the other way round and a storage block.
  const std::vector<ShaderBinding> only = reflect_test_shader("module_set_only.comp");
  ASSERT_EQ(only.size(), 3u);
  const std::pair<std::string, VkDescriptorType> expected[] = {
      {"test_module_map", VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
      {"TestModuleBlock", VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
      {"TestModuleOutBlock", VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
  for (uint32_t i = 0; i < 3; ++i) {
    EXPECT_EQ(only[i].set, kModuleSet);
    EXPECT_EQ(only[i].binding, i);
    EXPECT_EQ(only[i].name, expected[i].first);
    EXPECT_EQ(only[i].type, expected[i].second) << expected[i].first;
    EXPECT_EQ(only[i].stages, compute);
  }
}

// Sets 0 and 1 only; in set 1, neither a number with two names nor a name at two numbers (in one
// shader, or across a pipeline's stages).
TEST(Bindings, ReflectionRefusesOtherSetsAndAmbiguousSetOneBindings) {
  const std::string set_two = error_of([] { reflect_test_shader("module_set_2.comp"); });
  for (const char* part : {"module_set_2.comp", "'TestSetTwoBlock'", "set 2"})
    EXPECT_NE(set_two.find(part), std::string::npos) << set_two;
  EXPECT_EQ(set_two.find('\n'), std::string::npos) << set_two;

  const std::string twice = error_of([] { reflect_test_shader("module_set_twice.comp"); });
  for (const char* part :
       {"module_set_twice.comp", "set 1, binding 0", "'test_first'", "'test_second'"})
    EXPECT_NE(twice.find(part), std::string::npos) << twice;

  // module_set.comp has test_module_map at binding 1, module_set_only.comp at 0 (where the
  // other has TestModuleBlock): not one pipeline's stages.
  const std::string swapped = error_of([] {
    merge_bindings(
        {reflect_test_shader("module_set.comp"), reflect_test_shader("module_set_only.comp")},
        "test.vert + test.frag");
  });
  for (const char* part : {"test.vert + test.frag", "'test_module_map'", "'TestModuleBlock'"})
    EXPECT_NE(swapped.find(part), std::string::npos) << swapped;
  const VkDescriptorType sampler = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  const std::string moved = error_of([&] {
    merge_bindings({{{1, sampler, VK_SHADER_STAGE_VERTEX_BIT, kModuleSet, "fog_map"}},
                    {{3, sampler, VK_SHADER_STAGE_FRAGMENT_BIT, kModuleSet, "fog_map"}}},
                   "fog.vert + fog.frag");
  });
  for (const char* part : {"fog.vert + fog.frag", "'fog_map'", "binding 1", "binding 3"})
    EXPECT_NE(moved.find(part), std::string::npos) << moved;

  const std::string renamed = error_of([] {
    merge_bindings({{{2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_VERTEX_BIT, kModuleSet,
                      "FogBlock"}},
                    {{2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT,
                      kModuleSet, "MistBlock"}}},
                   "p");
  });
  for (const char* part : {"set 1, binding 2", "'FogBlock'", "'MistBlock'", "pipeline p"})
    EXPECT_NE(renamed.find(part), std::string::npos) << renamed;
}

// A raster pipeline's two stages: one entry a (set, binding), visible to the stages that use it;
// the same number in sets 0 and 1 is two bindings.
TEST(Bindings, MergingKeepsTheSetsApartAndTheStagesRight) {
  const VkShaderStageFlags vert = VK_SHADER_STAGE_VERTEX_BIT, frag = VK_SHADER_STAGE_FRAGMENT_BIT;
  const std::vector<ShaderBinding> merged =
      merge_bindings({{{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, vert, 0, "FrameParamsBlock"},
                       {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, vert, kModuleSet, "FogBlock"}},
                      {{1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, frag, kModuleSet, "fog_map"},
                       {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, frag, kModuleSet, "FogBlock"},
                       {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, frag, 0, "FrameParamsBlock"}}});
  ASSERT_EQ(merged.size(), 3u);
  EXPECT_EQ(merged[0].set, 0u);
  EXPECT_EQ(merged[0].binding, 0u);
  EXPECT_EQ(merged[0].stages, vert | frag);
  EXPECT_EQ(merged[1].set, kModuleSet);
  EXPECT_EQ(merged[1].binding, 0u);
  EXPECT_EQ(merged[1].name, "FogBlock");
  EXPECT_EQ(merged[1].stages, vert | frag);
  EXPECT_EQ(merged[2].set, kModuleSet);
  EXPECT_EQ(merged[2].binding, 1u);
  EXPECT_EQ(merged[2].name, "fog_map");
  EXPECT_EQ(merged[2].stages, frag);
}

}  // namespace
}  // namespace nephele::gpu

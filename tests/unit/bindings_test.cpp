// The one descriptor set's layout is declared twice, in GLSL (shaders/common/bindings_inc.glsl)
// and in C++ (gpu::Binding, gpu::binding_type): this static check proves they agree.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "gpu/kernel.h"

namespace nephele::gpu {
namespace {

// Binding number -> descriptor type, from the GLSL declarations.
std::map<uint32_t, VkDescriptorType> glsl_bindings(std::string& problems) {
  std::ifstream in(std::string(NEPHELE_SOURCE_DIR) + "/shaders/common/bindings_inc.glsl");
  std::map<uint32_t, VkDescriptorType> found;
  const std::regex declaration(
      R"(layout\(([^)]*)\)\s*(?:(?:readonly|writeonly|restrict|coherent)\s+)*(uniform|buffer)\s+(?:(?:readonly|writeonly|restrict|coherent)\s+)*(\w+))");
  const std::regex binding(R"(binding\s*=\s*(\d+))");
  std::string line;
  while (std::getline(in, line)) {
    std::smatch m, b;
    if (!std::regex_search(line, m, declaration)) continue;
    const std::string qualifiers = m[1];
    if (!std::regex_search(qualifiers, b, binding)) continue;
    const uint32_t n = uint32_t(std::stoul(b[1]));
    const std::string storage = m[2], type = m[3];
    VkDescriptorType t = VK_DESCRIPTOR_TYPE_MAX_ENUM;
    if (storage == "buffer")
      t = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    else if (type.starts_with("image") || type.starts_with("uimage") || type.starts_with("iimage"))
      t = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    else if (type.starts_with("sampler") || type.starts_with("usampler") ||
             type.starts_with("isampler"))
      t = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    else
      t = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;  // a uniform block
    if (found.count(n)) problems += "binding " + std::to_string(n) + " declared twice; ";
    found[n] = t;
  }
  return found;
}

TEST(Bindings, TheGlslDeclarationsAndTheCppLayoutAgree) {
  std::string problems;
  const std::map<uint32_t, VkDescriptorType> glsl = glsl_bindings(problems);
  EXPECT_EQ(problems, "");
  EXPECT_EQ(glsl.size(), size_t(kBindingCount))
      << "bindings_inc.glsl declares " << glsl.size() << ", gpu::Binding counts " << kBindingCount;
  for (uint32_t i = 0; i < kBindingCount; ++i) {
    const auto it = glsl.find(i);
    ASSERT_NE(it, glsl.end()) << "binding " << i << " is not declared in bindings_inc.glsl";
    EXPECT_EQ(it->second, binding_type(Binding(i))) << "binding " << i;
  }
  EXPECT_EQ(binding_type(kBindingCount), VK_DESCRIPTOR_TYPE_MAX_ENUM);
}

}  // namespace
}  // namespace nephele::gpu

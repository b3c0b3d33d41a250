// The tests' own shaders (tests/shaders/*.comp): compiled as the library's are (glslc -O with
// the names kept) and embedded into the test binary alone (tests/CMakeLists.txt).
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

#include "nephele_embedded.h"

namespace nephele_test_shaders {
extern const EmbeddedFile kFiles[];
extern const size_t kFileCount;
}  // namespace nephele_test_shaders

// The SPIR-V words of tests/shaders/`name` without ".spv" ("module_set.comp").
inline std::span<const uint32_t> test_shader(const std::string& name) {
  const EmbeddedFile* file =
      find_embedded(nephele_test_shaders::kFiles, nephele_test_shaders::kFileCount, name + ".spv");
  if (!file) throw std::runtime_error("no test shader " + name);
  return {reinterpret_cast<const uint32_t*>(file->data), file->size / 4};
}

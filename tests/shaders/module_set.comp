// A test shader (tests/render/module_bindings_test.cpp): reads a module's own uniform block and
// image from descriptor set 1, by name, and writes the global table's color_rw (set 0).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"

layout(local_size_x = 4, local_size_y = 4) in;

layout(std140, set = 1, binding = 0) uniform TestModuleBlock {
  vec4 scale;
  vec4 offset;
} test_module;
layout(set = 1, binding = 1) uniform sampler2D test_module_map;

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  imageStore(color_rw, p, texelFetch(test_module_map, p, 0) * test_module.scale + test_module.offset);
}

// A test shader (tests/render/module_bindings_test.cpp): set 1 alone, its numbers its own (the
// image at 0, the block at 1: module_set.comp has them the other way round), the result into a
// storage block of set 1.
#version 450

layout(local_size_x = 4, local_size_y = 4) in;

layout(set = 1, binding = 0) uniform sampler2D test_module_map;
layout(std140, set = 1, binding = 1) uniform TestModuleBlock {
  vec4 scale;
  vec4 offset;
} test_module;
layout(std430, set = 1, binding = 2) writeonly buffer TestModuleOutBlock { vec4 texels[16]; } test_out;

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  test_out.texels[p.y * 4 + p.x] = texelFetch(test_module_map, p, 0) * test_module.scale + test_module.offset;
}

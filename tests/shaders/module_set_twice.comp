// A test shader (tests/unit/bindings_test.cpp) that reflection refuses: two resources at one
// binding of set 1.
#version 450
layout(local_size_x = 1) in;
layout(set = 1, binding = 0) uniform sampler2D test_first;
layout(set = 1, binding = 0) uniform sampler2D test_second;
layout(set = 1, binding = 1) writeonly buffer TestTwiceOutBlock { vec4 v; } test_twice_out;
void main() { test_twice_out.v = texture(test_first, vec2(0.5)) + texture(test_second, vec2(0.5)); }

// A test shader (tests/unit/bindings_test.cpp) that reflection refuses: a resource in set 2.
#version 450
layout(local_size_x = 1) in;
layout(set = 2, binding = 0) writeonly buffer TestSetTwoBlock { vec4 v; } test_set_two;
void main() { test_set_two.v = vec4(1.0); }

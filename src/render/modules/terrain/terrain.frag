#version 450
// The terrain mesh's distance from the eye per pixel (terrain.vert), in alpha, where
// terrain.comp reads it back and writes the pixel's light beside it.
layout(location = 0) in vec3 from_eye;
layout(location = 0) out vec4 distance_out;

void main() { distance_out = vec4(0.0f, 0.0f, 0.0f, length(from_eye)); }

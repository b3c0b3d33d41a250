#version 450
// Pass: bloom and glare (render/modules/post/post.h). The lens spreads a share s (frame.bloom.x) of
// the light above the threshold over a Gaussian: out = c - s B(c) + s (G * B(c)), B(c) =
// max(c - threshold, 0) per channel, G separable, truncated at R taps each side and normalised
// over them, reflected at the image's edges (about -0.5 and size - 0.5): with a symmetric
// kernel, a reflected gather is exactly a scatter that folds back what would leave the image,
// so the sum of the image is kept. PASS 0: B(c) blurred along x into post_temp; PASS 1: that
// blurred along y, the result added to the image.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"

layout(constant_id = 0) const int PASS = 0;
layout(local_size_x = 8, local_size_y = 8) in;

// The index i reflected into [0, n) (once: R < n).
int reflected(int i, int n) {
  if (i < 0) i = -1 - i;
  if (i >= n) i = 2 * n - 1 - i;
  return clamp(i, 0, n - 1);
}

vec3 bright(vec3 c) { return max(c - vec3(frame.bloom.y), vec3(0.0f)); }

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = frame.size.xy;
  if (p.x >= size.x || p.y >= size.y) return;
  float sigma = frame.bloom.z;
  int taps = int(frame.bloom.w);
  float norm = 0.0f;
  vec3 sum = vec3(0.0f);
  for (int d = -taps; d <= taps; ++d) {
    float w = exp(-0.5f * float(d * d) / (sigma * sigma));
    norm += w;
    if (PASS == 0)
      sum += w * bright(imageLoad(color_rw, ivec2(reflected(p.x + d, size.x), p.y)).rgb);
    else
      sum += w * imageLoad(post_temp, ivec2(p.x, reflected(p.y + d, size.y))).rgb;
  }
  sum /= norm;
  if (PASS == 0) {
    imageStore(post_temp, p, vec4(sum, 0.0f));
  } else {
    vec4 c = imageLoad(color_rw, p);
    float s = frame.bloom.x;
    imageStore(color_rw, p, vec4(c.rgb - s * bright(c.rgb) + s * sum, c.a));
  }
}

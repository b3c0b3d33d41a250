#version 450
// Pass: resolve (temporal reprojection, seed 002 section 4). Builds this frame's cloud buffer
// from the pixels marched this frame (one per stride x stride block, march_out) and the
// previous frame's buffer (history): every other pixel is found in the previous frame by
// following its ray to the cloud's distance, moving that point back by the wind's
// displacement since then, and projecting it with the previous camera. Where the point falls
// outside the previous image, or no history exists, the marched samples around the pixel are
// interpolated (the low-resolution fallback). While the image moves, reprojected values are
// clamped to the range of the marched samples around them so stale content cannot smear.
// A marched pixel averages its new sample with its reprojected history when both see the same
// surface, so a still view keeps converging over the jittered frames.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

const float MAX_SAMPLES = 8.0f;  // marched samples averaged per pixel in a still view

// The two vec4 of one cloud pixel (bindings_inc.glsl); b.w = the number of marched samples
// averaged in it (reprojected along with it), 0 for an interpolated value.
struct CloudSample {
  vec4 a;
  vec4 b;
};

CloudSample mix_samples(CloudSample x, CloudSample y, float w) {
  CloudSample r;
  r.a = mix(x.a, y.a, w);
  r.b = mix(x.b, y.b, w);
  return r;
}

int stride() { return frame.cloud_grid.z; }
int blocks_x() { return (frame.cloud_grid.x + stride() - 1) / stride(); }

CloudSample marched(ivec2 block) {
  int i = block.y * blocks_x() + block.x;
  CloudSample s;
  s.a = march_out[2 * i];
  s.b = vec4(march_out[2 * i + 1].xyz, 1.0f);
  return s;
}

// Blocks whose marched pixel lies inside the buffer: 0 ... last.
ivec2 last_block() { return (frame.cloud_grid.xy - 1 - frame.march_offset.xy) / stride(); }

// Continuous block coordinates of pixel p (marched pixels at integers).
vec2 block_coord(ivec2 p) {
  return clamp(vec2(p - frame.march_offset.xy) / float(stride()), vec2(0.0f), vec2(last_block()));
}

// The marched samples around pixel p, interpolated bilinearly (the low-resolution fallback).
CloudSample interpolated(ivec2 p) {
  vec2 g = block_coord(p);
  ivec2 i0 = ivec2(floor(g));
  ivec2 i1 = min(i0 + 1, last_block());
  vec2 f = g - vec2(i0);
  CloudSample r = mix_samples(mix_samples(marched(i0), marched(ivec2(i1.x, i0.y)), f.x),
                              mix_samples(marched(ivec2(i0.x, i1.y)), marched(i1), f.x), f.y);
  r.b.w = 0.0f;
  return r;
}

// The range (lo, hi) of the radiance and transmittance over the 4 x 4 marched samples around
// p (a 16 x 16 pixel neighbourhood at stride 4): wide enough that detail between samples
// survives, tight enough to catch stale content.
void marched_range(ivec2 p, out vec4 lo, out vec4 hi) {
  ivec2 i0 = ivec2(floor(block_coord(p)));
  lo = vec4(1e30f);
  hi = vec4(-1e30f);
  for (int y = -1; y <= 2; ++y)
    for (int x = -1; x <= 2; ++x) {
      vec4 a = marched(clamp(i0 + ivec2(x, y), ivec2(0), last_block())).a;
      lo = min(lo, a);
      hi = max(hi, a);
    }
}

CloudSample history_at(ivec2 p) {
  int i = p.y * frame.cloud_grid.x + p.x;
  CloudSample s;
  s.a = history[2 * i];
  s.b = history[2 * i + 1];
  return s;
}

// Catmull-Rom weights for the four texels around a sample at fraction f.
vec4 catmull_rom_weights(float f) {
  float f2 = f * f, f3 = f2 * f;
  return vec4(-0.5f * f3 + f2 - 0.5f * f, 1.5f * f3 - 2.5f * f2 + 1.0f,
              -1.5f * f3 + 2.0f * f2 + 0.5f * f, 0.5f * f3 - 0.5f * f2);
}

// The history's radiance and transmittance at q, filtered with Catmull-Rom (4 x 4 texels): a
// pixel is resampled up to stride^2 times before it is marched again, and bilinear filtering
// would blur it a little more each time.
vec4 history_sharp(vec2 q) {
  ivec2 last = frame.cloud_grid.xy - 1;
  vec2 g = clamp(q, vec2(0.0f), vec2(last));
  ivec2 i0 = ivec2(floor(g));
  vec2 f = g - vec2(i0);
  vec4 wx = catmull_rom_weights(f.x), wy = catmull_rom_weights(f.y);
  vec4 sum = vec4(0.0f);
  for (int y = 0; y < 4; ++y) {
    vec4 row = vec4(0.0f);
    for (int x = 0; x < 4; ++x)
      row += wx[x] * history[2 * (clamp(i0.y + y - 1, 0, last.y) * frame.cloud_grid.x +
                                  clamp(i0.x + x - 1, 0, last.x))];
    sum += wy[y] * row;
  }
  return sum;
}

// The history bilinearly filtered at continuous pixel position q (centres at integers).
CloudSample history_bilinear(vec2 q) {
  ivec2 last = frame.cloud_grid.xy - 1;
  vec2 g = clamp(q, vec2(0.0f), vec2(last));
  ivec2 i0 = ivec2(floor(g));
  ivec2 i1 = min(i0 + 1, last);
  vec2 f = g - vec2(i0);
  return mix_samples(mix_samples(history_at(i0), history_at(ivec2(i1.x, i0.y)), f.x),
                     mix_samples(history_at(ivec2(i0.x, i1.y)), history_at(i1), f.x), f.y);
}

// Where the content at distance_m along `dir` was in the previous frame's image.
vec2 previous_pixel(vec3 dir, float distance_m) {
  // Relative to the previous eye: the point, moved back by the wind since the last frame.
  vec3 p = dir * distance_m - frame.prev_camera_pos_m.xyz -
           vec3(frame.wind_offset_m.z, frame.wind_offset_m.w, 0.0f);
  return camera_pixel(frame.prev_camera_forward.xyz, frame.prev_camera_right.xyz,
                      frame.prev_camera_up.xyz, frame.prev_camera_pos_m.w,
                      frame.prev_camera_forward.w, normalize(p), float(frame.cloud_grid.x),
                      float(frame.cloud_grid.y));
}

bool inside_image(vec2 q) {
  return all(greaterThanEqual(q, vec2(-0.5f))) &&
         all(lessThanEqual(q, vec2(frame.cloud_grid.xy) - 0.5f));
}

bool ray_meets_no_cloud(ivec2 p) {
  vec3 eye = frame.camera_pos_m.xyz;
  if (length(eye) >= frame.radii_m.z) return false;
  vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                        frame.camera_pos_m.w, frame.camera_forward.w, float(p.x), float(p.y),
                        float(frame.cloud_grid.x), float(frame.cloud_grid.y));
  return ray_sphere(eye, dir, frame.radii_m.x).x > 0.0f;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= frame.cloud_grid.x || p.y >= frame.cloud_grid.y) return;
  ivec2 offset = frame.march_offset.xy;
  bool is_marched = (p.x % stride()) == offset.x && (p.y % stride()) == offset.y;

  CloudSample result = is_marched ? marched(p / stride()) : interpolated(p);

  if (frame.cloud_grid.w == 1) {
    vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                          frame.camera_pos_m.w, frame.camera_forward.w, float(p.x), float(p.y),
                          float(frame.cloud_grid.x), float(frame.cloud_grid.y));
    // Two fixed-point steps: distance from this frame's samples, then from the history there.
    vec2 q = previous_pixel(dir, result.b.z);
    if (inside_image(q)) q = previous_pixel(dir, history_bilinear(q).b.z);
    if (inside_image(q)) {
      CloudSample h = history_bilinear(q);
      float moved_px = length(q - vec2(p));
      if (is_marched) {
        // Average with the history only where it is a real sample of the same surface.
        float d = result.b.z;
        // The running mean of up to MAX_SAMPLES samples (b.w counts them), so a still view
        // converges while a moving one, or new content, starts afresh.
        bool same = abs(h.b.z - d) < 0.1f * d && moved_px < 1.0f;
        float n = same ? min(floor(h.b.w + 0.5f), MAX_SAMPLES - 1.0f) : 0.0f;
        result = mix_samples(result, h, n / (n + 1.0f));
        result.b.w = n + 1.0f;
      } else {
        if (moved_px < 0.02f) {
          h = history_at(ivec2(round(q)));  // (nearly) still: the pixel itself, unfiltered
        } else {
          h.a = max(history_sharp(q), vec4(0.0f));  // Catmull-Rom may overshoot a little
        }
        if (moved_px > 0.5f) {
          // While the image moves, keep the history within the range of this frame's samples.
          vec4 lo, hi;
          marched_range(p, lo, hi);
          h.a = clamp(h.a, lo, hi);
        }
        result = h;
      }
    }
  }
  // Rays that cannot meet a cloud (from below the layer into the ground) hold none, exactly,
  // whatever the filters brought in from the horizon's other side.
  if (ray_meets_no_cloud(p)) result.a = vec4(0.0f, 0.0f, 0.0f, 1.0f);
  int i = p.y * frame.cloud_grid.x + p.x;
  cloud_out[2 * i] = result.a;
  cloud_out[2 * i + 1] = result.b;
}

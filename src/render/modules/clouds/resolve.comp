#version 450
// Pass: resolve (temporal reprojection, seed 002 section 4). Builds this frame's cloud buffer
// from the pixels marched this frame (one per stride x stride block, march_a/b) and the
// previous frame's buffer (history_a/b): every other pixel is found in the previous frame by
// following its ray to the cloud's distance, moving that point back by the wind's
// displacement since then, and projecting it with the previous camera. Where the point falls
// outside the previous image, or no history exists, the marched samples around the pixel are
// interpolated (the low-resolution fallback). While the image moves, reprojected values are
// clamped to the range of the marched samples around them so stale content cannot smear.
// A marched pixel averages its new sample with its reprojected history when both see the same
// surface, so a still view keeps converging over the jittered frames.
//
// Every read is a texture fetch, most of them filtered by the sampler: on a CPU device
// (lavapipe) that is one vector gather where a storage buffer is read lane by lane.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "entering_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

const float MAX_SAMPLES = 8.0f;  // marched samples averaged per pixel in a still view

// One cloud pixel (bindings_inc.glsl): a = radiance and transmittance, b = haze, ground
// shadow, distance (km) and the number of marched samples averaged in it (0 for an
// interpolated value).
struct CloudSample {
  vec4 a;
  vec4 b;
};

int stride() { return frame.cloud_grid.z; }

// Blocks whose marched pixel lies inside the buffer: 0 ... last.
ivec2 last_block() { return (frame.cloud_grid.xy - 1 - frame.march_offset.xy) / stride(); }

// Continuous block coordinates of pixel p (marched pixels at integers).
vec2 block_coord(ivec2 p) {
  return clamp(vec2(p - frame.march_offset.xy) / float(stride()), vec2(0.0f), vec2(last_block()));
}

// The marched samples around pixel p, interpolated bilinearly (the low-resolution fallback).
CloudSample interpolated(ivec2 p) {
  vec2 uv = (block_coord(p) + 0.5f) / vec2(textureSize(march_a, 0));
  CloudSample r;
  r.a = textureLod(march_a, uv, 0.0f);
  r.b = vec4(textureLod(march_b, uv, 0.0f).xyz, 0.0f);
  return r;
}

// The strip k (entering_inc.glsl) holds p.
bool entering_covers(int k, ivec2 p) {
  ivec4 strip = entering_strip(k);
  ivec2 i = p - strip.xy;
  return all(greaterThanEqual(i, ivec2(0))) && all(lessThan(i, strip.zw));
}

// The strip's samples around p, interpolated bilinearly: two pixels apart where the blocks'
// are four (stride 4), for where the history has nothing.
CloudSample entering_interpolated(int k, ivec2 p) {
  ivec4 strip = entering_strip(k);
  vec2 u = clamp(vec2(p - strip.xy) * 0.5f, vec2(0.0f), vec2((strip.zw - 1) / 2));
  vec2 uv = (vec2(entering_storage(k)) + u + 0.5f) / vec2(textureSize(march_a, 0));
  CloudSample r;
  r.a = textureLod(march_a, uv, 0.0f);
  r.b = vec4(textureLod(march_b, uv, 0.0f).xyz, 0.0f);
  return r;
}

vec2 history_uv(vec2 q) { return (q + 0.5f) / vec2(frame.cloud_grid.xy); }

// The history's radiance and transmittance at continuous pixel position q, filtered with
// Catmull-Rom: a pixel is resampled up to stride^2 times before it is marched again, and
// bilinear filtering would blur it a little more each time. Five bilinear fetches (the 4 x 4
// texel kernel without its corners, whose weights are products of the small negative lobes,
// renormalised).
vec4 history_sharp(vec2 q) {
  vec2 c = floor(q);
  vec2 f = q - c;
  vec2 f2 = f * f, f3 = f2 * f;
  vec2 w0 = -0.5f * f3 + f2 - 0.5f * f;
  vec2 w1 = 1.5f * f3 - 2.5f * f2 + 1.0f;
  vec2 w2 = -1.5f * f3 + 2.0f * f2 + 0.5f * f;
  vec2 w3 = 0.5f * f3 - 0.5f * f2;
  vec2 w12 = w1 + w2;
  vec2 t0 = c - 1.0f, t12 = c + w2 / w12, t3 = c + 2.0f;
  vec4 sum = textureLod(history_a, history_uv(vec2(t12.x, t0.y)), 0.0f) * (w12.x * w0.y) +
             textureLod(history_a, history_uv(vec2(t0.x, t12.y)), 0.0f) * (w0.x * w12.y) +
             textureLod(history_a, history_uv(t12), 0.0f) * (w12.x * w12.y) +
             textureLod(history_a, history_uv(vec2(t3.x, t12.y)), 0.0f) * (w3.x * w12.y) +
             textureLod(history_a, history_uv(vec2(t12.x, t3.y)), 0.0f) * (w12.x * w3.y);
  float weight = w12.x * w0.y + w0.x * w12.y + w12.x * w12.y + w3.x * w12.y + w12.x * w3.y;
  return sum / weight;
}

// Where the content at distance_km along `dir` was in the previous frame's image.
vec2 previous_pixel(vec3 dir, float distance_km) {
  // Relative to the previous eye: the point, moved back by the wind since the last frame.
  vec3 p = dir * (distance_km * 1e3f) - frame.prev_camera_pos_m.xyz -
           vec3(frame.wind_offset_m.z, frame.wind_offset_m.w, 0.0f);
  return camera_pixel(frame.prev_camera_forward.xyz, frame.prev_camera_right.xyz,
                      frame.prev_camera_up.xyz, frame.prev_camera_pos_m.w,
                      frame.prev_camera_forward.w, normalize(p), float(frame.cloud_grid.x),
                      float(frame.cloud_grid.y),
                      vec2(frame.prev_camera_right.w, frame.prev_camera_up.w));
}

bool inside_image(vec2 q) {
  return all(greaterThanEqual(q, vec2(-0.5f))) &&
         all(lessThanEqual(q, vec2(frame.cloud_grid.xy) - 0.5f));
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= frame.cloud_grid.x || p.y >= frame.cloud_grid.y) return;
  ivec2 offset = frame.march_offset.xy;
  bool is_marched = (p.x % stride()) == offset.x && (p.y % stride()) == offset.y;

  CloudSample result;
  if (is_marched) {
    result.a = texelFetch(march_a, p / stride(), 0);
    result.b = texelFetch(march_b, p / stride(), 0);
  } else {
    result = interpolated(p);
  }

  vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                        frame.camera_pos_m.w, frame.camera_forward.w, float(p.x), float(p.y),
                        float(frame.cloud_grid.x), float(frame.cloud_grid.y),
                        vec2(frame.camera_right.w, frame.camera_up.w));
  if (frame.cloud_grid.w >= 1) {
    // Two fixed-point steps: distance from this frame's samples, then from the history there.
    vec2 q = previous_pixel(dir, result.b.z);
    if (inside_image(q)) q = previous_pixel(dir, textureLod(history_b, history_uv(q), 0.0f).z);
    if (!inside_image(q) && !is_marched && entering_covers(0, p)) {
      result = entering_interpolated(0, p);
    } else if (!inside_image(q) && !is_marched && entering_covers(1, p)) {
      result = entering_interpolated(1, p);
    } else if (inside_image(q)) {
      float moved_px = length(q - vec2(p));
      // Filtered wherever q falls, also when it moved by a fraction of a pixel: snapping a
      // nearly still pixel to its texel kept slowly drifting clouds where they had been
      // (still-camera error 2.0% -> 1.9% at 80 frames, 2.5% -> 2.2% at 120).
      CloudSample h;
      h.a = max(history_sharp(q), vec4(0.0f));  // Catmull-Rom may overshoot a little
      h.b = textureLod(history_b, history_uv(q), 0.0f);
      if (is_marched) {
        // Average with the history only where it is a real sample of the same surface.
        float d = result.b.z;
        // The running mean of up to MAX_SAMPLES samples (b.w counts them), so a still view
        // converges while a moving one, or new content, starts afresh.
        bool same = abs(h.b.z - d) < 0.1f * d && moved_px < 1.0f && frame.cloud_grid.w == 1;
        float n = same ? min(floor(h.b.w + 0.5f), MAX_SAMPLES - 1.0f) : 0.0f;
        result.a = mix(result.a, h.a, n / (n + 1.0f));
        result.b = vec4(mix(result.b.xyz, h.b.xyz, n / (n + 1.0f)), n + 1.0f);
      } else {
        if (moved_px > 0.5f) {
          // While the image moves, keep the history within the range of this frame's samples.
          // The range of the 4 x 4 marched samples around p (march_range.comp): a 16 x 16
          // pixel neighbourhood at stride 4, wide enough that detail between samples
          // survives, tight enough to catch stale content.
          ivec2 i0 = ivec2(floor(block_coord(p)));
          h.a = clamp(h.a, imageLoad(range_lo, i0), imageLoad(range_hi, i0));
        }
        result = h;
      }
    }
  }
  // Rays that cannot meet a cloud (from below the layer into the ground) hold none, exactly,
  // whatever the filters brought in from the horizon's other side.
  vec3 eye = frame.camera_pos_m.xyz;
  if (length(eye) < frame.radii_m.z && ray_sphere(eye, dir, frame.radii_m.x).x > 0.0f)
    result.a = vec4(0.0f, 0.0f, 0.0f, 1.0f);
  imageStore(clouds_a_out, p, result.a);
  imageStore(clouds_b_out, p, result.b);
}

#version 450
// Pass: seed 002's screen-space god rays (quality.light_shafts = "screen"), after Mitchell,
// GPU Gems 3 ch. 13, and its radial blur. PASS 0: each pixel steps screen_shaft_samples times
// towards the sun's place on the screen, over `density` of the way, summing the occlusion
// image there, each sample weighted decay^i: the sky seen through the clouds
// (their transmittance from the cloud buffer, nothing below the horizon), brightest about the
// sun; into post_temp. PASS 1: that blurred along the same lines (as many samples again) and
// added to the image, in the sun's colour after the air, times screen_shaft_strength. Light is
// added, not conserved: the seed's look, for comparison with the volumetric shafts.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "terrain_inc.glsl"

layout(constant_id = 0) const int PASS = 0;
layout(local_size_x = 8, local_size_y = 8) in;

const float DENSITY = 0.8f;  // the share of the way to the sun the rays reach

// The sun's place on the screen in pixels (x right, y down), as camera_ray has it; z 1 when it
// is in front of the camera.
vec3 sun_on_screen(vec2 size) {
  vec3 sun = frame.sun_dir.xyz;
  float f = dot(sun, frame.camera_forward.xyz);
  float tan_half = frame.camera_pos_m.w, aspect = frame.camera_forward.w;
  float sx = (dot(sun, frame.camera_right.xyz) / max(f, 1e-6f) - frame.camera_right.w) / (tan_half * aspect);
  float sy = (dot(sun, frame.camera_up.xyz) / max(f, 1e-6f) - frame.camera_up.w) / tan_half;
  return vec3((sx + 1.0f) * 0.5f * size.x - 0.5f, (1.0f - sy) * 0.5f * size.y - 0.5f, f > 0.0f ? 1.0f : 0.0f);
}

// The occlusion image at pixel position q: the clouds' transmittance there, 0 below the
// horizon, times a glow about the sun (half at 17 deg).
float occlusion(vec2 q, vec2 size) {
  vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                        frame.camera_pos_m.w, frame.camera_forward.w, q.x, q.y, size.x, size.y,
                        vec2(frame.camera_right.w, frame.camera_up.w));
  vec3 up = normalize(frame.camera_pos_m.xyz);
  if (dot(dir, up) < 0.0f) return 0.0f;
  float transmittance = textureLod(clouds_a, (q + 0.5f) / size, 0.0f).a;
  if (terrain_distance_at((q + 0.5f) / size) > 0.0f) transmittance = 0.0f;  // the terrain occludes
  return transmittance * pow(max(dot(dir, frame.sun_dir.xyz), 0.0f), 16.0f);
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  vec2 size = vec2(frame.size.xy);
  if (p.x >= frame.size.x || p.y >= frame.size.y) return;
  vec3 sun = sun_on_screen(size);
  int n = int(frame.light_shafts.y);
  float decay = frame.light_shafts.w;
  vec2 step_px = (sun.xy - vec2(p)) * DENSITY / float(n);
  float weight = 1.0f, sum = 0.0f;
  vec2 q = vec2(p);
  if (PASS == 0) {
    for (int i = 0; i < n && sun.z > 0.0f; ++i) {
      sum += occlusion(q, size) * weight;
      weight *= decay;
      q += step_px;
    }
    imageStore(post_temp, p, vec4(sum / float(n)));
  } else {
    for (int i = 0; i < n && sun.z > 0.0f; ++i) {
      ivec2 k = clamp(ivec2(round(q)), ivec2(0), frame.size.xy - 1);
      sum += imageLoad(post_temp, k).r;
      q += step_px / float(n);  // the blur spans one step of the rays
    }
    vec3 sunlight = frame.sun_illuminance.rgb * frame.sun_transmittance.rgb / PI;
    vec4 c = imageLoad(color_rw, p);
    imageStore(color_rw, p, vec4(c.rgb + frame.light_shafts.z * sunlight * sum / float(n), c.a));
  }
}

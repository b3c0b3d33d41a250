#version 450
// Pass: the host's environment cube map (render/modules/host_lighting/host_lighting.h), one thread per texel
// of its six faces side by side (+X -X +Y -Y +Z -Z of ENU, the faces' texel directions as a
// Vulkan cube map's): the sky and the lit ground of the sky-view table, behind the clouds
// marched along the texel's direction in ENVIRONMENT_STEPS steps over the cloud shell (at most
// ENVIRONMENT_REACH_M away), lit as the view's clouds are (cloud_light: the diffusion field, the
// two-stream light or the octaves, as the scene's lighting) but more cheaply: the key light's
// depth through the light volume (or a short light march beyond it), the sky's light from
// above, the ground's from below. For image-based lighting and reflections.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/atmosphere_inc.glsl"
#include "common/atmosphere_lut_inc.glsl"
#include "common/clouds_inc.glsl"
#include "frame_atmosphere_inc.glsl"
#include "sky_light_inc.glsl"
const int MARCH_MODE = 0;  // cloud_field_inc.glsl's lookups
#include "cloud_field_inc.glsl"
#include "render/modules/cloud_diffusion/cloud_diffusion_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

const int ENVIRONMENT_STEPS = 32;
const float ENVIRONMENT_REACH_M = 40000.0f;

// The direction through texel (s, t) in [-1, 1]^2 of cube face `face`.
vec3 cube_direction(int face, vec2 st) {
  vec3 d = face == 0   ? vec3(1.0f, -st.y, -st.x)
           : face == 1 ? vec3(-1.0f, -st.y, st.x)
           : face == 2 ? vec3(st.x, 1.0f, st.y)
           : face == 3 ? vec3(st.x, -1.0f, -st.y)
           : face == 4 ? vec3(st.x, -st.y, 1.0f)
                       : vec3(-st.x, -st.y, -1.0f);
  return normalize(d);
}

void main() {
  int size = frame.host_shadow_grid.z;
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (texel.x >= 6 * size || texel.y >= size) return;
  int face = texel.x / size;
  vec2 st = (vec2(texel.x - face * size, texel.y) + 0.5f) / float(size) * 2.0f - 1.0f;
  vec3 dir = cube_direction(face, st);
  vec3 eye = frame.camera_pos_m.xyz;
  vec3 illuminance = frame.sun_illuminance.rgb;
  SkyViewFrame f = sky_view_frame_from(frame.sky_view_up, frame.sky_view_forward);
  vec3 behind = sky_radiance(f, dir) * illuminance;

  vec2 segment = shell_segment(eye, dir, ray_sphere(eye, dir, frame.radii_m.x));
  segment.y = min(segment.y, ENVIRONMENT_REACH_M);
  float dt = max(segment.y - segment.x, 0.0f) / float(ENVIRONMENT_STEPS);
  vec3 sun = frame.sun_dir.xyz;
  float mu = dot(dir, sun);
  vec4 phases = octave_phases(mu);
  bool two_stream = frame.cloud_phase.w > 0.5f, diffusion = frame.cloud_phase.w > 1.5f;
  float light_scale = frame.cloud_shape.z * frame.cloud_light.y, g1 = frame.cloud_droplets.z;
  vec3 ambient_above = frame.ambient_at_clouds.rgb * frame.cloud_light.w;
  vec3 ambient_below = frame.ambient_below_clouds.rgb * frame.cloud_light.w;
  float below_share = texelFetch(ground_light, ivec2(0), 0).r;  // the ground's light under the clouds
  float albedo = frame.cloud_shape.w;
  vec3 light = vec3(0.0f);
  float transmittance = 1.0f;
  for (int i = 0; i < (dt > 0.0f ? ENVIRONMENT_STEPS : 0); ++i) {
    vec3 p = eye + dir * (segment.x + (float(i) + 0.5f) * dt);
    float sigma_t = cloud_density(p, true) * frame.cloud_shape.z;
    // As the view's clouds are lit (clouds.comp): the sun's light scattered once and many times,
    // the sky's light from above through the cloud towards the sun, the ground's from below.
    float depth = light_volume_covers(p) ? light_volume_lookup(p) : march_light(p, sun, 0.0f, light_ray_length(p, sun), 4);
    vec3 sunlit = cloud_light(diffusion, p, dir, sun, depth * light_scale, light_scale, mu,
                              two_stream, phases, frame.cloud_light.z, albedo, g1);
    vec3 source = frame.sun_at_clouds.rgb * (sunlit.x + sunlit.y) + ambient_above * sunlit.z +
                  ambient_below * ((1.0f - layer_fraction(p)) * below_share);
    float step_t = exp(-sigma_t * dt);
    light += transmittance * (1.0f - step_t) * albedo * source;
    transmittance *= step_t;
  }
  imageStore(environment_out, texel, vec4(light + transmittance * behind, 1.0f));
}

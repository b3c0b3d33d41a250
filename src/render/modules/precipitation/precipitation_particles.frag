#version 450
// The precipitation's particles near the camera (precipitation_particles_inc.glsl): a pixel's
// share of its quad's particle and its light, blended "over" into LAYER_PRECIPITATION (rgb the
// light premultiplied, per unit of the key light's illuminance; a the opacity), which the
// medium puts in front of everything behind (precipitation_medium.glsl). A particle's light is
// the medium's in-scattered light near the camera (it scatters what reaches it as the medium
// does, nearly without absorbing), under the clouds' shade, and the lightning's flashes',
// scattered evenly.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "render/modules/precipitation/precipitation_particles_inc.glsl"
#include "render/modules/lightning/lightning_layer.glsl"

layout(set = 1, binding = 4) uniform sampler3D precipitation_froxels;

layout(location = 0) flat in vec3 now_in;
layout(location = 0) out vec4 layer_out;

void main() {
  vec2 image = vec2(frame.size.xy);
  vec2 pixel = gl_FragCoord.xy - 0.5f;
  vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                        frame.camera_pos_m.w, frame.camera_forward.w, pixel.x, pixel.y, image.x,
                        image.y, vec2(frame.camera_right.w, frame.camera_up.w));
  vec2 seen = precipitation_particle_seen(now_in, dir, 2.0f * frame.camera_pos_m.w / image.y);
  if (seen.x <= 0.0f) discard;
  vec3 eye = frame.camera_pos_m.xyz;
  float opacity = seen.x * precipitation_share_at(eye).x;
  // The medium's light where it starts along this pixel's ray (the froxels' first stretch: its
  // light over its opacity), which the pass marched before this one.
  vec4 first = textureLod(precipitation_froxels,
                          vec3(gl_FragCoord.xy / image, 1.5f / float(PRECIPITATION_STEPS + 1)), 0.0f);
  vec3 light = first.rgb / max(1.0f - first.a, 1e-4f) * texelFetch(ground_light, ivec2(0), 0).r +
               LIGHTNING_RGB * lightning_illuminance_lx(eye, vec3(0.0f)) /
                   (4.0f * PI * max(frame.sun_illuminance.g, 1e-20f));
  layer_out = vec4(opacity * light, opacity);
}

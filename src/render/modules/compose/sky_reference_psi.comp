#version 450
// Reference sky, pass 1 of 2 (atmosphere.model = reference): Psi_ms evaluated in place (no
// table) at every step of every view ray of one tile of pixels, one invocation per step.
// One invocation per whole pixel would run about a million loop iterations, and lavapipe stops
// an invocation after 65535; one step takes about 23,000.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "dispatch_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/atmosphere_inc.glsl"
#include "common/atmosphere_lut_inc.glsl"
#include "frame_atmosphere_inc.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

void main() {
  ivec3 id = ivec3(gl_GlobalInvocationID);
  if (id.x >= REFERENCE_TILE || id.y >= REFERENCE_TILE || id.z >= REFERENCE_SAMPLES) return;
  ivec2 pixel = dispatch.values.xy + id.xy;
  if (pixel.x >= frame.size.x || pixel.y >= frame.size.y) return;
  vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                        frame.camera_pos_m.w, frame.camera_forward.w, float(pixel.x),
                        float(pixel.y), float(frame.size.x), float(frame.size.y),
                        vec2(frame.camera_right.w, frame.camera_up.w));
  Atmosphere a = frame_atmosphere();
  SkyRay ray = sky_ray(a, frame.camera_pos_m.xyz, dir);
  vec2 t = sky_step(max(ray.length_m, 0.0f), id.z, REFERENCE_SAMPLES);
  vec3 x = ray.origin + dir * (0.5f * (t.x + t.y));
  vec3 psi = ms_psi(a, transmittance_lut, true, x, frame.sun_dir.xyz, frame.sky_model.y);
  imageStore(reference_psi_out, id, vec4(psi, 1.0f));
}

#version 450
// Pass: cloud profile. The density field averaged per altitude over a square region of the
// ground around the camera (Renderer::cloud_profile: what a cloud type looks like in height;
// tests check each genus peaks where it should). Invocation (x, y) takes altitude bin y of the
// cloud shell (PROFILE_SIZE bins from its bottom to its top) and sums row x of a
// PROFILE_SIZE^2 grid of points over the region (half extent cloud_shape.y); the host
// averages the rows. It writes the sky dome's image (bind_march(true)): x the full field's
// sum, y the base shape's, z the number of points in cloud, w the number of points.
#extension GL_GOOGLE_include_directive : require

const int MARCH_MODE = 0;
const int PROFILE_SIZE = 64;
layout(local_size_x = 8, local_size_y = 8) in;

#include "cloud_field_inc.glsl"

void main() {
  ivec2 id = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(id, ivec2(PROFILE_SIZE)))) return;
  float r = mix(frame.radii_m.z, frame.radii_m.w, (float(id.y) + 0.5f) / float(PROFILE_SIZE));
  float half_m = frame.cloud_shape.y;
  float cell_m = 2.0f * half_m / float(PROFILE_SIZE);
  vec2 row_start = frame.camera_pos_m.xy + vec2(cell_m * 0.5f - half_m,
                                                cell_m * (float(id.x) + 0.5f) - half_m);
  vec4 sums = vec4(0.0f);
  for (int i = 0; i < PROFILE_SIZE; ++i) {
    vec2 xy = row_start + vec2(cell_m * float(i), 0.0f);
    vec2 field = cloud_density_pair(point_at_radius(xy, r));
    sums += vec4(field.y, field.x, field.y > 0.0f ? 1.0f : 0.0f, 1.0f);
  }
  imageStore(march_a_out, id, sums);
}

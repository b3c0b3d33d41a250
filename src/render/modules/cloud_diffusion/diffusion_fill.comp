#version 450
// Pass: cloud diffusion, the medium. For each cell of the grid (diffusion_grid_inc.glsl), the
// clouds' mean extinction over 2 x 2 x 2 points, and the sunlight the cell scatters: what of
// the sun's beam flows in through its faces and not out, exp(-tau) at each face's centre (a
// short march, then the light volume: sun_transmittance) times the beam's share across it.
// A cell is often optically thick, its centre's exp(-tau) a poor mean; the faces' balance
// conserves the beam, each face being counted with the same value by its two cells. The
// fluence starts at zero, or where the last build's left it when the grid has not moved
// (dispatch.values: x the first row, y the rows, z 1 to start the fluence at zero).
#extension GL_GOOGLE_include_directive : require

const int MARCH_MODE = 0;
layout(constant_id = 0) const bool WITH_VOXELS = true;
layout(constant_id = 1) const bool WITH_FLOW = true;
#define CLOUD_FIELD_VARIANTS
layout(local_size_x = 8, local_size_y = 8) in;

// The detail noise over the grid's own cell (set in main), whatever the view.
float grid_footprint_m = 0.0f;
#define NOISE_DETAIL_FOOTPRINT_M(pos) grid_footprint_m
#include "cloud_field_inc.glsl"
#include "dispatch_inc.glsl"
#include "render/modules/cloud_diffusion/diffusion_grid_inc.glsl"

layout(set = 1, binding = 2, rgba32f) uniform writeonly image3D cloud_diffusion_medium_out;
layout(set = 1, binding = 3, rgba32f) uniform image3D cloud_diffusion_phi_out;
layout(set = 1, binding = 9, r32f) uniform image3D cloud_diffusion_inflow;

// Below this optical depth (similarity-scaled) across its thinnest side a cell is clear air:
// left out of the solve, the light crossing it gathered along rays (diffusion_exchange.comp).
// Raised to 0.05 (haze and thin veils as clear air, streaming the light instead of diffusing
// it), a veil over a deck in the lab came within 5% of the path tracer (2.8 times too bright
// diffused), but the suite's decks went 20-30% too dark: their thin bases scatter the light
// many times, which the gather's few rounds miss.
const float THIN_TAU = 2.5e-4f;
// The largest diffusion coefficient, in cell sides (below).
const float THIN_CAP = 3.0f;

// A point of the planet frame at coordinates g (cells, continuous) of cascade k's grid.
vec3 diffusion_point(vec3 g, int k) {
  vec2 offset = (g.xy / float(DIFFUSION_XY) * 2.0f - 1.0f) * diffusion.build[k].z;
  vec2 xy = diffusion.build[k].xy + offset + frame.wind_offset_m.xy;
  float h = (g.z - float(k * DIFFUSION_Z)) / float(DIFFUSION_Z);
  return point_at_radius(xy, mix(frame.radii_m.z, frame.radii_m.w, h));
}

// The sun's beam's transmittance to pos: a march over the first of the light volume's voxels
// (or the whole way where the volume does not reach), the volume's depth beyond.
float sun_transmittance(vec3 pos, vec3 sun, float scale) {
  float length_m = light_ray_length(pos, sun);
  float depth;
  if (light_volume_covers(pos)) {
    float near_m = min(light_volume_voxel_at(pos), length_m);
    depth = march_light(pos, sun, 0.0f, near_m, 6);
    if (near_m < length_m) depth += light_volume_lookup(pos + sun * near_m);
  } else {
    depth = march_light(pos, sun, 0.0f, length_m, 16);
  }
  return exp(-depth * frame.cloud_shape.z * frame.cloud_light.y * scale);
}

void main() {
  ivec3 c = diffusion_cell(gl_GlobalInvocationID.xy + uvec2(0, dispatch.values.x));
  int cascade = diffusion_cascade(c);
  if (!diffusion_in_grid(c, cascade) || int(gl_GlobalInvocationID.y) >= dispatch.values.y) return;
  grid_footprint_m = diffusion_cell_m(cascade).x;
  float density = 0.0f;
  for (int k = 0; k < 8; ++k) {
    vec3 sub = vec3(k & 1, (k >> 1) & 1, k >> 2) * 0.5f + 0.25f;
    density += cloud_density(diffusion_point(vec3(c) + sub, cascade), true);
  }
  float sigma_t = density / 8.0f * frame.cloud_shape.z * frame.cloud_light.y;
  vec3 h = diffusion_cell_m(cascade);
  bool zero = dispatch.values.z != 0;
  // The gathers' light starts at zero in diffusion_boundary.comp.
  if (zero) imageStore(cloud_diffusion_inflow, c, vec4(0.0f));
  float albedo = frame.cloud_shape.w;
  float g = cloud_transport_g();
  vec3 sun = frame.sun_dir.xyz;
  // Similarity (van de Hulst): the forward share g of scattering as no scattering.
  float reduced = 1.0f - albedo * g;
  // The beam's net inflow per unit volume: over each axis, (T at the face it enters by - T at
  // the face it leaves by) x its component / the side.
  // Bounded by what the cell's cloud can scatter of the brightest face's beam (the faces'
  // transmittances are point values: clear air would otherwise catch a difference).
  float inflow = 0.0f, brightest = 0.0f;
  for (int axis = 0; axis < 3 && sigma_t > 0.0f; ++axis) {
    vec3 lo = vec3(c) + 0.5f, hi = lo;
    lo[axis] -= 0.5f;
    hi[axis] += 0.5f;
    float t_lo = sun_transmittance(diffusion_point(lo, cascade), sun, reduced);
    float t_hi = sun_transmittance(diffusion_point(hi, cascade), sun, reduced);
    inflow += (t_lo - t_hi) * -sun[axis] / h[axis];
    brightest = max(brightest, max(t_lo, t_hi));
  }
  float q = albedo * (1.0f - g) * min(max(inflow, 0.0f) / reduced, sigma_t * brightest);
  // D is at most THIN_CAP cell sides: where a cell is optically thin the light crosses it in a
  // flight or a few, and diffusion's D = 1 / (3 sigma_tr), unbounded as sigma_tr goes to 0,
  // would pipe it through thin cloud to open sky at once (an eroded deck 3 times too dark
  // inside; capped at one side, 1.9 times too bright). Clear air is left out of the solve, its
  // faces open, and the light it brings back is gathered along rays (diffusion_exchange.comp).
  // A deck's open base is freed of the cap once the medium is filled (diffusion_column.comp).
  float side_m = min(h.x, h.z);
  float sigma_tr = sigma_t * reduced;
  float d = sigma_tr * side_m < THIN_TAU ? 0.0f : min(1.0f / (3.0f * sigma_tr), THIN_CAP * side_m);
  float sigma_a = (1.0f - albedo) * sigma_t;
  imageStore(cloud_diffusion_medium_out, c, vec4(d, sigma_a, q, sigma_tr));
  // What the solve reads of a cell, in one load (diffusion_grid_inc.glsl).
  float phi = zero ? 0.0f : imageLoad(cloud_diffusion_phi_out, c).x;
  float brought = zero ? 0.0f : imageLoad(cloud_diffusion_inflow, c).r;
  imageStore(cloud_diffusion_phi_out, c, vec4(phi, d, sigma_a, q + brought));
}

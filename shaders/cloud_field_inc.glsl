// The cloud density field and the light reaching a point of it, shared by the passes that
// sample clouds (clouds.comp, light_volume.comp). Reads the noise and weather textures, so it
// is GLSL only (unlike common/*_inc.glsl). The includer defines the int MARCH_MODE (0 default,
// 1 the seed's baseline) before including this file.
#ifndef NEPHELE_CLOUD_FIELD_INC
#define NEPHELE_CLOUD_FIELD_INC

#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/clouds_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/droplets_inc.glsl"
#include "common/light_volume_inc.glsl"
#ifndef CLOUD_FIELD_VARIANTS
// An includer that compiles variants declares these specialization constants (and defines
// CLOUD_FIELD_VARIANTS) before including this file: false leaves the voxel clouds, or the flow
// map's swirls, out.
const bool WITH_VOXELS = true;
const bool WITH_FLOW = true;
#endif
#include "voxel_field_inc.glsl"
#include "noise_density_inc.glsl"


// The clouds' phase function (clouds.optics): the droplets' fitted Mie phase, or the seed's
// two Henyey-Greenstein lobes; with every eccentricity scaled by c (1: the phase itself; the
// octaves' c^i).
float cloud_phase_function(float mu, float c) {
  vec4 mie = frame.cloud_mie;
  return frame.cloud_droplets.y > 0.5f
             ? mie_phase(vec4(mie.x * c, mie.y * c, mie.z, mie.w), mu)
             : dual_lobe_hg(frame.cloud_phase.x * c, frame.cloud_phase.y * c, frame.cloud_phase.z, mu);
}

// The asymmetry the clouds' diffuse light is carried with (frame.cloud_droplets.w): the phase
// function's mean cosine (the droplets' delta-scaled one: 0.76 at 9 um, for the optical depths
// of their sigma_t without the diffraction peak), or with the seed's lighting the seed's fixed
// one.
float cloud_transport_g() { return frame.cloud_droplets.w; }

// Multiple-scattering approximation (Wrenninge et al. 2013, "Oz: the great and volumetric"):
// octave i scatters with contribution a^i, extinction b^i and eccentricity c^i. b < 1 lets
// light reach deep into the cloud as repeated forward scattering does, so thick clouds keep
// their brightness instead of turning grey. a = 0.6, b = 0.4, c = 0.5, four octaves.
// The octaves' phase functions depend only on the view ray: evaluated once per ray.
vec4 octave_phases(float mu) {
  vec4 phases;
  float c = 1.0f;
  for (int i = 0; i < 4; ++i) {
    phases[i] = cloud_phase_function(mu, c);
    c *= 0.5f;
  }
  return phases;
}

float multiple_scattering(float tau_light, float mu, float powder, vec4 phases) {
  float energy = 0.0f;
  float a = 1.0f, b = 1.0f;
  for (int i = 0; i < 4; ++i) {
    energy += a * cloud_beer_powder(b * tau_light, mu, powder) * phases[i];
    a *= 0.6f;
    b *= 0.4f;
  }
  return energy;
}

const vec3 SEED_EXTINCTION_MULT = vec3(0.8f, 0.8f, 1.0f);  // listing B.3

// The point at radius r (m) above horizontal position xy (planet frame).
vec3 point_at_radius(vec2 xy, float r) { return vec3(xy, sqrt(max(r * r - dot(xy, xy), 0.0f))); }

// The part of the view ray inside the cloud shell: (t_enter, t_exit), empty if exit <= enter.
// `ground` is ray_sphere(eye, dir, planet radius).
vec2 shell_segment(vec3 eye, vec3 dir, vec2 ground) {
  float r = length(eye);
  vec2 inner = ray_sphere(eye, dir, frame.radii_m.z);
  vec2 outer = ray_sphere(eye, dir, frame.radii_m.w);
  if (outer.y <= 0.0f) return vec2(0.0f);  // the shell is behind
  float t_enter;
  float t_exit;
  if (r < frame.radii_m.z) {  // below the layer: from leaving the inner sphere to the outer
    if (ground.x > 0.0f) return vec2(0.0f);  // looking at the ground
    t_enter = inner.y;
    t_exit = outer.y;
  } else if (r <= frame.radii_m.w) {  // inside the layer
    t_enter = 0.0f;
    t_exit = inner.x > 0.0f ? inner.x : outer.y;
  } else {  // above: from entering the outer sphere to the inner sphere or out again
    t_enter = max(outer.x, 0.0f);
    t_exit = inner.x > 0.0f ? inner.x : outer.y;
  }
  return vec2(t_enter, t_exit);
}

// Height fraction in the whole cloud shell (all layers): the light volume's vertical axis.
float altitude_fraction(vec3 pos) {
  return cloud_height_fraction(length(pos), frame.radii_m.z, frame.radii_m.w);
}

// Height fraction in the layer at pos: 0 at its bottom, 1 at its top.
float layer_fraction(vec3 pos) {
  float radius_m = length(pos);
  vec4 radii = cloud_layer_at(radius_m).radii_m;
  return cloud_height_fraction(radius_m, radii.x, radii.y);
}

// The thickness of the layer at pos (m).
float layer_thickness_m(vec3 pos) {
  vec4 radii = cloud_layer_at(length(pos)).radii_m;
  return radii.y - radii.x;
}

// Every cloud at pos: the noise clouds, faded out near the voxel clouds' regions, and the voxel
// clouds. Returns (x) the base shape (voxel clouds whole) and (y) the full field; `voxels` is
// what the voxel clouds hold there (their distance, region, nearest cloud). Where a whole
// batch of lanes lies in voxel regions the noise is not read at all.
vec2 cloud_field(vec3 pos, out VoxelSample voxels) {
  if (!WITH_VOXELS) {  // what the voxel field holds where there are no voxel clouds
    voxels = VoxelSample(0.0f, 1e9f, 1e9f, 1.0f, 0);
    return noise_density_pair(pos);
  }
  voxels = voxel_field(pos);
  float fade = voxel_noise_fade(voxels.region_m);
  vec2 noise = vec2(0.0f);
  noise_shape_margin = -1.0f;
  if (fade > 0.0f) noise = noise_density_pair(pos) * fade;
  return noise + voxels.density;
}

// One call, not a choice between cloud_field and noise_density_pair: a CPU device runs both
// sides of a branch, even a uniform one, and would read the noise twice.
vec2 cloud_density_pair(vec3 pos) {
  VoxelSample voxels;
  return cloud_field(pos, voxels);
}

float cloud_density(vec3 pos, bool with_detail) {
  vec2 pair = cloud_density_pair(pos);
  return with_detail ? pair.y : pair.x;
}

// Optical depth (density field x metres) along the sun from pos over [t0, t1], n midpoint
// steps growing linearly (short near pos, where the light changes fastest).
float march_light(vec3 pos, vec3 sun, float t0, float t1, int n) {
  float unit = (t1 - t0) / float(n * (n + 1) / 2);
  float t = t0;
  float depth = 0.0f;
  for (int i = 1; i <= n; ++i) {
    float s = unit * float(i);
    float mid = t + 0.5f * s;
    depth += cloud_density(pos + sun * mid, true) * s;
    t += s;
  }
  return depth;
}

// The clouds' diffuse transmittance (cloud_diffuse_transmittance) for an optical depth of the
// density field (density x m) along the light.
float light_transmittance(float depth) {
  return cloud_diffuse_transmittance(depth * frame.cloud_shape.z * frame.cloud_light.y,
                                     cloud_transport_g());
}

// How far along the sun the light is traced: to the top of the layer, at most two layer
// thicknesses (for a low sun, so a sample near the base still sees the dense tops above it).
float light_ray_length(vec3 pos, vec3 sun) {
  float thickness = frame.radii_m.w - frame.radii_m.z;
  return min(ray_sphere(pos, sun, frame.radii_m.w).y, 2.0f * thickness);
}

// Whether pos is inside the light volume's horizontal extent (and the volume is in use).
bool light_volume_covers(vec3 pos) {
  vec2 offset = pos.xy - frame.wind_offset_m.xy - frame.light_volume.xy;
  return frame.light_volume.w > 0.5f && length(offset) < frame.light_volume.z;
}

// The size of the light volume's voxels at pos (the largest of their three sides).
float light_volume_voxel_at(vec3 pos) {
  vec2 offset = pos.xy - frame.wind_offset_m.xy - frame.light_volume.xy;
  return max(light_volume_voxel_m(length(offset), frame.light_volume.z, LIGHT_VOLUME_XY),
             (frame.radii_m.w - frame.radii_m.z) / float(LIGHT_VOLUME_Z));
}

// The light volume's optical depth at pos (trilinear).
float light_volume_lookup(vec3 pos) {
  vec2 offset = pos.xy - frame.wind_offset_m.xy - frame.light_volume.xy;
  vec3 coord = vec3(light_volume_coord(offset, frame.light_volume.z), altitude_fraction(pos));
  return textureLod(light_volume, coord, 0.0f).r;
}

// Optical depth (density field x m) of the clouds behind pos as seen from the sun: along the
// sun's chord onwards, away from the sun, to the cloud shell's bottom (at most twice the
// shell's thickness), for the two-stream light (cloud_two_stream_fluxes). Where the light
// volume holds both ends, the difference of its two depths towards the sun (the chord is the
// same line); elsewhere a march of the light march's steps (at least 12), unless the includer
// defines DEPTH_BEHIND_MAY_MARCH false (a variant that runs only with a light volume: then its
// edge's depths). On lavapipe, which runs both sides of a branch, the march costs the default
// clouds pass a fifth of its time (the diffusion light's, beyond its grids) even where the
// volume holds every sample.
#ifndef DEPTH_BEHIND_MAY_MARCH
#define DEPTH_BEHIND_MAY_MARCH true
#endif
float depth_behind(vec3 pos, vec3 sun) {
  vec2 hit = ray_sphere(pos, -sun, frame.radii_m.z);
  float thickness = frame.radii_m.w - frame.radii_m.z;
  float length_m = hit.x > 0.0f ? min(hit.x, 2.0f * thickness) : 2.0f * thickness;
  vec3 far_end = pos - sun * length_m;
  if (!(DEPTH_BEHIND_MAY_MARCH) || (light_volume_covers(pos) && light_volume_covers(far_end)))
    return max(light_volume_lookup(far_end) - light_volume_lookup(pos), 0.0f);
  return march_light(pos, -sun, 0.0f, length_m, max(frame.steps.y, 12));
}

// The sunlight a cloud sample scatters towards a viewer, per unit of the sun's irradiance and
// of albedo, as the fast mode lights it (clouds.comp and the ground's cloud light,
// ground_light.comp): x the light that reaches it from the sun's direction (single scattering
// with the two-stream light, else the seed's octaves and powder), y the diffuse light the
// cloud between it and the sun passes on to it, per unit of a horizontal deck's flux
// (mu_sun), z the cloud's diffuse transmittance towards the sun (which the sky's light shares).
// pos: the sample; tau_light: the optical depth towards the sun, light_scale the optical depth
// per unit of the density field x m along the light (the two-stream light marches or looks up
// the depth behind the sample along the sun's chord, depth_behind); mu: the cosine between the
// viewer's ray and the sun; g1: the phase function's mean cosine.
vec3 cloud_sun_light(vec3 pos, vec3 sun, float tau_light, float light_scale, float mu,
                     bool two_stream, vec4 phases, float powder, float albedo, float g1) {
  float mu_sun = max(dot(sun, normalize(pos)), 0.0f);
  if (two_stream) {
    float tau_behind = depth_behind(pos, sun) * light_scale;
    // Single scattering and the two-stream field along the sun's chord (clouds_inc.glsl):
    // the light going on and the light scattered back towards the sun, which lights the
    // sunlit faces.
    vec2 fluxes = cloud_two_stream_fluxes(tau_light, tau_behind, albedo, cloud_transport_g());
    return vec3(exp(-tau_light) * phases[0],
                cloud_two_stream_radiance(fluxes, tau_light, mu, g1) * mu_sun, fluxes.x);
  }
  // The light thick cloud passes on by scattering it forward: a diffuse flux (radiance = flux
  // / pi, the flux through a horizontal deck mu_sun times the sun's).
  float t_d = cloud_diffuse_transmittance(tau_light, cloud_transport_g());
  return vec3(multiple_scattering(tau_light, mu, powder, phases),
              (t_d - exp(-tau_light)) * mu_sun / PI, t_d);
}

// Optical depth (density field x m) of the clouds towards the sun from `base`, a point at the
// bottom of the cloud shell: from the light volume if `from_volume`, else `samples` samples of
// the full density over the light ray (coarser sampling turns thin wisps into deep shadow). A
// loop with a per-lane trip count: a CPU device (lavapipe) ends it once no lane has iterations
// left, but runs its body once even when no lane takes a trip.
float depth_towards_sun(vec3 base, vec3 sun, bool from_volume, int samples) {
  float depth = from_volume ? light_volume_lookup(base) : 0.0f;
  int n = from_volume ? 0 : samples;
  float ds = light_ray_length(base, sun) / float(samples);
  for (int i = 0; i < n; ++i) depth += cloud_density(base + sun * ((float(i) + 0.5f) * ds), true) * ds;
  return depth;
}

// Cloud shadow at p, a point of the ground or the terrain `distance_m` from the eye, below the
// cloud shell or inside it (a peak in the layer): the share of the sunlight that reaches it
// through the clouds (direct and scattered forward). From the light volume where its voxels are
// small against the distance (at most 2% of it: a few pixels), else `samples` samples of the
// density towards the sun (seed 002's mesh shadowing): nearer, the volume's coarse voxels would
// draw blocks. 1 above the shell.
float cloud_shadow_at(vec3 p, vec3 sun, float distance_m, int samples) {
  float r = length(p);
  if (r >= frame.radii_m.w) return 1.0f;
  vec3 base = p;  // where the sunlight leaves the cloud shell, or p inside it
  if (r < frame.radii_m.z) {
    vec2 inner = ray_sphere(p, sun, frame.radii_m.z);
    vec2 outer = ray_sphere(p, sun, frame.radii_m.w);
    if (inner.y <= 0.0f || outer.y <= inner.y) return 1.0f;
    base = p + sun * inner.y;
  }
  bool covered = MARCH_MODE == 0 && light_volume_covers(base) &&
                 light_volume_voxel_at(base) < 0.02f * distance_m;
  return light_transmittance(depth_towards_sun(base, sun, covered, samples));
}

// Share of the clear sky's light that the ground and the air below the clouds receive around
// pos: the clouds' diffuse transmittance towards the sun, averaged over four points of the
// shell's bottom `reach_m` from pos's foot (four samples each where the light volume does not
// reach). A cloud sample looks as far as it is high (the middle of its cosine-weighted view of
// the ground): under a storm's anvil or a deck the ground is in shadow and the bases go dark,
// while a fair-weather cumulus still sees sunlit ground around its own shadow.
float below_light_share(vec3 pos, float reach_m) {
  vec3 foot = pos * (frame.radii_m.z / length(pos));
  float share = 0.0f;
  for (int k = 0; k < 4; ++k) {
    vec2 axis = k < 2 ? vec2(k == 0 ? 1.0f : -1.0f, 0.0f) : vec2(0.0f, k == 2 ? 1.0f : -1.0f);
    vec3 p = foot + vec3(axis * reach_m, 0.0f);
    float depth = depth_towards_sun(p, frame.sun_dir.xyz, light_volume_covers(p), 4);
    share += light_transmittance(depth);
  }
  return 0.25f * share;
}

// Optical depth towards the sun from pos as the seed marches it (listing B.2): three steps of
// 1% of the layer thickness, the fourth six times longer.
float seed_light_optical_depth(vec3 pos, vec3 sun) {
  float step_m = layer_thickness_m(pos) * 0.01f;
  float depth = 0.0f;
  for (int i = 0; i < 4; ++i) {
    float s = i == 3 ? step_m * 6.0f : step_m;
    pos += sun * s;
    depth += cloud_density(pos, true) * s;
  }
  return depth;
}

#endif

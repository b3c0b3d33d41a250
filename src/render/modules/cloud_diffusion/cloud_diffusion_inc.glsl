// The cloud diffusion's field as the clouds' march reads it (clouds.comp): the multiple-
// scattered light of the clouds, solved on a regular grid in cloud space (CloudDiffusionModule,
// diffusion_solve.comp) as a fluence phi and a flux vector E per unit of the sun's irradiance
// (the light scattered at least once; single scattering is the march's own). The radiance of a
// P1 field, (phi + 3 E . w) / 4 pi, scattered by a phase function of mean cosine g1 towards
// the viewer. Needs cloud_field_inc.glsl (frame, altitude_fraction).
#ifndef NEPHELE_CLOUD_DIFFUSION_INC
#define NEPHELE_CLOUD_DIFFUSION_INC

#include "render/modules/cloud_diffusion/cloud_diffusion_gpu_inc.glsl"

layout(std140, set = 1, binding = 0) uniform CloudDiffusionBlock { CloudDiffusionGpu diffusion; };
layout(set = 1, binding = 1) uniform sampler3D cloud_diffusion_field;

// The coordinates ([0, 1]^3) in cascade k's grid of a point of the planet frame.
vec3 diffusion_coord(vec3 pos, int k) {
  vec2 offset = pos.xy - frame.wind_offset_m.xy - diffusion.grid[k].xy;
  return vec3(0.5f + 0.5f * offset / diffusion.grid[k].z, altitude_fraction(pos));
}

// The multiple-scattered light a cloud sample at pos scatters towards a viewer looking along
// `dir`, per unit of the sun's irradiance and of albedo (as cloud_sun_light's y), from the
// finest cascade that covers pos: in use, and two cells or more inside its grid's sides (the
// cells at its sides lose their light through them). False where none does.
bool diffusion_light(vec3 pos, vec3 dir, float g1, out float radiance) {
  radiance = 0.0f;
  float margin = 2.0f / float(DIFFUSION_XY);
  // The cascade first, then one lookup (lavapipe would make a loop's lookup for every
  // cascade).
  int found = -1;
  vec3 c = vec3(0.0f);
  for (int k = DIFFUSION_CASCADES - 1; k >= 0; --k) {
    vec3 ck = diffusion_coord(pos, k);
    bool covers = diffusion.grid[k].w > 0.5f && all(greaterThanEqual(ck.xy, vec2(margin))) &&
                  all(lessThanEqual(ck.xy, vec2(1.0f - margin)));
    found = covers ? k : found;
    c = covers ? ck : c;
  }
  if (found < 0) return false;
  // Within the cascade's own slices of the stacked volume (no blend with the next one's).
  float z = float(found * DIFFUSION_Z) + clamp(c.z * float(DIFFUSION_Z), 0.5f, float(DIFFUSION_Z) - 0.5f);
  vec4 f = textureLod(cloud_diffusion_field,
                      vec3(c.xy, z / float(DIFFUSION_Z * DIFFUSION_CASCADES)), 0.0f);
  // The light propagating towards the viewer travels along -dir.
  radiance = max(f.x - 3.0f * g1 * dot(f.yzw, dir), 0.0f) / (4.0f * PI);
  return true;
}

// The sunlight a sample at optical depth tau from the sun scatters towards a viewer (mu: the
// cosine between the view ray and the sun), per unit of the sun's irradiance, from the light
// that has scattered forward k = 0, 1, 2 ... times on its way in (Poisson, e^-tau (w tau)^k /
// k!). Light scattered k times by a Henyey-Greenstein lobe of asymmetry g spreads about the
// sun's direction as HG(g^k) (the convolution of HG lobes multiplies their Legendre moments),
// and scatters towards the viewer as HG(g^(k+1)). The similarity-scaled diffusion already
// carries the share 1 - g^k of order k, isotropic; this is the rest: order 0 by the phase
// function itself (phase0), order k by HG(g^(k+1)) - (1 - g^k) / 4 pi. Their sum over k of the
// weight g^k is the scaled beam exp(-(1 - w g) tau), which the diffusion light took with the
// full phase function before stop 60: deep in a cloud that counted light scattered ten times
// as if it were still a beam, and near a face it missed the forward orders' spread (the lab's
// thin cumulus lit from in front 13.9% off the path tracer, now 3.9%).
float diffusion_forward_orders(float tau, float albedo, float g, float mu, float phase0) {
  float p_k = exp(-tau);
  float light = p_k * phase0;
  float g_k = 1.0f;
  for (int k = 1; k <= 16; ++k) {
    p_k *= albedo * tau / float(k);
    g_k *= g;
    float gg = g_k * g;
    float x = max(1.0f + gg * gg - 2.0f * gg * mu, 1e-6f);
    light += p_k * ((1.0f - gg * gg) / (x * sqrt(x)) - (1.0f - g_k)) / (4.0f * PI);
    if (float(k) > tau && p_k < 1e-6f) break;  // past the orders' peak, the rest negligible
  }
  return max(light, 0.0f);
}

// The sunlight a cloud sample scatters towards a viewer, as cloud_sun_light's (x, y, z): with
// the diffusion light (`diffusion`) where a cascade covers pos, the forward orders of the
// sun's beam (diffusion_forward_orders), the field's multiple-scattered light and the diffuse
// transmittance; elsewhere cloud_sun_light's. For the clouds' march and the clouds' light on
// the ground.
vec3 cloud_light(bool diffusion, vec3 pos, vec3 dir, vec3 sun, float tau_light, float light_scale,
                 float mu, bool two_stream, vec4 phases, float powder, float albedo, float g1) {
  float diffused;
  if (diffusion && diffusion_light(pos, dir, g1, diffused)) {
    float g = cloud_transport_g();
    return vec3(diffusion_forward_orders(tau_light, albedo, g, mu, phases[0]), diffused,
                cloud_diffuse_transmittance(tau_light, g));
  }
  return cloud_sun_light(pos, sun, tau_light, light_scale, mu, two_stream, phases, powder, albedo,
                         g1);
}

#endif

// Cloud density model of seed 000 (section 2.2.2, listing B.1) in physical units, split into
// the pure parts (here, compiled as C++ for tests) and the texture lookups (clouds.comp).
#ifndef NEPHELE_CLOUDS_INC
#define NEPHELE_CLOUDS_INC

// Height fraction in the layer: 0 at the cloud bottom sphere, 1 at the top sphere.
float cloud_height_fraction(float radius_m, float bottom_radius_m, float top_radius_m) {
  return (radius_m - bottom_radius_m) / (top_radius_m - bottom_radius_m);
}

// Shape height gradient SA (listing B.1): rounds the bottom over the lowest 7% of the layer and
// tapers the top from 20% of the weather map's maximum height `max_height` (B channel) to it.
float cloud_shape_gradient(float h, float max_height) {
  float bottom = saturate(remap(h, 0.0f, 0.07f, 0.0f, 1.0f));
  float top = saturate(remap(h, max_height * 0.2f, max(max_height, 1e-3f), 1.0f, 0.0f));
  return bottom * top;
}

// Density height gradient DA without the weather and density factors (listing B.1): density
// grows with height (h times soft ramps at both ends), so bases are thin and tops dense.
float cloud_density_gradient(float h) {
  float bottom = h * saturate(remap(h, 0.0f, 0.15f, 0.0f, 1.0f));
  float top = h * saturate(remap(h, 0.9f, 1.0f, 1.0f, 0.0f));
  return bottom * top;
}

// Cloud types (seed 002, "Cloud Modeling 改进": height-density gradients blended by the weather
// map's cloud-type channel). A type t in [0, 1] runs through five genera, each a trapezoid over
// the layer's height fraction h (rising from r0 to r1, falling from f0 to f1):
//   t = 0     stratus         flat sheet at the base       0.00-0.05 ... 0.12-0.22
//   t = 0.25  stratocumulus   low lumpy layer              0.00-0.08 ... 0.28-0.42
//   t = 0.5   altocumulus     band high in the layer       0.30-0.42 ... 0.58-0.72
//   t = 0.75  cumulus         flat base, rounded tops      0.00-0.07 ... 0.25-0.80
//   t = 1     cumulonimbus    the whole layer, anvil top   0.00-0.05 ... 0.92-1.00
// Neighbouring genera blend linearly, so precipitation (which pushes t towards 1) grows
// cumulus into cumulonimbus.
const int CLOUD_GENERA = 5;

float cloud_trapezoid(float h, vec4 r) {
  return saturate(remap(h, r.x, r.y, 0.0f, 1.0f)) * saturate(remap(h, r.z, r.w, 1.0f, 0.0f));
}

vec4 cloud_genus_profile(int genus) {
  if (genus == 0) return vec4(0.0f, 0.05f, 0.12f, 0.22f);
  if (genus == 1) return vec4(0.0f, 0.08f, 0.28f, 0.42f);
  if (genus == 2) return vec4(0.30f, 0.42f, 0.58f, 0.72f);
  if (genus == 3) return vec4(0.0f, 0.07f, 0.25f, 0.80f);
  return vec4(0.0f, 0.05f, 0.92f, 1.0f);
}

// The type's height gradient at h: 1 inside its genus' core, 0 outside it.
float cloud_type_gradient(float h, float type) {
  float x = saturate(type) * float(CLOUD_GENERA - 1);
  int lo = min(int(x), CLOUD_GENERA - 2);
  float w = x - float(lo);
  return mix(cloud_trapezoid(h, cloud_genus_profile(lo)),
             cloud_trapezoid(h, cloud_genus_profile(lo + 1)), w);
}

// The highest height fraction the type reaches (its profile's f1, blended): the seed 000
// baseline's "maximum cloud height".
float cloud_type_top(float type) {
  float x = saturate(type) * float(CLOUD_GENERA - 1);
  int lo = min(int(x), CLOUD_GENERA - 2);
  return mix(cloud_genus_profile(lo).w, cloud_genus_profile(lo + 1).w, x - float(lo));
}

// How much of cumulonimbus the type holds: 0 up to cumulus (t = 0.75), 1 at t = 1.
float cloud_cumulonimbus_share(float type) { return saturate(4.0f * type - 3.0f); }

// Precipitation (seed 002, 积雨云渐变): the weather map's precipitation p in [0, 1] turns any
// sky into cumulonimbus at 70% coverage or more, rising to 95% where p is 1 (a storm cell's
// core: a solid tower). Returns (coverage, type).
vec2 cloud_precipitate(float coverage, float type, float p) {
  return vec2(mix(coverage, max(coverage, 0.7f + 0.25f * p), p), mix(type, 1.0f, p));
}

// A storm cell from the weather map's storm channel g and the layer's precipitation p (seed
// 002, 积雨云渐变). Returns (x) how far the towers' core turns into cumulonimbus: from g = 0.1,
// fully from 0.5; (y) the cell's extent, where its anvil spreads: wider than the core, fully
// from g = 1/3.
vec2 cloud_storm_cell(float g, float p) {
  return vec2(saturate(p * (2.5f * g - 0.25f)), saturate(p * 3.0f * g));
}

// The anvil (seed 002, "shape bias": coverage rising with height): over a storm cell's extent
// `cell` in [0, 1], a sheet of coverage 0.85 spreading at the top of the layer, from 62% of its
// height, fullest between 75% and 90%. Nothing below, and nothing where there is no cell. The
// wind's lean (cloud_wind_offset) streams it downwind.
float cloud_anvil_coverage(float h, float cell) {
  return 0.85f * cell * cloud_trapezoid(h, vec4(0.62f, 0.75f, 0.9f, 1.0f));
}

// Density height gradient of the default model over the height fraction h within the cloud
// type's extent: bases at 40% of the tops' density (the seed's h^2 left the lower half of a
// cumulonimbus a transparent veil seen from below), rising linearly, faded over the last 10%.
float cloud_type_density_gradient(float h) {
  return mix(0.4f, 1.0f, h) * saturate(remap(h, 0.9f, 1.0f, 1.0f, 0.0f));
}

// Local coverage in [0, 1] from the weather map's coverage channel (R) and the layer's coverage
// c in [0, 1]: c = 0.5 takes the map as it is, c -> 0 removes all cloud, c -> 1 covers
// everything.
float cloud_local_coverage(float weather_coverage, float coverage) {
  return saturate(weather_coverage + 2.0f * coverage - 1.0f);
}

// Shape from noise and coverage (listing B.1): noise below 1 - coverage is cut away, the rest
// is rescaled to [0, 1].
float cloud_apply_coverage(float shape_noise, float local_coverage) {
  if (local_coverage <= 0.0f) return 0.0f;
  return saturate(remap(shape_noise, 1.0f - local_coverage, 1.0f, 0.0f, 1.0f));
}

// Erosion by detail noise (Schneider 2015): detail fBm cuts wisps into the edges; inverted
// near the base for billows above and wisps below.
float cloud_erode(float base, float detail_fbm, float h, float erosion) {
  float detail = mix(detail_fbm, 1.0f - detail_fbm, saturate(h * 5.0f));
  return saturate(remap(base, detail * erosion, 1.0f, 0.0f, 1.0f));
}

// The shear's tops run ahead of their bases only while a cloud lives (about an hour): the time
// the shear has acted, t_s tanh(t / t_s), is t for the first minutes and never more than t_s.
// In the seed it is t itself, so over hours each height drifts over unrelated weather (after a
// day at 1 m/s, tops 90 km from their bases) and the layer turns into a uniform sheet.
const float SHEAR_LIFETIME_S = 3600.0f;
float shear_time_s(float time_s) { return SHEAR_LIFETIME_S * tanh(time_s / SHEAR_LIFETIME_S); }

// Wind displacement (seed 002, 全局流动效果) of a sample at height fraction h in [0, 1] of its
// layer: the seed's (wind + h shear) (time + h skew), with the shear acting over
// shear_time = shear_time_s(time). The wind grows with height (shear: its growth up to the
// top, m/s), and the sample sits where the wind had carried it h x skew seconds longer, so tops
// lean downwind. drift_m = wind x time and shear_time are computed on the host, once a frame.
vec2 cloud_wind_offset(vec2 drift_m, vec2 wind_mps, vec2 shear_mps, float shear_time, float skew_s,
                       float h) {
  return drift_m + h * (wind_mps * skew_s + shear_mps * (shear_time + h * skew_s));
}

// The flow map's two phases (seed 002, 局部流动效果): phase k in {0, 1} of a cycle at
// `phase` = fract(time / cycle). Returns (weight, progress): the noise is displaced by the flow
// x progress x cycle, so it stretches at most speed x cycle before it restarts; the two phases
// are half a cycle apart and their weights (1 - |1 - 2 progress|) sum to 1 and vanish where
// each restarts, hiding the jump.
vec2 cloud_flow_phase(float phase, int k) {
  float progress = fract(phase + 0.5f * float(k));
  return vec2(1.0f - abs(1.0f - 2.0f * progress), progress);
}

// Cirrus genera (seed 002): the weights of cirrus, cirrostratus and cirrocumulus for a cirrus
// type t in [0, 1] (0, 0.5 and 1 pure), neighbours blended linearly; they sum to 1.
vec3 cirrus_genus_weights(float type) {
  float t = saturate(type);
  return vec3(saturate(1.0f - 2.0f * t), 1.0f - abs(2.0f * t - 1.0f), saturate(2.0f * t - 1.0f));
}

// Transmittance of a thin sheet of vertical optical depth `tau` crossed at `cos_zenith` (the
// cosine between the ray and the local vertical): the slant path is 1 / |cos_zenith| longer,
// capped at 50x where the ray grazes the sheet.
float cirrus_transmittance(float tau, float cos_zenith) {
  return exp(-tau / max(abs(cos_zenith), 0.02f));
}

// The asymmetry parameter of cloud droplets' Mie scattering at visible wavelengths.
const float CLOUD_DROPLET_G = 0.85f;

// Share of the light falling on a cloud that it transmits, direct and diffuse, at optical depth
// tau: the two-stream result for a conservatively scattering slab, 1 / (1 + 3/4 (1 - g) tau)
// (Bohren 1987). Thick cloud passes on far more than the direct beam's exp(-tau): forward
// scattering carries light through (the grey light under an overcast).
float cloud_diffuse_transmittance(float tau, float g) {
  return 1.0f / (1.0f + 0.75f * (1.0f - g) * max(tau, 0.0f));
}

// With the seed's droplets' asymmetry, CLOUD_DROPLET_G.
float cloud_diffuse_transmittance(float tau) { return cloud_diffuse_transmittance(tau, CLOUD_DROPLET_G); }

// The direct beam's share exp(-tau) through a cloud whose diffuse transmittance
// (cloud_diffuse_transmittance with asymmetry g) is t_d: tau = (1 / t_d - 1) / (3/4 (1 - g)).
float cloud_direct_transmittance(float t_d, float g) {
  return exp(-(1.0f / max(t_d, 1e-6f) - 1.0f) / (0.75f * (1.0f - g)));
}

// The ground's light under a cloud of diffuse transmittance t_d towards the sun (asymmetry g),
// given the sunlight the clouds around scatter down (`cloud_light`, ground_light.comp: a
// cosine-weighted mean over the sky): x the share of the sun's light on the ground, y the
// weight of the clouds' light. Half a horizontal surface's diffuse light comes from within
// 45 deg of the zenith, where the cloud towards the sun, as far as it is cloud (w = 1 -
// exp(-tau)), stands for the cloud overhead (as cloud_ground_sky_share does for the sky's
// light): its diffuse transmittance lights that half, the clouds around the rest. So the sunlit
// ground (w = 0) gets the direct beam and all the clouds' light, a closed deck's ground its
// diffuse transmittance. Without the clouds' light measured (no volumetric clouds), the sun's
// share is the direct and diffuse light together.
vec2 cloud_ground_light_shares(float t_d, float g, vec3 cloud_light) {
  if (max(cloud_light.r, max(cloud_light.g, cloud_light.b)) <= 0.0f) return vec2(t_d, 0.0f);
  float t_direct = cloud_direct_transmittance(t_d, g);
  float w = 1.0f - t_direct;
  return vec2(t_direct + 0.5f * w * (t_d - t_direct), 1.0f - 0.5f * w);
}

// (1 - e^(-2 k x)) / (2 k), which tends to x as k goes to 0 (a conservative medium).
float two_stream_spread(float k, float x) {
  float y = 2.0f * k * x;
  return y < 1e-3f ? x * (1.0f - 0.5f * y) : (1.0f - exp(-y)) / (2.0f * k);
}

// The diffuse fluxes at a point of a cloud, per unit of the sun's irradiance, in the Eddington
// two-stream model of a homogeneous slab across the sun's chord through the point (Meador &
// Weaver 1980): optical depth tau_sun towards the sun, tau_behind onwards to where the chord
// leaves the cloud, droplets of single-scattering albedo `albedo` and asymmetry g (the phase
// function's mean cosine). gamma1 = (7 - w (4 + 3g)) / 4, gamma2 = -(1 - w (4 - 3g)) / 4,
// k = sqrt(gamma1^2 - gamma2^2), r = gamma2 / (gamma1 + k) (a deep cloud's reflectance); with
// the light entering at the sunlit end (F_on = 1 there) and none entering at the far end
// (F_back = 0 there), F_on = a e^(-k tau)(1 - r^2 e^(-2k tau_b)), F_back = a r e^(-k tau)(1 -
// e^(-2k tau_b)), written in a form that stays finite as w goes to 1, where it gives
// F_on = (1 + gamma1 tau_b) / (1 + gamma1 T), F_back = gamma1 tau_b / (1 + gamma1 T), T the
// whole chord. x: the light going on away from the sun (the direct beam included), y: the
// light scattered back towards the sun.
vec2 cloud_two_stream_fluxes(float tau_sun, float tau_behind, float albedo, float g) {
  tau_sun = max(tau_sun, 0.0f);
  tau_behind = max(tau_behind, 0.0f);
  float w = clamp(albedo, 0.0f, 1.0f);
  float gamma1 = (7.0f - w * (4.0f + 3.0f * g)) * 0.25f;
  float gamma2 = -(1.0f - w * (4.0f - 3.0f * g)) * 0.25f;
  float k = sqrt(max(gamma1 * gamma1 - gamma2 * gamma2, 0.0f));
  float edge = 1.0f / (gamma1 + k);
  float chord = tau_sun + tau_behind;
  float d = two_stream_spread(k, chord) + exp(-2.0f * k * chord) * edge;
  float decay = exp(-k * tau_sun);
  float behind = two_stream_spread(k, tau_behind);
  float on = decay * (behind + exp(-2.0f * k * tau_behind) * edge) / d;
  float back = gamma2 * edge * decay * behind / d;
  return vec2(on, back);
}

// With the seed's droplets' asymmetry, CLOUD_DROPLET_G.
vec2 cloud_two_stream_fluxes(float tau_sun, float tau_behind, float albedo) {
  return cloud_two_stream_fluxes(tau_sun, tau_behind, albedo, CLOUD_DROPLET_G);
}

// The light a cloud sample scatters from the two-stream field (cloud_two_stream_fluxes) towards
// a viewer, per unit of the sun's irradiance and of albedo: the diffuse fluxes as a radiance
// linear in the direction (Eddington: I0 = (F_on + F_back) / 2 pi, I1 = 3 (F_on - F_back) /
// 4 pi, the direct beam left out of F_on), scattered by a phase function of mean cosine g1:
// I0 + g1 I1 mu, mu the cosine between the view ray and the direction to the sun.
float cloud_two_stream_radiance(vec2 fluxes, float tau_sun, float mu, float g1) {
  float on = max(fluxes.x - exp(-tau_sun), 0.0f);
  float i0 = (on + fluxes.y) / (2.0f * PI);
  float i1 = 3.0f * (on - fluxes.y) / (4.0f * PI);
  return max(i0 + g1 * i1 * mu, 0.0f);
}

// Share of the clear sky's light that reaches a ground point under clouds: half of a horizontal
// surface's sky light comes from within 45 deg of the zenith (cosine weighting), where the
// cloud towards the sun (its diffuse transmittance `local_t`) stands for the cloud overhead;
// the other half from further out, where the clouds' mean transmittance over the region
// around (`mean_t`: 1 - cover + cover x T) counts. A closed deck passes T; a broken field's
// shadow keeps the light of the gaps, blue as shadows under fair-weather cumulus are.
float cloud_ground_sky_share(float local_t, float mean_t) {
  return 0.5f * (local_t + mean_t);
}

// The light of the ground around a cloud sample, as a share of the clear ground's (per channel):
// the sun's light on the ground `sun_ground` by the mean share `sun_t` the clouds pass of it
// there (the diffuse transmittance towards the sun, below_light_share), the sky's `sky_ground`
// by the clouds' mean transmittance down `mean_t`, and the sunlight the clouds around scatter
// down `clouds_down`, the share of it from the cloud overhead (half the diffuse light comes
// from within 45 deg of the zenith, as in cloud_ground_light_shares) being in sun_t already;
// all per unit of the key light, as ground_light.comp's r and gba. Means over the ground
// around: the clear ground's light times the sun's share alone left the shadows around a
// cumulus black to the bases above them (the sky and the clouds light them) and the sunlit
// ground without the clouds' light (14% of it at noon, ground_light.comp).
vec3 cloud_ground_light_ratio(float sun_t, float mean_t, vec3 clouds_down, vec3 sun_ground,
                              vec3 sky_ground) {
  vec3 cloudy = sun_ground * sun_t + sky_ground * mean_t + clouds_down * (0.5f + 0.5f * sun_t);
  return cloudy / max(sun_ground + sky_ground, vec3(1e-20f));
}

// The radiance the clouds' layer adds, seen from above, to the clear ground's (per unit of the
// key light, as ground_light.comp's): the layer's own light `clouds_up` plus the ground seen
// through it (the share `up_t`), itself lit `ground_ratio` times as the clear ground
// (cloud_ground_light_ratio), against the clear ground of albedo `albedo` whose radiance
// under a white ground's `white_ground` the sky-view table already counts. Never negative.
vec3 cloud_layer_gain(vec3 clouds_up, float up_t, vec3 ground_ratio, vec3 white_ground,
                      float albedo) {
  return max(clouds_up + (up_t * ground_ratio - 1.0f) * albedo * white_ground, vec3(0.0f));
}

// Light reaching a sample (listing B.2, formulas 1.7, 1.9, 1.10): Beer-Lambert exp(-tau) times
// the powder term mix(2 (1 - exp(-2 tau)), 1, (mu + 1) / 2), with `powder` in [0, 1] blending
// it in. tau is the optical depth towards the sun.
float cloud_beer_powder(float tau, float mu, float powder) {
  float beer = exp(-tau);
  // exp(-2 tau) = beer^2: one exponential, not two (they cost the same on every lane of a
  // CPU device's SIMD batch).
  float powder_term = mix(2.0f * (1.0f - beer * beer), 1.0f, 0.5f * (mu + 1.0f));
  return beer * mix(1.0f, powder_term, powder);
}

#endif

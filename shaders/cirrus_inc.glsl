// The cirrus sheet (scene.h CirrusParams): its optical depth from the noise textures, and the
// where a ray crosses it. GLSL only (texture reads); the pure parts are in common/clouds_inc.glsl,
// its lighting in compose.comp. Includers include bindings, math and clouds first.
#ifndef NEPHELE_CIRRUS_INC
#define NEPHELE_CIRRUS_INC

#include "forecast_inc.glsl"

// Vertical optical depth of the sheet at the planet-frame point p on it. Cirrus: the base
// noise stretched 8x along the wind into streaks, with finer fibres, in patches tens of
// kilometres across; cirrostratus: a smooth
// veil over most of the sky; cirrocumulus: small Worley cells (about 190 m) in patches.
float cirrus_optical_depth(vec3 p) {
  vec2 xy = p.xy - frame.cirrus_wind.xy;
  vec2 along = frame.cirrus_wind.zw;
  vec2 q = vec2(dot(xy, along), dot(xy, vec2(-along.y, along.x)));
  float patches = textureLod(base_noise, vec3(xy / 40000.0f, 0.8f), 0.0f).r;
  float streaks = (textureLod(base_noise, vec3(q.x / 48000.0f, q.y / 6000.0f, 0.3f), 0.0f).r * 0.7f +
                   textureLod(base_noise, vec3(q.x / 12000.0f, q.y / 1500.0f, 0.6f), 0.0f).g * 0.3f) *
                  saturate(remap(patches, 0.45f, 0.8f, 0.0f, 1.2f));
  float veil = mix(0.55f, 1.0f, patches);
  float cells = textureLod(base_noise, vec3(xy / 3000.0f, 0.45f), 0.0f).a * mix(0.6f, 1.1f, patches);
  vec3 w = cirrus_genus_weights(frame.cirrus.z);
  float field = dot(w, vec3(streaks, veil, cells));
  float coverage = frame.cirrus.y * forecast_share(vec2(p)).z;  // a forecast's, fixed to the ground
  float density = coverage > 0.0f ? saturate(remap(field, 1.0f - coverage, 1.0f, 0.0f, 1.0f)) : 0.0f;
  return frame.cirrus.w * density;
}

// Where the view ray from `eye` crosses the sheet: the distance (m), 0 when it does not (no
// cirrus, the sheet behind, or the ground in the way).
float cirrus_distance(vec3 eye, vec3 dir) {
  vec2 hit = ray_sphere(eye, dir, frame.cirrus.x);
  bool below = length(eye) < frame.cirrus.x;
  float t = below ? hit.y : hit.x;
  bool blocked = below && ray_sphere(eye, dir, frame.radii_m.x).x > 0.0f;  // the ground
  return frame.cirrus.y <= 0.0f || t <= 0.0f || blocked ? 0.0f : t;
}

#endif

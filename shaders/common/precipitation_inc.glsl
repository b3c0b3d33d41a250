// Rain and snow as a medium (render/modules/precipitation): its extinction from the rate by an
// empirical law, its profile below the cloud base, and where the clouds let it fall. Pure
// functions, also compiled as C++ (src/render/glsl.h conventions; needs clouds_inc.glsl).
//
// Falling particles are large against the wavelength of light. Each takes its geometric
// cross-section out of a beam by reflection and refraction, and as much again by diffraction
// (the extinction paradox: efficiency 2); but a drop of a millimetre diffracts within a few
// hundredths of a degree, which the eye and the image count as unscattered light. Rain and
// drizzle: efficiency 1. Snow and sleet: the aggregates' small crystals diffract more widely,
// and efficiency 2 is what the observed visibilities in snow bear out (below). The visibility
// follows by Koschmieder (3.912 / sigma_t).
//
// Rain: Marshall and Palmer (1948), N(D) = N0 exp(-lambda D), N0 = 8000 m^-3 mm^-1,
// lambda = 4.1 R^-0.21 mm^-1 for a rate R in mm/h; sigma_t = int (pi D^2 / 4) N(D) dD =
// pi N0 / (2 lambda^3) = 1.82e-4 R^0.63 per m: 21 km of visibility at 1 mm/h, 5 km at 10,
// 2.1 km at 40 (Atlas 1953 measured 0.25 R^0.63 per km).
//
// Drizzle, snow and sleet: a rate R (mm/h of water, R / 3600 kg m^-2 s^-1) carried by
// particles of cross-section per mass A/m falling at v holds R / (3600 v) kg of them per m^3:
// sigma_t = Q (A/m) R / (3600 v), Q the efficiency. Spheres of diameter D and density rho
// have A/m = 3 / (2 rho D):
//   drizzle: drops of 0.3 mm (5 m^2/kg) falling at 1.2 m/s (Gunn and Kinzer 1949);
//   dry snow: aggregates of 5 mm at 50 kg/m^3 (6 m^2/kg) falling at 1 m/s (Locatelli and
//     Hobbs 1974): 1.2 km of visibility at 1 mm/h, 0.4 km at 3 (the US observers' light and
//     heavy snow; Rasmussen et al. 1999 find a factor of 3 to 10 about it from storm to storm);
//   sleet (wet snow): 3 mm at 200 kg/m^3 (2.5 m^2/kg) falling at 2 m/s.
#ifndef NEPHELE_PRECIPITATION_INC
#define NEPHELE_PRECIPITATION_INC

const int PRECIPITATION_RAIN = 0;
const int PRECIPITATION_DRIZZLE = 1;
const int PRECIPITATION_SNOW = 2;
const int PRECIPITATION_SLEET = 3;

// The particles' fall speed (m/s) in still air. Rain: the drops of Marshall and Palmer's median
// volume diameter D0 = 3.67 / lambda (0.9 mm at 1 mm/h, 1.45 mm at 10), by Atlas, Srivastava
// and Sekhon's (1973) fit to Gunn and Kinzer's measurements, v = 9.65 - 10.3 exp(-0.6 D)
// (D in mm): 3.6 m/s at 1 mm/h, 5.3 at 10. Drizzle, snow and sleet: as below.
float precipitation_fall_mps(int kind, float rate_mm_per_h) {
  if (kind == PRECIPITATION_RAIN) {
    float d0_mm = 3.67f / (4.1f * pow(max(rate_mm_per_h, 1e-3f), -0.21f));
    return 9.65f - 10.3f * exp(-0.6f * d0_mm);
  }
  return kind == PRECIPITATION_DRIZZLE ? 1.2f : kind == PRECIPITATION_SNOW ? 1.0f : 2.0f;
}

// The extinction efficiency counted (above): rain and drizzle 1, snow and sleet 2.
float precipitation_efficiency(int kind) {
  return kind == PRECIPITATION_RAIN || kind == PRECIPITATION_DRIZZLE ? 1.0f : 2.0f;
}

// Extinction (1/m) of precipitation of `kind` at `rate_mm_per_h` (liquid-water equivalent).
float precipitation_sigma_t_per_m(int kind, float rate_mm_per_h) {
  float rate = max(rate_mm_per_h, 0.0f);
  if (rate <= 0.0f) return 0.0f;
  if (kind == PRECIPITATION_RAIN) {
    float lambda_per_m = 4100.0f * pow(rate, -0.21f);
    return 0.5f * 3.14159265f * 8.0e6f / (lambda_per_m * lambda_per_m * lambda_per_m);
  }
  float efficiency = precipitation_efficiency(kind);
  float area_per_kg = kind == PRECIPITATION_DRIZZLE ? 5.0f : kind == PRECIPITATION_SNOW ? 6.0f : 2.5f;
  return efficiency * area_per_kg * rate / (3600.0f * precipitation_fall_mps(kind, rate));
}

// The particles seen one by one near the camera (precipitation_particles_inc.glsl): each kind by one
// diameter (m): rain by Marshall and Palmer's median volume diameter D0 = 3.67 / lambda (as its
// fall speed), drizzle 0.3 mm, snow aggregates 5 mm, sleet 3 mm (the sizes above).
float precipitation_particle_m(int kind, float rate_mm_per_h) {
  if (kind == PRECIPITATION_RAIN) return 3.67f / (4100.0f * pow(max(rate_mm_per_h, 1e-3f), -0.21f));
  return kind == PRECIPITATION_DRIZZLE ? 0.3e-3f : kind == PRECIPITATION_SNOW ? 5.0e-3f : 3.0e-3f;
}

// How many particles of that diameter there are per m^3: as many as carry the medium's
// extinction, sigma_t / (Q pi D^2 / 4), so the particles drawn near the camera hide as much
// of what lies behind them, on average, as the medium they stand for (rain at 5 mm/h: 406 drops
// of 1.25 mm; snow at 1 mm/h: 85 flakes of 5 mm).
float precipitation_particles_per_m3(int kind, float rate_mm_per_h) {
  float d_m = precipitation_particle_m(kind, rate_mm_per_h);
  return precipitation_sigma_t_per_m(kind, rate_mm_per_h) /
         (precipitation_efficiency(kind) * 0.25f * 3.14159265f * d_m * d_m);
}

// The opacity a pixel sees of one particle of diameter `d_m` drawn out over the exposure into a
// streak `streak_m` long (across the view), where the pixel spans `footprint_m`: the share of
// the pixel's area and of the exposure it covers, its cross-section over the larger of the
// streak's area and the pixel's (a drop 1.25 mm across streaked 9 cm, 5 m away in a 900-pixel
// image of 60 degrees: 0.2%).
float precipitation_streak_opacity(float d_m, float streak_m, float footprint_m) {
  float area_m2 = 0.25f * 3.14159265f * d_m * d_m;
  return min(area_m2 / (max(streak_m + d_m, footprint_m) * max(d_m, footprint_m)), 1.0f);
}

// The wind (east, north; m/s) at `height_m` above the ground, from the wind at the cloud base
// `base_m` above it by a 1/7 power law (taken from 2 m up): the near particles' drift.
vec2 precipitation_wind_at(vec2 base_wind_mps, float height_m, float base_m) {
  return base_wind_mps * pow(saturate(max(height_m, 2.0f) / max(base_m, 2.0f)), 1.0f / 7.0f);
}

// How far the wind carries the particles sideways per metre they fall (east, north): the mean
// wind over the fall, 7/8 of the wind at the cloud base by that power law from the ground,
// over the fall speed. A shaft leans downwind by this slope.
vec2 precipitation_drift_slope(vec2 base_wind_mps, float fall_mps) {
  return base_wind_mps * (0.875f / max(fall_mps, 0.1f));
}

// The particles' phase asymmetry, without the diffraction peak counted as unscattered above:
// drops (reflection and refraction, about 0.8), snow and sleet (ice aggregates, about 0.7).
// Both scatter nearly without absorbing in visible light (albedo 1).
float precipitation_phase_g(int kind) {
  return kind == PRECIPITATION_RAIN || kind == PRECIPITATION_DRIZZLE ? 0.8f : 0.7f;
}

// The density's profile (0 to 1) at `altitude_m` under a cloud base `top_m`: 1 from the base
// down to the ground when `bottom_m` is 0; virga otherwise, the particles evaporating as they
// fall: 1 at the base, thinning linearly over the lower half of the fall to 0 at `bottom_m`.
// Nothing above the base or below the bottom.
float precipitation_profile(float altitude_m, float bottom_m, float top_m) {
  if (altitude_m > top_m || altitude_m < bottom_m) return 0.0f;
  if (bottom_m <= 0.0f) return 1.0f;
  return saturate((altitude_m - bottom_m) / max(0.5f * (top_m - bottom_m), 1e-3f));
}

// The profile's integral from the ground to `altitude_m` (m of density 1): the column below a
// point, and by difference any stretch of altitudes.
float precipitation_column_m(float altitude_m, float bottom_m, float top_m) {
  float z = min(altitude_m, top_m);
  if (z <= bottom_m) return 0.0f;
  if (bottom_m <= 0.0f) return z;
  float ramp_m = max(0.5f * (top_m - bottom_m), 1e-3f);
  float above_m = z - bottom_m;
  return above_m <= ramp_m ? 0.5f * above_m * above_m / ramp_m : above_m - 0.5f * ramp_m;
}

// Where the low layer lets it fall, from its weather map (R coverage, G storm cells) and the
// layer's coverage and storm growth (clouds.precipitation). Returns (x) the share, 0 to 1:
// under the storm cells' cumulonimbus cores (y: cloud_storm_cell from half to wholly a
// cumulonimbus), and under a deck: a layer of coverage 0.6 to 0.8 and more (broken to
// overcast: nimbostratus, the closed decks of stratus and stratocumulus) where it is nearly
// closed (a local coverage from 0.55 to 0.85). Not from the fair-weather cumulus of a
// scattered layer, however dense its clusters.
vec2 precipitation_shaft_share(float weather_coverage, float weather_storm, float coverage,
                               float storm_growth) {
  float core = smoothstep(0.5f, 1.0f, cloud_storm_cell(weather_storm, storm_growth).x);
  float deck = smoothstep(0.55f, 0.85f, cloud_local_coverage(weather_coverage, coverage)) *
               smoothstep(0.6f, 0.8f, coverage);
  return vec2(max(core, deck), core);
}

// The light in a shaft, as a share of what the clouds around let through on average: under a
// storm's core (`core` 1), whose cloud above is hundreds deep in optical depth and passes a
// tenth or less of that, the shaft is lit mostly from its sides: a quarter of it.
float precipitation_core_light(float core) {
  return 1.0f - 0.75f * core;
}

// The march's steps, and the froxels' slices (one more: the ray's start).
const int PRECIPITATION_STEPS = 24;
// A storm's shafts stand out from 100 km away and more; beyond, the haze has taken them.
const float PRECIPITATION_MAX_RANGE_M = 150000.0f;

// Where sample k (0 to PRECIPITATION_STEPS) of a ray lies (m along it). The samples lie on
// fixed horizontal distances from the eye, r_k = range (k / n)^2, so that every pixel of a
// column of the image samples the same vertical shafts at the same places and they stand as
// columns (fractions of each ray's own stretch gave each row its own places: a moire across
// the shafts). Those outside the ray's stretch fall on its ends: a short ray up through the
// shafts is taken in one step. The last is the stretch's end.
float precipitation_sample_t(int k, vec2 stretch, float horizontal) {
  if (k >= PRECIPITATION_STEPS) return stretch.y;
  float u = float(k) / float(PRECIPITATION_STEPS);
  return clamp(PRECIPITATION_MAX_RANGE_M * u * u / horizontal, stretch.x, stretch.y);
}

// The (fractional) sample at `t_m` along a ray: sample k's place is at or before it, k + 1's
// after (precipitation_sample_t's inverse, continuous where the samples are apart).
float precipitation_sample_at(float t_m, vec2 stretch, float horizontal) {
  float k = floor(float(PRECIPITATION_STEPS) * sqrt(max(t_m * horizontal, 0.0f) / PRECIPITATION_MAX_RANGE_M));
  k = clamp(k, 0.0f, float(PRECIPITATION_STEPS - 1));
  float ta = precipitation_sample_t(int(k), stretch, horizontal);
  float tb = precipitation_sample_t(int(k) + 1, stretch, horizontal);
  return k + (tb > ta ? saturate((t_m - ta) / (tb - ta)) : 1.0f);
}

#endif

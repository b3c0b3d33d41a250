// A forecast's cover (render/modules/weather, weather/grib.h): the share of each layer's own
// coverage that a GRIB forecast gives at a point of the ground, fixed to it (it does not move
// with the wind). Reads `frame` and the sampler forecast_cover (the CPU queries define both:
// render/cloud_query.cpp). Written without swizzles, so that it compiles as C++ (glm).
#ifndef NEPHELE_FORECAST_INC
#define NEPHELE_FORECAST_INC

// At `ground_xy` (planet frame, m: east and north of the observer): x the low layer's share,
// y the high volumetric layer's, z the cirrus sheet's; 1 without a forecast.
vec4 forecast_share(vec2 ground_xy) {
  vec2 uv = clamp(ground_xy * frame.forecast.x + 0.5f, vec2(frame.forecast.y), vec2(1.0f - frame.forecast.y));
  return textureLod(forecast_cover, uv, 0.0f);
}

#endif

// Reading a cloud layer's weather map (render/modules/weather) where it lies over a point of the
// ground: the clouds' density (noise_density_inc.glsl), the rain's shafts
// (precipitation_field_inc.glsl) and the lightning's storm cores (lightning.comp) read it alike.
// Reads `frame` and the sampler weather_map (the CPU queries define both: render/cloud_query.cpp).
// Written without swizzles, so that it compiles as C++ (glm).
#ifndef NEPHELE_WEATHER_MAP_INC
#define NEPHELE_WEATHER_MAP_INC

// `layer`'s weather map at `ground_xy` (planet frame, m), a place already moved back by the
// layer's wind.
vec4 weather_map_at(CloudLayerGpu layer, vec2 ground_xy) {
  return textureLod(weather_map, ground_xy * frame.cloud_noise.z + vec2(layer.radii_m.z, layer.radii_m.w) + 0.5f, 0.0f);
}

#endif

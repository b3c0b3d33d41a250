// The one descriptor set every pass uses (src/render/passes.cpp creates its layout).
#ifndef NEPHELE_BINDINGS_INC
#define NEPHELE_BINDINGS_INC

#extension GL_GOOGLE_include_directive : require
#include "common/params_inc.glsl"

layout(std140, set = 0, binding = 0) uniform FrameBlock { FrameParams frame; };
layout(set = 0, binding = 1, rgba8) uniform writeonly image3D base_noise_out;
layout(set = 0, binding = 2, rgba8) uniform writeonly image3D detail_noise_out;
layout(set = 0, binding = 3, rgba8) uniform writeonly image2D weather_out;
layout(set = 0, binding = 4) uniform sampler3D base_noise;
layout(set = 0, binding = 5) uniform sampler3D detail_noise;
layout(set = 0, binding = 6) uniform sampler2D weather_map;
// Cloud samples: two vec4 per cloud pixel (see clouds.comp): (rgb in-scattered cloud radiance,
// a cloud transmittance), (x haze weight, y ground shadow, z cloud distance (m), w unused).
// march_out: the pixels marched this frame, one per stride x stride block (clouds.comp);
// history: the previous frame's full cloud buffer; cloud_out: this frame's (resolve.comp).
layout(std430, set = 0, binding = 7) buffer MarchBuffer { vec4 march_out[]; };
layout(std430, set = 0, binding = 11) readonly buffer HistoryBuffer { vec4 history[]; };
layout(std430, set = 0, binding = 12) buffer CloudBuffer { vec4 cloud_out[]; };
// Optical depth towards the sun (density field x metres) on the light volume's grid
// (common/light_volume_inc.glsl), x fastest: LIGHT_VOLUME_XY^2 x LIGHT_VOLUME_Z floats.
layout(std430, set = 0, binding = 13) buffer LightVolume { float light_volume[]; };
// Per pixel: linear HDR radiance of the final image.
layout(std430, set = 0, binding = 8) buffer ColorBuffer { vec4 color_out[]; };
// Sky-view LUT (common/sky_view_inc.glsl): sky_view.comp writes it, compose.comp samples it.
// Two stacked tables: rows [0, H) in-scattered radiance, rows [H, 2H) the ground's sun-lit
// radiance, both per unit solar illuminance.
layout(set = 0, binding = 9, rgba16f) uniform writeonly image2D sky_view_out;
layout(set = 0, binding = 10) uniform sampler2D sky_view_lut;

#endif

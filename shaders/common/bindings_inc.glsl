// The bindings of set 0, declared once: gpu::Binding is generated from these declarations
// (cmake/bindings_header.cmake; an image `sky_view_lut` is gpu::kSkyViewLut, a block
// `StarsBlock` gpu::kStars), and each pipeline's layout holds only those its shaders use
// (reflected from their SPIR-V: src/gpu/shader_interface.h). The numbers run 0, 1, 2, ...
#ifndef NEPHELE_BINDINGS_INC
#define NEPHELE_BINDINGS_INC

#extension GL_GOOGLE_include_directive : require
#include "common/params_inc.glsl"

layout(std140, set = 0, binding = 0) uniform FrameParamsBlock { FrameParams frame; };
layout(set = 0, binding = 1, rgba8) uniform writeonly image3D base_noise_out;
layout(set = 0, binding = 2, rgba8) uniform writeonly image3D detail_noise_out;
// The evolving weather's states (render/modules/weather/weather.h), one a layer, written by
// weather.comp and read by weather_blend.comp.
layout(set = 0, binding = 3, rgba8) uniform image3D weather_states;
layout(set = 0, binding = 4) uniform sampler3D base_noise;
layout(set = 0, binding = 5) uniform sampler3D detail_noise;
layout(set = 0, binding = 6) uniform sampler2D weather_map;
// Sky-view LUT (common/sky_view_inc.glsl): sky_view.comp writes it, compose.comp samples it.
// Two stacked tables: rows [0, H) in-scattered radiance, rows [H, 2H) the ground's sun-lit
// radiance, both per unit solar illuminance.
layout(set = 0, binding = 7, rgba16f) uniform writeonly image2D sky_view_out;
layout(set = 0, binding = 8) uniform sampler2D sky_view_lut;
// Optical depth towards the sun (density field x metres) on the light volume's grid
// (common/light_volume_inc.glsl): LIGHT_VOLUME_XY^2 x LIGHT_VOLUME_Z texels, written by
// light_volume.comp (which reads back the layers it built above), sampled with trilinear
// filtering.
layout(set = 0, binding = 9, r32f) uniform image3D light_volume_out;
layout(set = 0, binding = 10) uniform sampler3D light_volume;
// Cloud samples: two images per cloud buffer, A = (rgb in-scattered cloud radiance, a cloud
// transmittance), B = (x haze weight, y ground shadow, z cloud distance (km), w samples
// averaged). march: the pixels marched this frame, one texel per stride x stride block
// (clouds.comp); clouds: this frame's full cloud buffer (resolve.comp), history: the previous
// frame's. Images, not storage buffers: a CPU device (lavapipe) reads and writes images with
// vector gathers, buffers one lane at a time.
layout(set = 0, binding = 11, rgba32f) uniform writeonly image2D march_a_out;
layout(set = 0, binding = 12, rgba32f) uniform writeonly image2D march_b_out;
layout(set = 0, binding = 13) uniform sampler2D march_a;
layout(set = 0, binding = 14) uniform sampler2D march_b;
layout(set = 0, binding = 15, rgba32f) uniform writeonly image2D clouds_a_out;
layout(set = 0, binding = 16, rgba32f) uniform writeonly image2D clouds_b_out;
layout(set = 0, binding = 17) uniform sampler2D clouds_a;
layout(set = 0, binding = 18) uniform sampler2D clouds_b;
layout(set = 0, binding = 19) uniform sampler2D history_a;
layout(set = 0, binding = 20) uniform sampler2D history_b;
// Per pixel: linear HDR radiance of the final image.
layout(set = 0, binding = 21, rgba32f) uniform writeonly image2D color_out;
// Per block: the range (lo, hi) of march_a over the 4 x 4 marched samples from one block up
// and left to two down and right (march_range.comp; read by resolve.comp).
layout(set = 0, binding = 22, rgba32f) uniform image2D range_lo;
layout(set = 0, binding = 23, rgba32f) uniform image2D range_hi;
// The star catalogue (StarGpu), and the final image again, read and written by stars.comp.
layout(std430, set = 0, binding = 24) readonly buffer StarsBlock { StarGpu star_list[]; };
layout(set = 0, binding = 25, rgba32f) uniform image2D color_rw;
// Hillaire's atmosphere tables (common/atmosphere_lut_inc.glsl): transmittance (r, mu),
// multiple scattering Psi_ms (sun zenith, altitude), and the aerial-perspective volume
// (common/sky_view_inc.glsl: rgb in-scattered radiance per unit illuminance, a transmittance).
layout(set = 0, binding = 26, rgba32f) uniform writeonly image2D transmittance_lut_out;
layout(set = 0, binding = 27) uniform sampler2D transmittance_lut;
layout(set = 0, binding = 28, rgba32f) uniform writeonly image2D ms_lut_out;
layout(set = 0, binding = 29) uniform sampler2D ms_lut;
layout(set = 0, binding = 30, rgba32f) uniform writeonly image3D aerial_perspective_out;
layout(set = 0, binding = 31) uniform sampler3D aerial_perspective;
// The brute-force reference sky (atmosphere.model = reference): Psi_ms at every step of every
// view ray of one tile (REFERENCE_TILE^2 x REFERENCE_SAMPLES), and per pixel the sky it
// integrates to (width x 2 height: rows [0, H) radiance, [H, 2H) the ground's sun-lit radiance).
layout(set = 0, binding = 32, rgba32f) uniform writeonly image3D reference_psi_out;
layout(set = 0, binding = 33) uniform sampler3D reference_psi;
layout(set = 0, binding = 34, rgba32f) uniform writeonly image2D reference_sky_out;
layout(set = 0, binding = 35) uniform sampler2D reference_sky;
// Curl noise (noise_curl.comp): RG a divergence-free 2D field, tiling, 128^2.
layout(set = 0, binding = 36, rgba32f) uniform writeonly image2D curl_noise_out;
layout(set = 0, binding = 37) uniform sampler2D curl_noise;
// The ground's light under the clouds around the camera (ground_light.comp; read by
// compose.comp and terrain.comp), texel 0: r the share of the sky's light, gba the clouds'
// light; texel 1, the layer seen from above: r the share of the ground seen, gba the clouds'.
layout(set = 0, binding = 38, rgba32f) uniform writeonly image2D ground_light_out;
layout(set = 0, binding = 39) uniform sampler2D ground_light;
// The display image (tonemap.comp): exposed, tone-mapped, sRGB code values, 8 bits.
layout(set = 0, binding = 40, rgba8) uniform writeonly image2D display_out;
// The weather map the clouds sample (binding 6), as weather_blend.comp writes it (16 bits).
layout(set = 0, binding = 41, rgba16f) uniform writeonly image2D weather_map_out;
// Voxel clouds (params_inc.glsl, VoxelCloudGpu): the brick atlas (x density, y signed
// distance in voxels; trilinear) and the page table (texelFetch).
layout(set = 0, binding = 42) uniform sampler3D voxel_atlas;
layout(set = 0, binding = 43) uniform sampler3D voxel_pages;
// The reference path tracer's accumulation (path_trace.comp): per pixel the sum of its
// samples' radiance (rgb; a the count) and the sum of their squares (rgb).
layout(set = 0, binding = 44, rgba32f) uniform image2D path_sum;
layout(set = 0, binding = 45, rgba32f) uniform image2D path_squares;
// The noise clouds' majorant grid (r: sigma_t bound, 1/m; read with texelFetch).
layout(set = 0, binding = 46) uniform sampler3D path_majorant;
// The multiple-scattering light field (atmosphere_lut_inc.glsl, ms_field_texel).
layout(set = 0, binding = 47, rgba32f) uniform writeonly image2D ms_field_out;
layout(set = 0, binding = 48) uniform sampler2D ms_field;
// The exposure meter (meter.comp), one per frame in flight, read by the host: the mean of
// log(luminance, cd/m^2) over METER_GRID^2 points of the final image.
layout(std430, set = 0, binding = 49) writeonly buffer MeterBlock { float meter_mean_log_luminance; };
// Particle clouds (render/modules/particle_clouds/particle_clouds.h): this frame's particles back to front
// (particles.vert) and their procedural textures side by side (PARTICLE_TEXTURES tiles of
// PARTICLE_TEXTURE_SIZE texels); they are drawn into the layers LAYER_PARTICLES and
// LAYER_PARTICLE_DEPTH (below).
layout(std430, set = 0, binding = 50) readonly buffer ParticlesBlock { ParticleGpu particle_list[]; };
layout(set = 0, binding = 51) uniform sampler2D particle_textures;
// The layers compose blends over the clouds (render/image_layers.h): one 2D array at the
// frame's size, a layer (LAYER_*, params_inc.glsl) each, written by the modules that draw them
// (terrain.comp, host_scene.comp, the particles' raster pass) and read through
// layers_inc.glsl, so that a new layer adds no binding.
layout(set = 0, binding = 52) uniform sampler2DArray layers;
layout(set = 0, binding = 53, rgba32f) uniform image2DArray layers_out;
// Impostors of far particle clouds (render/modules/impostors/impostors.h): this frame's quads back to
// front (impostor.vert), the atlas their images live in, each impostor's tile slots (the tiles
// method), the scratch image an impostor is drawn into before impostor_tiles.comp splits it
// into tiles, the atlas as that pass writes it, and its jobs (one per tile).
layout(std430, set = 0, binding = 54) readonly buffer ImpostorsBlock { ImpostorGpu impostor_list[]; };
layout(set = 0, binding = 55) uniform sampler2D impostor_atlas;
layout(std430, set = 0, binding = 56) readonly buffer ImpostorTileSlotsBlock { int impostor_tile_slots[]; };
layout(set = 0, binding = 57) uniform sampler2D impostor_scratch;
layout(set = 0, binding = 58, rgba16f) uniform writeonly image2D impostor_atlas_out;
layout(std430, set = 0, binding = 59) readonly buffer ImpostorTileJobsBlock { ImpostorTileJob impostor_tile_jobs[]; };
// The particle clouds' lighting on the device (particle_light.comp, render/modules/
// particle_light_gpu.h): every cloud's particles seen from the light, nearest first, the clouds
// (one workgroup each), and the light reaching each particle, I_k in [0, 1], in the field's order.
layout(std430, set = 0, binding = 60) readonly buffer ParticleSplatsBlock { ParticleSplatGpu particle_splats[]; };
layout(std430, set = 0, binding = 61) readonly buffer ParticleLightCloudsBlock { ParticleLightCloudGpu particle_light_clouds[]; };
layout(std430, set = 0, binding = 62) writeonly buffer ParticleLightsBlock { float particle_lights[]; };
// Nishita and Nakamae's metaball clouds (render/modules/metaball_clouds/metaball_clouds.h): three volumes of
// the grid stacked in depth (NISHITA_SLABS): the density field (r), the sun's transmittance and
// the sky's light (r, gba), the second order's light (x its total, yzw its flux vector).
layout(set = 0, binding = 63, rgba32f) uniform writeonly image3D nishita_volume_out;
layout(set = 0, binding = 64) uniform sampler3D nishita_volume;
// Bloom's horizontal pass's result (bloom.comp), read by its vertical pass.
layout(set = 0, binding = 65, rgba32f) uniform image2D post_temp;
// Volumetric light shafts (light_shafts.comp, read by compose.comp): rgb the air's light lost to
// the clouds' shadows, a the share of it in front of the clouds.
layout(set = 0, binding = 66, rgba32f) uniform writeonly image2D light_shafts_out;
layout(set = 0, binding = 67) uniform sampler2D light_shafts;
// The terrain (render/modules/terrain/terrain.h): its heights (r, m above the ground; rows [0, H), row
// 0 the north edge) with their pyramid of maxima packed below them (rows from H:
// terrain::MaxPyramid; texelFetch), and its albedo map (terrain.albedo_map; linear rgb) over
// its rectangle, row 0 north. What terrain.comp finds goes into the layer LAYER_SURFACES.
layout(set = 0, binding = 68) uniform sampler2D terrain_heights;
layout(set = 0, binding = 69) uniform sampler2D terrain_albedo_map;
// The host's depth and colour texels as the frame copied them from its images (nephele::
// HostScene; host_scene.comp merges them into LAYER_SURFACES): the depth from word 0, the colour
// from word frame.host_layout.x.
layout(std430, set = 0, binding = 70) readonly buffer HostSceneBlock { uint host_texels[]; };
// The lighting for the host (host_lighting.comp; render/modules/host_lighting/host_lighting.h): [0] x, y the
// clouds' transmittance at the camera towards the key and the second light, z the clouds'
// sigma_t there (1/m), w the share of the clear sky's light under the clouds; [1 + k] the sky's
// radiance's spherical-harmonic coefficient k (rgb, per unit key-light illuminance). And the
// cloud shadow map (r: the key light's share through the clouds; cloud_shadow_map.comp).
layout(std430, set = 0, binding = 71) writeonly buffer HostLightingBlock { vec4 host_lighting_out[]; };
layout(set = 0, binding = 72, r32f) uniform writeonly image2D cloud_shadow_map_out;
// The host's environment cube map (environment.comp): its six faces side by side, +X -X +Y -Y
// +Z -Z of ENU, radiance (cd/m^2).
layout(set = 0, binding = 73, rgba16f) uniform writeonly image2D environment_out;
// The reference path tracer's paths in progress (path_trace.comp, PATH_STATE_TEXELS texels a
// path, in blocks of path_sum's height) and its counts, read by the host: samples finished,
// invocations with samples still to take after the last pass (the host zeroes it before each),
// walks cut at PT_MAX_COLLISIONS, tentative collisions above their majorant, invocations whose
// pass lavapipe's loop limit ended early.
layout(set = 0, binding = 74, rgba32f) uniform image2D path_state;
layout(std430, set = 0, binding = 75) buffer PathCountsBlock {
  uint path_finished;
  uint path_running;
  uint path_cut;
  uint path_violations;
  uint path_limited;
};
// A forecast's cloud cover around the observer (weather/grib.h, forecast_texels; 1 x 1 white
// without one): r the low layer's, g the high volumetric layer's and b the cirrus sheet's
// coverage as a share of the layer's own; read by forecast_inc.glsl.
layout(set = 0, binding = 76) uniform sampler2D forecast_cover;

#endif

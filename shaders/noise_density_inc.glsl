// The noise clouds' density field (seed 000 listing B.1, Schneider 2015): the cloud layers'
// coverage, type and density from the weather map, carved by the base noise and eroded by the
// detail noise. Shared by the passes (through cloud_field_inc.glsl) and by the host's CPU
// queries (render/cloud_query.cpp), which define what it reads: `frame` (FrameParams), the
// samplers base_noise, detail_noise, weather_map and curl_noise, the int MARCH_MODE (0
// default, 1 the seed's baseline) and the bool WITH_FLOW (false: a variant without the flow
// map's reads). Written without swizzles, so that it compiles as C++ (glm).
#ifndef NEPHELE_NOISE_DENSITY_INC
#define NEPHELE_NOISE_DENSITY_INC

// The footprint (m) over which the detail noise is read at pos, which picks its mip level: in
// the passes that draw a view, a pixel's at pos' distance (cloud_shape.x; 0 for the finest
// level, as the path tracer reads it). The lighting's grids, built once for every view of a
// scene (the light volume, the diffusion light's medium, the ground's light), define it before
// including this file as their own cell's size. Read at a view's level they depended on the
// image's size, its field of view and where the camera stood: a 64 x 40 still lit by a 640 x 400
// one's grids was 1.8% off its own (up to 8% in a pixel), and the suite's 40 x 25 views were lit
// with the detail all but averaged away. With the cells' level: the suite 99.9 -> 98.9 points
// (inside a cloud 12.8 -> 10.2%); with the finest level 104.0 (docs/validation.md).
#include "forecast_inc.glsl"
#include "weather_map_inc.glsl"

#ifndef NOISE_DETAIL_FOOTPRINT_M
#define NOISE_DETAIL_FOOTPRINT_M(pos) (distance(pos, vec3(frame.camera_pos_m)) * frame.cloud_shape.x)
#endif

// The layer at `radius_m` (FrameParams::cloud_layers): the one whose band holds it, else layer
// 0. The layers in use are read in turn, the same for every lane, and selected per lane: an
// index that differs between lanes would make a CPU device gather every field lane by lane.
// With one layer the loop makes no trip.
CloudLayerGpu cloud_layer_at(float radius_m) {
  CloudLayerGpu layer = frame.cloud_layers[0];
  int used = int(frame.cloud_layers[0].band_m.w);
  for (int k = 1; k < used; ++k) {
    CloudLayerGpu other = frame.cloud_layers[k];
    bool inside = radius_m >= other.band_m.x && radius_m < other.band_m.y;
    layer = CloudLayerGpu(inside ? other.radii_m : layer.radii_m, inside ? other.shape : layer.shape,
                          inside ? other.wind : layer.wind, inside ? other.band_m : layer.band_m);
  }
  return layer;
}

// The base noise at ground_xy moved back along the flow by one of its phases (phase: weight,
// progress; cloud_flow_phase), weighted.
vec4 flowed_base_noise(vec2 ground_xy, float altitude_m, vec2 flow_m, vec2 phase) {
  return phase.x * textureLod(base_noise, vec3(ground_xy - flow_m * phase.y, altitude_m) *
                                              frame.cloud_noise.x, 0.0f);
}

// How far the last noise_density_pair's point lies inside the base shape (or the anvil), in
// units of the shape noise: the noise less the threshold the coverage sets, negative outside
// (-1 where no cloud can be: no coverage, outside the layer). The clouds' coarse steps shorten
// where it is a little under 0 (clouds.comp), so that they do not step over a thin part of the
// shape: a tower's rounded top seen at a grazing angle was hit by some pixels' jittered steps
// and not by their neighbours', dithering a still's tops.
float noise_shape_margin = -1.0f;

// The noise clouds' density field (dimensionless, listing B.1); sigma_t = field * cloud_shape.z
// (with the droplets' optics the field carries its genus' share of cloud_shape.z).
// Returns (x) the base shape alone, without detail erosion (what coarse steps test), and
// (y) the full field. Every texture is read whatever the early outs: a CPU device (lavapipe)
// executes both sides of a branch, so the reads cost the same either way.
vec2 noise_density_pair(vec3 pos) {
  float radius_m = length(pos);
  CloudLayerGpu layer = cloud_layer_at(radius_m);
  float h = cloud_height_fraction(radius_m, layer.radii_m.x, layer.radii_m.y);
  float h_wind = saturate(h);
  // The layer's wind, grown with height and leaning the tops downwind (seed 002).
  vec2 ground_xy = vec2(pos) - cloud_wind_offset(vec2(layer.wind), vec2(layer.wind.z, layer.wind.w), vec2(frame.cloud_wind),
                                              frame.cloud_wind.w, frame.cloud_wind.z, h_wind);
  vec4 weather = weather_map_at(layer, ground_xy);
  float altitude_m = radius_m - frame.radii_m.x;
  // The shape noise, moved by the flow map's swirls in two phases half a cycle apart (seed
  // 002, 局部流动效果); without a flow, one phase of weight 1 and no displacement. The flow's
  // reads are loops of at most one trip. A CPU device (lavapipe) still runs a loop's body once
  // when no lane takes a trip, so a scene without a flow runs a variant without them
  // (WITH_FLOW false): 15% of the clouds pass at 900x600.
  bool flowing = WITH_FLOW && frame.cloud_flow.x > 0.0f;
  vec2 flow_m = vec2(0.0f);  // the flow's displacement over a whole cycle
  for (int k = 0; k < (flowing ? 1 : 0); ++k)
    flow_m = vec2(textureLod(curl_noise, ground_xy * frame.cloud_flow.w, 0.0f)) *
             (frame.cloud_flow.x * frame.cloud_flow.y);
  vec4 base = flowed_base_noise(ground_xy, altitude_m, flow_m,
                                flowing ? cloud_flow_phase(frame.cloud_flow.z, 0) : vec2(1.0f, 0.0f));
  for (int k = 0; k < (flowing ? 1 : 0); ++k)
    base += flowed_base_noise(ground_xy, altitude_m, flow_m, cloud_flow_phase(frame.cloud_flow.z, 1));
  // The detail noise: its own wind relative to the shapes, and displaced by curl noise, most
  // at the bases (Schneider 2015), into swirls.
  vec2 curl = vec2(textureLod(curl_noise, ground_xy * (0.25f * frame.cloud_noise.y), 0.0f));
  vec3 detail_pos = vec3(ground_xy + curl * (frame.cloud_detail_wind.w * (1.0f - h_wind)), altitude_m) -
                    vec3(frame.cloud_detail_wind);
  // Far away a pixel spans many of the detail noise's texels: the mip level that matches the
  // pixel's footprint averages them, where the finest level aliased into speckle. The
  // baseline samples the finest level, as the seed does.
  float footprint_texels = NOISE_DETAIL_FOOTPRINT_M(pos) *
                           frame.cloud_noise.y * float(textureSize(detail_noise, 0).x);
  float detail_lod = MARCH_MODE == 1 ? 0.0f : log2(max(footprint_texels, 1e-6f));
  vec3 d = vec3(textureLod(detail_noise, detail_pos * frame.cloud_noise.y, detail_lod));
  noise_shape_margin = -1.0f;
  if (h <= 0.0f || h >= 1.0f) return vec2(0.0f);
  // Cloud type (B, around the layer's type) and precipitation (the layer's, where the map has
  // storm cells: G), which turns the cells' cores into cumulonimbus and spreads an anvil over
  // the cells.
  vec2 cell = cloud_storm_cell(weather.g, layer.shape.w);
  // A forecast's share of the layer's coverage where pos is, fixed to the ground.
  vec4 forecast = forecast_share(vec2(pos));
  float layer_coverage = layer.shape.x * mix(forecast.x, forecast.y, layer.band_m.z);
  vec2 coverage_type = cloud_precipitate(cloud_local_coverage(weather.r, layer_coverage),
                                         saturate(layer.shape.z + weather.b - 0.5f), cell.x);
  float type = coverage_type.y;
  // The genus' extinction at field 1 as a share of cloud_shape.z (droplets_inc.glsl; 1 with the
  // seed's optics).
  float genus_sigma = cloud_genus_blend(type, frame.cloud_genus_sigma, frame.cloud_droplets.x);
  float cumulonimbus = cloud_cumulonimbus_share(type);
  float coverage = coverage_type.x;
  float anvil = cloud_anvil_coverage(h, cell.y);
  // The anvil's density: the map's, as dense as a tower's top.
  float anvil_density = weather.a * 2.0f * layer.shape.y;
  float top = cloud_type_top(type);
  float h_type = saturate(h / top);  // height fraction within the type's extent
  // The seed's gradient (thin bases, dense tops; over the type's extent); cumulonimbus fills
  // towards the flatter one, so a storm's base is dark from below rather than a transparent
  // veil. The baseline keeps the seed's gradient over the whole layer.
  float density_gradient =
      (MARCH_MODE == 1 ? cloud_density_gradient(h)
                       : mix(cloud_density_gradient(h_type), cloud_type_density_gradient(h_type),
                             cumulonimbus)) *
      weather.a * 2.0f * layer.shape.y;
  if (MARCH_MODE == 1) {
    // The seed's shape gradient, up to the type's top (the seed's "maximum height").
    float shape_gradient = cloud_shape_gradient(h, top);
    // Seed: low-frequency noise 85% plus detail noise 15%, then coverage and height shape.
    float noise = base.r * 0.85f + d.r * 0.15f;
    float field = cloud_apply_coverage(noise * shape_gradient, coverage) * density_gradient;
    return vec2(max(field, cloud_apply_coverage(noise, anvil) * anvil_density) * genus_sigma);
  }
  // Schneider: Worley fBm (GBA) carves the Perlin-Worley (R), the type's height gradient
  // shapes it, coverage cuts, detail erodes.
  float worley = base.g * 0.625f + base.b * 0.25f + base.a * 0.125f;
  float noise = saturate(remap(base.r, worley - 1.0f, 1.0f, 0.0f, 1.0f));
  float detail = d.r * 0.625f + d.g * 0.25f + d.b * 0.125f;
  float shape_noise = noise * cloud_type_gradient(h, type);
  float shape = cloud_apply_coverage(shape_noise, coverage);
  noise_shape_margin = max(coverage > 0.0f ? shape_noise - (1.0f - coverage) : -1.0f,
                           anvil > 0.0f ? noise - (1.0f - anvil) : -1.0f);
  float eroded = cloud_erode(shape, detail, h, frame.cloud_noise.w);
  // The anvil, smooth (not eroded): ice, spread thin by the wind.
  float anvil_shape = cloud_apply_coverage(noise, anvil) * anvil_density;
  return max(vec2(shape, shape > 0.0f ? eroded : 0.0f) * density_gradient, vec2(anvil_shape)) *
         genus_sigma;
}

#endif

#version 450
// Pass 4: compose. Sky (from the sky-view LUT of sky_view.comp) behind and between the clouds,
// the sun disk with limb darkening and the moon disk with its phase drawn separately so clouds
// occlude them, and the clouds over both: color = background * T_cloud + cloud in-scattering
// (seed listing B.3), plus the haze in front of distant clouds, coloured by the
// aerial-perspective volume at the cloud's distance; the cirrus sheet behind the clouds or in
// front of them (cirrus_inc.glsl).
// REFERENCE (specialization constant) 1: the sky comes per pixel from the brute-force reference
// (sky_reference.comp), which the LUT path is checked against.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "dispatch_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/sun_disk_inc.glsl"
#include "common/atmosphere_inc.glsl"
#include "common/atmosphere_lut_inc.glsl"
#include "common/sky_view_inc.glsl"
#include "frame_atmosphere_inc.glsl"
#include "common/clouds_inc.glsl"
#include "cirrus_inc.glsl"
#include "terrain_inc.glsl"
// The media of the modules (their *_medium.glsl): media_in_front (generated, media_inc.glsl).
#include "media_inc.glsl"

layout(constant_id = 0) const int REFERENCE = 0;
// The scene's features (ComposeModule, from the FramePlan): false compiles a feature's code out
// of this variant (lavapipe runs both sides of every branch). True keeps it, where the frame's
// parameters still decide per pixel as they would without the constant.
layout(constant_id = 1) const bool WITH_CONDITIONS = true;  // the time-of-day keyframes
layout(constant_id = 2) const bool WITH_SHAFTS = true;      // volumetric light shafts
layout(constant_id = 3) const bool WITH_SURFACES = true;    // the terrain or the host's scene
layout(constant_id = 4) const bool WITH_CIRRUS = true;      // the cirrus sheet
layout(constant_id = 5) const bool WITH_LAYERS = true;      // a translucent layer (particles)
layout(constant_id = 6) const bool WITH_MEDIA = true;       // a medium's module is on (fog)
layout(local_size_x = 8, local_size_y = 8) in;

// Moon disk radiance as a share of the full moon's (params_inc.glsl). Its regolith scatters
// by the Lommel-Seeliger law, L ~ mu0 / (mu0 + mu) (mu0, mu: cosines of the sun's and the
// viewer's angle from the surface normal), which makes the full moon evenly bright to the limb;
// the night side glows with earthshine.
float moon_disk(vec3 dir) {
  vec3 m = frame.moon_dir.xyz;
  float cos_angle = dot(dir, m);
  if (cos_angle < frame.moon_dir.w) return 0.0f;
  float sin_radius = sqrt(max(1.0f - frame.moon_dir.w * frame.moon_dir.w, 1e-12f));
  vec3 q = (dir - m * cos_angle) / sin_radius;  // position on the disk, |q| <= 1
  float mu = sqrt(saturate(1.0f - dot(q, q)));
  vec3 normal = q - m * mu;  // the surface normal facing the viewer
  float mu0 = max(dot(normal, frame.moon_sun_dir.xyz), 0.0f);
  return 2.0f * mu0 / max(mu0 + mu, 1e-6f) + frame.moon_sun_dir.w;
}

// The sheet along the view ray from `eye`: rgb the light it scatters towards the eye per unit
// key-light illuminance (single scattering of the key light through the atmosphere's
// transmittance at the sheet, ice crystals' forward-peaked phase, plus the sky's ambient);
// a its transmittance; where the ray crosses it `distance_m` away (cirrus_distance).
vec4 cirrus_layer(Atmosphere atmo, vec3 eye, vec3 dir, float distance_m) {
  vec3 p = eye + dir * distance_m;
  float transmittance = cirrus_transmittance(cirrus_optical_depth(p), dot(dir, normalize(p)));
  vec3 sun = frame.sun_dir.xyz;
  vec3 sun_t = transmittance_to_light(atmo, transmittance_lut, false, p, sun);
  float phase = dual_lobe_hg(0.75f, -0.25f, 0.85f, dot(dir, sun));
  vec3 ambient = frame.ambient_at_clouds.rgb / max(frame.sun_illuminance.rgb, vec3(1e-30f));
  return vec4((1.0f - transmittance) * (sun_t * phase + ambient), transmittance);
}

// Linear fog ramp of the time-of-day keyframes on the sky and the discs: 1 at and below
// `start_deg`, 0 at and above `end_deg`. Their fog by distance is the ground fog's medium's.
float fog_ramp(float elevation_deg, float start_deg, float end_deg) {
  return saturate((end_deg - elevation_deg) / max(end_deg - start_deg, 1e-3f));
}

// The resolved cloud buffer at image pixel (x, y), filtered bilinearly when the clouds are
// rendered at a lower resolution than the image (both grids span the same field of view).
void cloud_at(int x, int y, out vec4 a, out vec4 b) {
  vec2 uv = (vec2(x, y) + 0.5f) / vec2(frame.size.xy);
  a = textureLod(clouds_a, uv, 0.0f);
  b = textureLod(clouds_b, uv, 0.0f);
}

// The air between the eye and `distance_m` along the view at `uv` (the aerial-perspective
// volume's): its in-scattered light (rgb, per unit of sunlight) and transmittance (a).
vec4 air_in_front(vec2 uv, float distance_m) {
  return textureLod(aerial_perspective,
                    vec3(uv.x, sky_view_v_clamped(uv, float(AP_SIZE_V)), aerial_perspective_w(distance_m)),
                    0.0f);
}

// The media in front of a layer at `distance_m` (0: the sky; media_in_front) as they are seen
// through the air in front of them: their light dimmed by the air up to their opacity-weighted
// distance, and that air's own light, which they do not hide, kept (per unit of the key
// light's illuminance; a their transmittance). What lies behind, with all the air in front of
// it, composites as behind * a + rgb.
vec4 media_through_air(vec2 uv, vec3 eye, vec3 dir, float distance_m, float cloud_light) {
  float depth_m;
  vec4 m = media_in_front(eye, dir, distance_m, cloud_light, depth_m);
  vec4 air = depth_m > 0.0f ? air_in_front(uv, depth_m) : vec4(0.0f, 0.0f, 0.0f, 1.0f);
  return vec4(m.rgb * air.a + (1.0f - m.a) * air.rgb, m.a);
}

// The part of the view under the clouds' base, [x, y] (m; y <= x where it has none), and the
// aerial perspective's in-scattering at its ends (per unit of the key light, as
// air_in_front's). The aerial perspective counts the clear sky's light there, where the clouds
// let only part of it through.
struct AirBelowBase {
  vec2 span_m;
  vec3 near, far;
};

// table_air: the sky-view table's air along the whole view (in front of the ground where it
// meets the ground), the span's far end where the view ends under the base, and nearly so
// where it comes out of the base's sphere again from above (grazing it beyond the horizon:
// the air further on is far). One lookup (lavapipe runs both sides of a branch): the far end
// from under the base, the near end from above it.
AirBelowBase air_below_base(vec2 uv, vec3 eye, vec3 dir, float ground_m, vec3 table_air) {
  vec2 base = ray_sphere(eye, dir, frame.radii_m.z);
  bool above = length(eye) > frame.radii_m.z;
  AirBelowBase a;
  a.span_m = vec2(max(base.x, 0.0f), ground_m > 0.0f ? min(base.y, ground_m) : base.y);
  vec3 looked_up = air_in_front(uv, max(above ? a.span_m.x : a.span_m.y, 0.0f)).rgb;
  a.near = above ? looked_up : vec3(0.0f);
  a.far = ground_m > 0.0f || above ? table_air : looked_up;
  if (a.span_m.y <= a.span_m.x) a.far = a.near;
  return a;
}

// Its in-scattering in front of distance_m, given the aerial perspective's there (`at`).
vec3 air_below_base_before(AirBelowBase a, float distance_m, vec3 at) {
  vec3 end = distance_m >= a.span_m.y ? a.far : distance_m > a.span_m.x ? at : a.near;
  return max(end - a.near, vec3(0.0f));
}

// The air above the clouds' layer, lit from below by the layer's reflection beyond the
// clear ground's (`gain`: the radiance it adds, per unit of the key light, cloud_layer_gain):
// the sky-view table's air sees a ground of the ground's albedo (from above the layer, the
// sky above a cumulus field was 16-24% too dark against the path tracer). The layer fills the
// lower hemisphere with a uniform radiance and the air scatters half of it towards any view
// (Rayleigh's phase is even), as much as the view's span above the layer's top is opaque.
// `front`: the span in front of everything (the eye above the top, down to where the view
// meets the top or out to space); `behind`: behind the clouds (the eye under the top: the sky
// through their gaps), dimmed by the air in front.
struct AirAboveLayer {
  vec3 front, behind;
};

AirAboveLayer air_above_layer(Atmosphere atmo, vec3 eye, vec3 dir, vec3 gain) {
  float top = frame.radii_m.w;
  vec2 hit = ray_sphere(eye, dir, top);
  AirAboveLayer air = AirAboveLayer(vec3(0.0f), vec3(0.0f));
  vec3 to_space = transmittance_to_light(atmo, transmittance_lut, false, eye, dir);
  if (dot(eye, eye) > top * top) {
    // Down to the top: the air from there back to space over the eye's to space, reversed.
    vec3 span_t = to_space;
    if (hit.x > 0.0f)
      span_t = transmittance_to_light(atmo, transmittance_lut, false, eye + dir * hit.x, -dir) /
               max(transmittance_to_light(atmo, transmittance_lut, false, eye, -dir), vec3(1e-6f));
    air.front = 0.5f * gain * (1.0f - min(span_t, vec3(1.0f)));
  } else {
    // Out through the top: the air to it from the eye, less the air to space.
    vec3 exit_t = transmittance_to_light(atmo, transmittance_lut, false, eye + dir * hit.y, dir);
    air.behind = 0.5f * gain * max(to_space / max(exit_t, vec3(1e-6f)) - to_space, vec3(0.0f));
  }
  return air;
}

// What the translucent layers are blended over (layers_over): the light in front of the sky so
// far (premultiplied), its opacity and distance, and what blending a layer needs.
#define NEPHELE_LAYER_BLEND
struct LayerBlend {
  vec3 front;
  float alpha;
  float depth_m;
  vec2 sky_uv;         // the view's sky-view coordinates (the aerial perspective's)
  vec3 eye, dir;
  vec3 illuminance;    // the key light's
  float surface_m;     // the terrain or the host's geometry along the view; 0 for none
  float clouds_m;      // the volumetric clouds' opacity-weighted distance
  float clouds_diffuse;  // the media's light under the clouds (media_in_front)
};

// One translucent layer (premultiplied radiance and opacity at its distance layer_m) in depth
// order with the volumetric clouds: the air and the media in front of it dim its light and add
// their own as far as it covers, and it goes in front of the clouds or behind them (a layer
// of light alone, as the lightning's, hides nothing: a = 0). Hidden
// behind the surface. A loop of at most one trip, as the cirrus' below, whose cost only the
// variant without layers saves.
void blend_layer(vec4 layer, float layer_m, inout LayerBlend b) {
  for (int i = 0; i < (layer.a > 1e-4f || layer.r + layer.g + layer.b > 0.0f ? 1 : 0); ++i) {
    if (b.surface_m > 0.0f && layer_m > b.surface_m) break;  // behind the terrain
    vec4 air = air_in_front(b.sky_uv, layer_m);
    vec3 light = layer.rgb * air.a + air.rgb * b.illuminance * layer.a;
    if (WITH_MEDIA) {
      vec4 m = media_through_air(b.sky_uv, b.eye, b.dir, layer_m, b.clouds_diffuse);
      light = light * m.a + layer.a * m.rgb * b.illuminance;
    }
    bool in_front = b.alpha < 1e-3f || layer_m < b.clouds_m;
    b.front = in_front ? light + (1.0f - layer.a) * b.front : b.front + (1.0f - b.alpha) * light;
    b.depth_m = in_front ? layer_m : b.depth_m;
    b.alpha = 1.0f - (1.0f - b.alpha) * (1.0f - layer.a);
  }
}
// The translucent layers of the modules (their *_layer.glsl): layers_over (generated).
#include "layer_list_inc.glsl"

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  int width = frame.size.x;
  int height = frame.size.y;
  if (pixel.x >= width || pixel.y >= height) return;

  vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                        frame.camera_pos_m.w, frame.camera_forward.w, float(pixel.x),
                        float(pixel.y), float(width), float(height),
                        vec2(frame.camera_right.w, frame.camera_up.w));
  vec3 sun = frame.sun_dir.xyz;
  SkyViewFrame sky_frame = sky_view_frame_from(frame.sky_view_up, frame.sky_view_forward);
  vec2 uv = sky_view_uv(sky_frame, dir);
  bool above_horizon = uv.y >= 0.5f;
  vec3 sky;
  vec4 ground_sun;  // rgb: the ground's sun-lit radiance; a: the air's transmittance to it
  if (REFERENCE == 1) {
    sky = texelFetch(reference_sky, pixel, 0).rgb;
    ground_sun = texelFetch(reference_sky, ivec2(pixel.x, pixel.y + height), 0);
  } else {
    float rows = float(textureSize(sky_view_lut, 0).y / 2);
    sky = textureLod(sky_view_lut, sky_view_texcoord(uv, rows, 0.0f), 0.0f).rgb;
    ground_sun = above_horizon
                     ? vec4(0.0f)
                     : textureLod(sky_view_lut, sky_view_texcoord(uv, rows, 1.0f), 0.0f);
  }
  vec3 sky_table = sky;  // the air's light and the ground's sky-lit part, on the ground
  int conditions = WITH_CONDITIONS ? int(frame.conditions_sky.w) : 0;
  float albedo = frame.sky_model.y;
  float elevation_deg = degrees(asin(clamp(dot(dir, sky_frame.up), -1.0f, 1.0f)));
  if (conditions == 1) {  // artist: the keyframes' sky, and the ground lit by their lights
    sky = above_horizon ? frame.conditions_sky.rgb : albedo * frame_ground_sky();
    ground_sun = above_horizon ? vec4(0.0f)
                               : vec4(albedo / PI * max(dot(sky_frame.up, sun), 0.0f) *
                                          frame.conditions_light.rgb,
                                      1.0f);
  }
  if (conditions != 0 && above_horizon)
    sky = mix(sky, frame.conditions_sky_fog.rgb,
              fog_ramp(elevation_deg, frame.conditions_fog_deg.x, frame.conditions_fog_deg.y));
  vec4 cloud, cloud_b;
  cloud_at(pixel.x, pixel.y, cloud, cloud_b);
  float haze = cloud_b.x;
  // The haze's colour: the air's in-scattering between the eye and the cloud per unit of its
  // opacity (clouds.comp weights the haze by the air's opacity in front of each sample).
  vec4 ap = air_in_front(uv, cloud_b.z * 1000.0f);
  vec3 haze_color = ap.rgb / max(1.0f - ap.a, 1e-6f);
  float ground_shadow = cloud_b.y;  // cloud transmittance towards the sun
  // Under clouds the ground's sky light comes through the gaps and through the clouds
  // (cloud_ground_sky_share, ground_light.comp): an overcast's ground is a dim grey, not lit by
  // the clear blue sky, and a broken field's shadows keep the gaps' blue light. Off the
  // ground ground_sun.a is 0.
  // The clouds' light on the ground around (ground_light.comp): r their mean transmittance
  // down, gba the light they scatter down.
  vec4 ground_light_texel = texelFetch(ground_light, ivec2(0), 0);
  float sky_share = cloud_ground_sky_share(ground_shadow, ground_light_texel.r);
  // A medium above the ground (a fog) dims the sun's and the sky's light on it as well.
  // The ground along the view, 0 for none.
  float ground_m = max(ray_sphere(frame.camera_pos_m.xyz, dir, frame.radii_m.x).x, 0.0f);
  vec2 ground_media = WITH_MEDIA && ground_m > 0.0f
                          ? media_surface_light(frame.camera_pos_m.xyz + dir * ground_m)
                          : vec2(1.0f);
  // The ground's sky light under a clear sky, and as much of it as comes through the clouds
  // and a fog over the ground.
  vec3 white_sky = frame_ground_sky();
  vec3 ground_sky_clear = ground_sun.a * albedo * white_sky;
  vec3 ground_sky = ground_sky_clear * sky_share * ground_media.y;
  sky = max(sky - ground_sky_clear + ground_sky, 0.0f);
  // And the sunlight the clouds around scatter down onto it (ground_light.comp), shared with the
  // diffuse light of the cloud towards the sun (cloud_ground_light_shares).
  vec3 clouds_down = ground_light_texel.gba;
  vec2 shares = cloud_ground_light_shares(
      ground_shadow, frame.cloud_droplets.w,
      clouds_down);
  vec3 ground_clouds = ground_sun.a * ground_media.y * albedo * clouds_down * shares.y;
  sky += ground_clouds;
  ground_sun.rgb *= ground_media.x;
  // The planet hides the part of the sun's disk below the horizon.
  vec3 sun_light = above_horizon
                       ? frame.sun_transmittance.rgb * sun_disk(dir, sun, frame.sun_dir.w)
                       : vec3(0.0f);
  vec3 moon_light = above_horizon ? frame.moon_radiance.rgb * moon_disk(dir) : vec3(0.0f);
  vec3 discs = sun_light + moon_light;
  if (conditions != 0 && max(discs.r, max(discs.g, discs.b)) > 0.0f)  // dissolve into the sky
    discs = mix(discs, frame.conditions_disk_fog.rgb,
                fog_ramp(elevation_deg, frame.conditions_fog_deg.z, frame.conditions_fog_deg.w));
  vec3 background = sky + ground_sun.rgb * shares.x + discs;
  // The ground around's light over the clear ground's, the sun's share taken as the clouds'
  // mean transmittance down; and a white ground's clear light.
  vec3 white_sun = frame_ground_sun(sky_frame.up);
  vec3 ground_ratio = cloud_ground_light_ratio(ground_light_texel.r, ground_light_texel.r,
                                               clouds_down, white_sun, white_sky);
  // Under the clouds' base the air is lit as the ground around is (cloud_ground_light_ratio,
  // the sun's share taken as the clouds' mean transmittance): the aerial perspective's clear
  // light is kept by that share there, in front of the sky, the ground and the clouds alike.
  // The volumetric shafts shadow the air's sunlight themselves.
  vec3 air_kept = vec3(1.0f);
  AirBelowBase below_base = AirBelowBase(vec2(0.0f), vec3(0.0f), vec3(0.0f));
  if (!(WITH_SHAFTS && int(frame.light_shafts.x) == LIGHT_SHAFTS_VOLUMETRIC) && REFERENCE == 0 &&
      conditions != 1) {
    air_kept = min(ground_ratio, vec3(1.0f));
    below_base = air_below_base(uv, frame.camera_pos_m.xyz, dir, ground_m,
                                max(sky_table - ground_sky_clear, 0.0f));
    background -= (1.0f - air_kept) * max(below_base.far - below_base.near, vec3(0.0f));
  }
  // The air above the clouds' layer, lit by it from below.
  AirAboveLayer above_layer = AirAboveLayer(vec3(0.0f), vec3(0.0f));
  if (REFERENCE == 0 && conditions != 1) {
    vec4 from_above = texelFetch(ground_light, ivec2(1, 0), 0);
    vec3 gain =
        cloud_layer_gain(from_above.gba, from_above.r, ground_ratio, white_sun + white_sky, albedo);
    above_layer = air_above_layer(frame_atmosphere(), frame.camera_pos_m.xyz, dir, gain);
    background += above_layer.behind;
  }
  // Volumetric light shafts (light_shafts.comp, an eighth of the resolution): the air's light
  // dimmed by the share of it the clouds' shadows take from the sun, along the whole ray
  // behind the clouds (the sky seen through them; the ground's light keeps its own shadowing)
  // and in front of them (the haze).
  float haze_kept = 1.0f;
  vec4 shaft = vec4(0.0f);
  if (WITH_SHAFTS && int(frame.light_shafts.x) == LIGHT_SHAFTS_VOLUMETRIC && REFERENCE == 0 &&
      conditions != 1) {
    shaft = textureLod(light_shafts, (vec2(pixel) + 0.5f) / vec2(width, height), 0.0f);
    // The air's light alone: the ground's light from the sky and the clouds left out.
    vec3 air = max(sky - ground_sky - ground_clouds, vec3(0.0f));
    background -= air * shaft.rgb;
    haze_kept = 1.0f - shaft.a;
  }
  // The terrain (terrain.comp) in place of the sky and the ground behind it, seen through the
  // air in front (the aerial perspective at its distance, its sunlight dimmed by the shafts'
  // share); clouds whose light lies mostly beyond it are hidden.
  float terrain_m =
      WITH_SURFACES ? terrain_distance_at((vec2(pixel) + 0.5f) / vec2(width, height)) : 0.0f;
  for (int i = 0; i < (terrain_m > 0.0f ? 1 : 0); ++i) {  // a loop: see the cirrus' below
    vec4 air = air_in_front(uv, terrain_m);
    vec3 lit = layer_texel(LAYER_SURFACES, pixel).rgb;
    background = lit * air.a + air.rgb * (1.0f - shaft.rgb) -
                 (1.0f - air_kept) * air_below_base_before(below_base, terrain_m, air.rgb);
    if (cloud_b.z * 1000.0f > terrain_m) {
      cloud = vec4(0.0f, 0.0f, 0.0f, 1.0f);
      haze = 0.0f;
    }
  }
  if (conditions == 1) haze = 0.0f;  // the keyframes' fog stands for the aerial perspective
  vec3 illuminance = frame.sun_illuminance.rgb;
  // The air in front of a cloud scatters as the sky does along this direction.
  vec3 haze_below =
      air_below_base_before(below_base, cloud_b.z * 1000.0f, ap.rgb) / max(ap.rgb, vec3(1e-20f));
  vec3 cloud_light =
      haze_color * haze * haze_kept * (1.0f - (1.0f - air_kept) * min(haze_below, vec3(1.0f))) *
          illuminance +
      cloud.rgb;
  // The surface along the view: the terrain or the host's scene, else the ground; 0 for none.
  float surface_m = terrain_m > 0.0f
                        ? terrain_m
                        : ground_m;
  // The cirrus sheet: seen from below, over the sky and the discs and behind the volumetric
  // clouds, its light dimmed by the air in front and the air's own light kept; from above,
  // in front of everything.
  // Lavapipe runs both sides of a branch, and a loop's body once even when no lane takes a
  // trip (measured: four lookups in a loop no lane entered cost compose 38%): only the
  // variant without cirrus (WITH_CIRRUS false) saves a sky without it the lookups.
  vec3 eye = frame.camera_pos_m.xyz;
  // The share of the light that reaches the media under the clouds: their mean diffuse
  // transmittance to the ground around, and where the view meets the ground, at least the
  // clouds' transmittance to the sun there, so that a fog sea shows the clouds' shadows and is
  // sunlit in their gaps (the ground's shadow stands for the fog's above it).
  float clouds_diffuse = ground_light_texel.r;
  if (ground_m > 0.0f) clouds_diffuse = max(clouds_diffuse, ground_shadow);
  // The media (fog) in front of the clouds: the clouds' light through them, and their own light
  // as far as the clouds cover (premultiplied).
  if (WITH_MEDIA && cloud.a < 1.0f) {
    vec4 m = media_through_air(uv, eye, dir, cloud_b.z * 1000.0f, clouds_diffuse);
    cloud_light = cloud_light * m.a + (1.0f - cloud.a) * m.rgb * illuminance;
  }
  float cirrus_m = WITH_CIRRUS ? cirrus_distance(eye, dir) : 0.0f;
  vec4 cirrus = vec4(0.0f, 0.0f, 0.0f, 1.0f);
  bool cirrus_in_front = WITH_CIRRUS && length(eye) > frame.cirrus.x;
  if (terrain_m > 0.0f && cirrus_m > terrain_m) cirrus_m = 0.0f;  // behind the terrain
  for (int i = 0; i < (cirrus_m > 0.0f ? 1 : 0); ++i) {
    cirrus = cirrus_layer(frame_atmosphere(), eye, dir, cirrus_m);
    if (cirrus_in_front || conditions == 1) continue;
    vec4 air = air_in_front(uv, cirrus_m);
    background = background * cirrus.a + (1.0f - cirrus.a) * air.rgb + cirrus.rgb * air.a;
  }
  // The media in front of the surface (the terrain, the host's scene or the ground), else in
  // front of the sky.
  if (WITH_MEDIA) {
    vec4 m = media_through_air(uv, eye, dir, surface_m, clouds_diffuse);
    background = background * m.a + m.rgb;
  }
  // The film layers (dispatch.values.x, render --layers): everything behind the clouds (sky,
  // sun, moon, the ground and the cirrus seen from below), and what lies in front of it,
  // premultiplied: the clouds' light with the haze in front of them, and the cirrus seen from
  // above over both; alpha = 1 - their transmittance. The image is their "over": exactly
  // front + (1 - alpha) sky.
  vec3 sky_layer = background * illuminance;
  vec3 front = cloud_light + above_layer.front * illuminance;
  float alpha = 1.0f - cloud.a;
  // The clouds' opacity-weighted distance (clouds.comp), where they are not clear; 0 elsewhere.
  float depth_m = cloud.a < 0.999f ? cloud_b.z * 1000.0f : 0.0f;
  // The translucent layers (the particle clouds, particles.vert) in depth order with the
  // volumetric clouds: both premultiplied, the nearer over the farther, at their
  // opacity-weighted distances (blend_layer).
  if (WITH_LAYERS) {
    LayerBlend blend = LayerBlend(front, alpha, depth_m, uv, eye, dir, illuminance, terrain_m,
                                  cloud_b.z * 1000.0f, clouds_diffuse);
    layers_over((vec2(pixel) + 0.5f) / vec2(width, height), blend);
    front = blend.front;
    alpha = blend.alpha;
    depth_m = blend.depth_m;
  }
  if (cirrus_in_front) {
    front = front * cirrus.a + cirrus.rgb * illuminance;
    alpha = 1.0f - (1.0f - alpha) * cirrus.a;  // over the clouds and the layers
  }
  vec3 color = front + (1.0f - alpha) * sky_layer;
  int layer = dispatch.values.x;
  vec4 out_value = layer == 1   ? vec4(sky_layer, 1.0f)
                   : layer == 2 ? vec4(front, alpha)
                   : layer == 3 ? vec4(depth_m, depth_m, depth_m, 1.0f)
                                : vec4(color, 1.0f);
  imageStore(color_out, pixel, out_value);
}

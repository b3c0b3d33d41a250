#version 450
// Pass 3: clouds. Per pixel, march the view ray through the cloud shell between two spheres
// (seed 000, 2.2) compositing front to back (formulas 1.5, 1.6) with Beer-Lambert attenuation,
// a light march towards the sun, the clouds' phase function (cloud_phase_function), the
// powder term and ambient light (1.4, listings B.1-B.3). Writes one texel per marched pixel to march_a (rgb in-scattered
// radiance attenuated by the air between the eye and each sample, a = cloud transmittance) and
// march_b (x haze weight: the share of the cloud's light replaced by the air's in-scattering,
// y ground shadow, z cloud distance (km), w 1 sample).
//
// MARCH_MODE (specialization constant) selects the variant:
//   0 default:  distance-adaptive coarse and fine steps with per-pixel jitter, a light march
//               over the first light-volume voxel and the rest looked up, multiple-scattering
//               octaves, early exit at T < 0.01.
//   1 baseline: the seed's algorithm as written: fixed step (layer thickness / 64), at most 128
//               steps, 4-sample light march (3 short steps and one 6x), colour extinction
//               (0.8, 0.8, 1.0), no jitter, no skipping.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"

layout(constant_id = 0) const int MARCH_MODE = 0;
// The scene's features (CloudsModule::march_variant): WITH_VOXELS false compiles the voxel
// clouds' code out (lavapipe runs both sides of every branch); LIGHTING 0 the octaves, 1 the
// two-stream light, 2 the diffusion field (cloud_diffusion_inc.glsl; only with a light volume:
// the two-stream light beyond its grids takes its depth behind a sample from the volume
// alone), -1 as frame.cloud_phase.w says; WITH_FLOW false the flow map's reads.
layout(constant_id = 1) const bool WITH_VOXELS = true;
layout(constant_id = 2) const int LIGHTING = -1;
layout(constant_id = 3) const bool WITH_FLOW = true;
#define CLOUD_FIELD_VARIANTS
#define DEPTH_BEHIND_MAY_MARCH (LIGHTING != 2)
layout(local_size_x = 8, local_size_y = 8) in;

#include "cloud_field_inc.glsl"
#include "render/modules/cloud_diffusion/cloud_diffusion_inc.glsl"
#include "entering_inc.glsl"
#include "dispatch_inc.glsl"
#include "cirrus_inc.glsl"
#include "air_inc.glsl"
#include "terrain_inc.glsl"
#include "frame_atmosphere_inc.glsl"

const float COARSE_STEPS = 6.0f;    // a coarse step is this many fine steps
const float FINE_PER_M = 0.0025f;   // fine steps grow to this fraction of the distance
// Near the base shape a coarse step is at most the distance to it were the shape noise to rise
// by 1 over this many metres (noise_shape_margin, noise_density_inc.glsl), rounded down to 1,
// 2 or 4 fine steps: a few lengths, so that a ray and one a rounding error away (a tile's)
// take the same steps unless the margin lies on a boundary between two of them.
const float SHAPE_NOISE_M = 3000.0f;
const float TAU_STEP_96 = 0.5f;     // optical depth per step in dense cloud at 96 primary steps

// Cloud shadow on the ground where this ray hits it (cloud_shadow_at), 1 where it misses the
// ground. `ground` is ray_sphere(eye, dir, planet radius).
float ground_shadow(vec3 eye, vec3 dir, vec3 sun, vec2 ground) {
  if (ground.x <= 0.0f) return 1.0f;
  return cloud_shadow_at(normalize(eye + dir * ground.x) * (frame.radii_m.x + 1.0f), sun, ground.x, 16);
}

// Writes the marched sample of `block` (see bindings_inc.glsl).
void write_sample(ivec2 block, vec3 scattered, float transmittance, float haze, float shadow,
                  float distance_m) {
  imageStore(march_a_out, block, vec4(scattered, transmittance));
  imageStore(march_b_out, block, vec4(haze, shadow, distance_m * 1e-3f, 1.0f));
}

// One thread per stride x stride block of the cloud buffer: it marches the block's pixel
// frame.march_offset.xy (every pixel when the stride is 1).
void main() {
  int stride = frame.cloud_grid.z;
  int blocks_x = (frame.cloud_grid.x + stride - 1) / stride;
  ivec2 block = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, dispatch.values.x);
  ivec2 pixel = block * stride + frame.march_offset.xy;
  int width = frame.cloud_grid.x;
  int height = frame.cloud_grid.y;
  if (dispatch.values.y > 0) {
    // A strip the previous frame did not see (entering_inc.glsl), every other pixel, the
    // samples in a row of 8 invocations after another so that a narrow strip fills the
    // workgroups.
    int k = dispatch.values.y - 1;
    ivec4 strip = entering_strip(k);
    int columns = (strip.z + 1) / 2;
    int n = int(gl_GlobalInvocationID.y) * 8 + int(gl_GlobalInvocationID.x);
    ivec2 i = ivec2(n % max(columns, 1), n / max(columns, 1));
    if (gl_GlobalInvocationID.x >= 8u || any(greaterThanEqual(2 * i, strip.zw))) return;
    pixel = strip.xy + 2 * i;
    block = entering_storage(k) + i;
    if (pixel.x >= width || pixel.y >= height) return;
  } else if (block.x >= blocks_x || pixel.x >= width || pixel.y >= height) {
    return;
  }

  vec3 eye = frame.camera_pos_m.xyz;
  vec3 dir = frame.steps.w == PROJECTION_SKY_DOME
                 ? sky_dome_ray(normalize(eye), float(pixel.x), float(pixel.y), float(width),
                                float(height))
                 : camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz,
                              frame.camera_up.xyz, frame.camera_pos_m.w, frame.camera_forward.w,
                              float(pixel.x), float(pixel.y), float(width), float(height),
                        vec2(frame.camera_right.w, frame.camera_up.w));
  vec3 sun = frame.sun_dir.xyz;
  float mu = dot(dir, sun);
  vec2 ground = ray_sphere(eye, dir, frame.radii_m.x);
  vec2 segment = shell_segment(eye, dir, ground);
  // Without noise clouds only the voxel clouds' boxes hold anything, and the march spans just
  // them: a lab's grid, or voxel clouds in a clear sky, make a thin shell that a ray along it
  // crosses for kilometres.
  bool noise_clouds = false;
  for (int k = 0; k < CLOUD_LAYERS; ++k)
    noise_clouds = noise_clouds || frame.cloud_layers[k].shape.x > 0.0f || frame.cloud_layers[k].shape.w > 0.0f;
  if (WITH_VOXELS && frame.voxel_info.x > 0 && !noise_clouds) {
    vec2 boxes = voxel_boxes_segment(eye, dir);
    segment = vec2(max(segment.x, boxes.x), min(segment.y, boxes.y));
  }
  // The terrain hides what lies behind it (terrain.comp, at the image's resolution: the pixel
  // under this sample's centre); the sky dome is an observer's sky and sees past it.
  float terrain_m = frame.steps.w == PROJECTION_SKY_DOME
                        ? 0.0f
                        : terrain_distance_at((vec2(pixel) + 0.5f) / vec2(width, height));
  if (terrain_m > 0.0f) segment.y = min(segment.y, terrain_m);
  float surface_m = terrain_m > 0.0f ? terrain_m : ground.x;
  float shadow = ground_shadow(eye, dir, sun, ground);
  // The sky dome counts cloud of any kind as an observer does: a visible cirrus sheet
  // (vertical optical depth 0.03 or more) covers its direction as thick cloud does.
  float cirrus_m = frame.steps.w == PROJECTION_SKY_DOME ? cirrus_distance(eye, dir) : 0.0f;
  bool cirrus_covers = cirrus_m > 0.0f && cirrus_optical_depth(eye + dir * cirrus_m) >= 0.03f;
  if (segment.y <= segment.x) {
    write_sample(block, vec3(0.0f), cirrus_covers ? 0.0f : 1.0f, 0.0f, shadow,
                 surface_m > 0.0f ? surface_m : FAR_M);
    return;
  }
  float eye_alt_m = length(eye) - frame.radii_m.x;
  float haze = 0.0f;

  float sigma_scale = frame.cloud_shape.z;  // sigma_t (1/m) at density field 1
  float view_atten = frame.cloud_light.x;
  float light_atten = frame.cloud_light.y;
  float powder = frame.cloud_light.z;
  float albedo = frame.cloud_shape.w;
  vec3 sun_light = frame.sun_at_clouds.rgb;
  // Ambient light from above (the sky) at the tops, from below (the ground) at the bases.
  vec3 ambient_above = frame.ambient_at_clouds.rgb * frame.cloud_light.w;
  vec3 ambient_below = frame.ambient_below_clouds.rgb * frame.cloud_light.w;
  vec3 ambient = 0.5f * (ambient_above + ambient_below);
  // The ground light's share under the clouds, once per ray: where it enters the clouds.
  vec3 entry = eye + dir * segment.x;
  float below_share = WITH_VOXELS && frame.voxel_info.x > 0 ? -1.0f : below_light_share(entry, length(entry) - frame.radii_m.x);
  // The ground's light under the clouds around (ground_light.comp), per unit of the key light:
  // the clear ground's is the sun's and the sky's (cloud_ground_light_ratio).
  vec4 ground_light_texel = texelFetch(ground_light, ivec2(0), 0);
  vec3 sun_ground = frame_ground_sun(normalize(entry));
  vec3 sky_ground = frame_ground_sky();
  vec3 below = cloud_ground_light_ratio(max(below_share, 0.0f), ground_light_texel.r,
                                        ground_light_texel.gba, sun_ground, sky_ground);
  float thickness = frame.radii_m.w - frame.radii_m.z;
  vec4 phases = octave_phases(mu);
  int light_model = LIGHTING < 0 ? int(frame.cloud_phase.w + 0.5f) : LIGHTING;
  bool two_stream = light_model >= 1;  // the diffusion field's, where it does not cover a sample
  float g1 = frame.cloud_droplets.z;  // the phase function's mean cosine

  vec3 scattered = vec3(0.0f);
  vec3 transmittance = vec3(1.0f);
  float weighted_t = 0.0f;  // sum of t x opacity gained there: the cloud's mean distance

  if (MARCH_MODE == 1) {
    // Seed listing B.3: fixed steps from the entry point, stop on leaving the layer.
    float step_m = thickness / 64.0f;
    float phase = cloud_phase_function(mu, 1.0f);
    for (int i = 0; i < 128; ++i) {
      float t = segment.x + float(i) * step_m;
      if (t > segment.y) break;
      vec3 pos = eye + dir * t;
      float density = cloud_density(pos, true);
      if (density > 0.01f) {
        vec3 tau_light = seed_light_optical_depth(pos, sun) * sigma_scale * light_atten *
                         SEED_EXTINCTION_MULT;
        vec3 beer = exp(-tau_light) * phase;
        vec3 powder_term = 1.0f - exp(-2.0f * tau_light);
        vec3 energy = beer * mix(2.0f * powder_term, vec3(1.0f), remap(mu, -1.0f, 1.0f, 0.0f, 1.0f));
        energy = mix(exp(-tau_light) * phase, energy, powder);
        vec3 luminance = albedo * (ambient + sun_light * energy);
        vec3 step_t = exp(-density * step_m * sigma_scale * view_atten * SEED_EXTINCTION_MULT);
        vec3 air = air_transmittance(eye_alt_m, length(pos) - frame.radii_m.x, t);
        scattered += transmittance * air * luminance * (1.0f - step_t);
        haze += transmittance.g * (1.0f - air.g) * (1.0f - step_t.g);
        weighted_t += t * transmittance.g * (1.0f - step_t.g);
        transmittance *= step_t;
        if (length(transmittance) <= 0.01f) {
          transmittance = vec3(0.0f);
          break;
        }
      }
    }
  } else {
    // Adaptive steps (seed 002): empty space is crossed in coarse steps that test only the
    // base shape; on a hit the march steps back one coarse step and goes on in fine steps
    // testing the full density, shortened to half a mean free path in dense cloud, so lighting
    // is sampled where the cloud's surface really is; after six empty fine samples past the
    // hit it returns to coarse steps. Both step sizes grow with distance so far rays stay
    // affordable; the start is jittered per pixel and frame so the step pattern becomes fine
    // noise that the temporal resolve averages away.
    //
    // Each iteration evaluates the density field once: at the next point of the view ray, or
    // at the next point of the light march of the sample being lit (light_k > 0). A SIMD
    // device that executes every branch for all its lanes (lavapipe) then pays one density
    // per iteration instead of a primary and a whole light march, and the lanes of a batch
    // stay busy whether their rays cross empty sky or cloud.
    float fine_base = layer_thickness_m(eye + dir * segment.x) / float(frame.steps.x);
    // A new jitter pattern per frame index (Jimenez 2014: offset the pixel by 5.588238 per frame).
    float shift = 5.588238f * float(frame.march_offset.z);
    // In the whole image's pixels: a tile's pattern continues its neighbours' (output_image.zw).
    vec2 image_pixel = vec2(pixel) + frame.output_image.zw;
    float jitter = interleaved_gradient_noise(image_pixel.x + shift, image_pixel.y + shift);
    float t = segment.x + COARSE_STEPS * max(fine_base, FINE_PER_M * segment.x) * jitter;
    bool fine = false;
    int misses = 0;
    float fine_until = 0.0f;  // stay fine at least past the coarse sample that hit
    float sampled_until = segment.x;  // fine steps have sampled the ray up to here
    int primary = 0;          // view-ray iterations so far
    int light_n = frame.steps.y;
    int light_k = 0;          // 0: next view-ray point; k > 0: light march step k of the sample
    vec3 lit_pos = eye;       // the sample being lit, its sigma_t, step and the light march
    float lit_sigma_t = 0.0f, lit_step_m = 0.0f, lit_unit_m = 0.0f, lit_near_m = 0.0f;
    float lit_depth = 0.0f;   // optical depth gathered so far (density field x m)
    bool lit_volume = false;  // look the rest up in the light volume
    bool lit_doubling = false;  // the light march's steps double (else grow linearly)
    int budget = 4 * frame.steps.x * (light_n + 1);
    // Voxel clouds (seed 002, New Three-Phases Raymarching): phase 1 the adaptive steps above
    // in the noise clouds; phase 2, in a voxel cloud's box (where the noise clouds have faded
    // out) but outside the cloud, sphere tracing through its signed distance field, at least
    // voxel_min_step_m a step near surfaces and box edges, never past the box's exit; phase 3,
    // inside the cloud, the fine steps, entered by stepping back. Leaving the cloud inside the
    // box returns to sphere tracing at once, leaving the box to phase 1.
    bool three_phase = WITH_VOXELS && frame.voxel_info.x > 0 && frame.voxel_info.y == VOXEL_MARCH_THREE_PHASE;
    bool sdf_shadow = WITH_VOXELS && frame.voxel_info.x > 0 && frame.voxel_info.z == VOXEL_SHADOW_SDF_CONE;
    float skipped_m = 1e30f;   // the last coarse (or sphere-traced, phase 2) view-ray step
    int slow = 0;              // phase 2 steps in a row at the shortest step (voxel_min_step_m)
    float lit_visibility = 1.0f;  // the SDF cone's soft shadow of the sample being lit
    for (int i = 0; i < budget && t < segment.y && transmittance.x >= 0.01f; ++i) {
      bool lighting = light_k > 0;
      // Light march steps grow linearly (step k is k units long and starts k (k - 1) / 2 units
      // in) or, across a voxel region, geometrically (2^(k-1) units, starting 2^(k-1) - 1 in).
      float seg_m = lit_unit_m * (lit_doubling ? exp2(float(light_k - 1)) : float(light_k));
      float mid_m = lit_unit_m * (lit_doubling ? exp2(float(light_k - 1)) - 1.0f
                                               : 0.5f * float(light_k * (light_k - 1))) + 0.5f * seg_m;
      vec3 pos = lighting ? lit_pos + sun * mid_m : eye + dir * t;
      VoxelSample vox = VoxelSample(0.0f, 1e9f, 1e9f, 1.0f, 0);
      vec2 field = cloud_field(pos, vox);
      bool in_region = WITH_VOXELS && vox.region_m <= 0.0f;
      // Fine steps from the thickness of the layer the ray is in.
      float fine_step = max(layer_thickness_m(pos) / float(frame.steps.x), FINE_PER_M * t);
      float coarse_step = COARSE_STEPS * fine_step;

      if (lighting) {
        lit_depth += field.y * seg_m;
        if (light_k < light_n) {
          ++light_k;
          continue;
        }
      } else {
        if (++primary > 4 * frame.steps.x) break;
        bool tracing = three_phase && in_region;
        if (!fine) {
          if (field.x <= 0.0f) {
            // Shorter near the base shape, at least a fine step (SHAPE_NOISE_M).
            float fine_steps = -noise_shape_margin * SHAPE_NOISE_M / fine_step;
            skipped_m = fine_steps >= COARSE_STEPS ? coarse_step
                                                   : fine_step * exp2(floor(log2(clamp(fine_steps, 1.0f, 4.0f))));
            if (tracing) {  // phase 2
              float min_step = voxel_min_step_m(fine_step, coarse_step, slow);
              slow = vox.sdf_m - vox.voxel_m < min_step ? slow + 1 : 0;
              skipped_m = min(voxel_sphere_step(vox.sdf_m, vox.voxel_m, min_step),
                              voxel_region_exit_m(pos, dir) + 0.5f * fine_step);
            }
            t += skipped_m;
            continue;
          }
          fine = true;
          misses = 0;
          fine_until = t;
          // Step back over what the last coarse (or sphere-traced) step skipped, not into what
          // fine steps have sampled: where the base shape fills space that erosion has emptied
          // (a deck's thin base seen at a grazing angle) the march would otherwise crawl one
          // fine step per return.
          t = max(t - skipped_m, sampled_until);
          skipped_m = coarse_step;
          continue;
        }
        sampled_until = t;
        if (field.y <= 0.0f) {
          // Out of a voxel cloud, in its box, past the sample that found it: sphere tracing
          // again (phase 3 to 2).
          bool left = tracing && vox.sdf_m > vox.voxel_m;
          if ((++misses >= 6 || left) && t > fine_until) fine = false;
          t += fine_step;
          continue;
        }
        misses = 0;
        // Light this sample in the next light_n iterations: march the first voxel of the light
        // volume towards the sun (where it is too coarse for the light's fast change at a cloud's
        // surface) and look the rest up where that march ends; without the volume, march all.
        // In a voxel region with SDF shadows: a cone traced through the cloud's distance field
        // to its box's edge, and the light volume from there, at once.
        float sigma_t = field.y * sigma_scale * view_atten;
        // At most TAU_STEP_96 * 96 / primary_steps of optical depth per step (0.5 at 96 steps).
        lit_step_m = clamp(TAU_STEP_96 * 96.0f / (float(frame.steps.x) * sigma_t), 1.0f, fine_step);
        lit_sigma_t = sigma_t;
        lit_pos = pos;
        lit_visibility = 1.0f;
        if (sdf_shadow && in_region) {  // shaded below, in this iteration
          // Opaque at an optical depth of 100 along the light: the diffuse light through the
          // cloud, 1 / (1 + 0.11 tau), still counts at 40.
          vec4 cone = sdf_cone_trace(pos, sun, vox.cloud, 100.0f / (sigma_scale * light_atten), field.y);
          lit_depth = cone.x;
          lit_visibility = cone.y;
          // The light volume from where the cone ended: inside the box, the rest of the cloud
          // from its coarse voxels; past the box, from a voxel beyond it (see below), what lies
          // between being the noise clouds' fade, nearly empty.
          lit_near_m = cone.z + cone.w * light_volume_voxel_at(pos);
          lit_volume = light_volume_covers(pos + sun * lit_near_m);
        } else {
          float length_m = light_ray_length(pos, sun);
          lit_volume = light_volume_covers(pos);
          lit_near_m = lit_volume ? min(light_volume_voxel_at(pos), length_m) : length_m;
          // In a voxel region, across the region and one of the light volume's voxels beyond:
          // the volume is too coarse for a voxel cloud's sharp shapes (its trilinear voxels, which
          // straddle the region's edge, would draw facets on them).
          if (in_region)
            lit_near_m = min(max(lit_near_m, voxel_region_exit_m(pos, sun) + light_volume_voxel_at(pos)),
                             length_m);
          lit_volume = lit_volume && lit_near_m < length_m;
          // A voxel cloud's light changes fastest just inside its sharp surface, and the march
          // crosses its whole region: doubling steps put the first short step there (linear
          // ones left a 6-step baseline 6.5% darker than a converged march, doubling 2%); the
          // noise clouds' soft edges and one light-volume voxel keep the linear steps.
          lit_doubling = in_region;
          lit_unit_m = lit_near_m / (lit_doubling ? exp2(float(light_n)) - 1.0f
                                                  : float(light_n * (light_n + 1) / 2));
          lit_depth = 0.0f;
          light_k = 1;
          continue;
        }
      }
      // The sample's light is known (its light march done, or its SDF cone traced in this
      // iteration): shade it and step on along the view ray.
      light_k = 0;
      float depth = lit_depth + (lit_volume ? light_volume_lookup(lit_pos + sun * lit_near_m) : 0.0f);
      float tau_light = depth * sigma_scale * light_atten;
      // The sun's light the sample scatters towards the eye (cloud_light: the diffusion
      // light's field where it covers the sample, else cloud_sun_light).
      vec3 sunlit = cloud_light(light_model == 2, lit_pos, dir, sun, tau_light,
                                sigma_scale * light_atten, mu, two_stream, phases, powder, albedo, g1);
      float energy = sunlit.x * lit_visibility;
      // A voxel cloud may reach above or below the layers: the ground light weighs 0 to 1.
      float h = saturate(layer_fraction(lit_pos));
      // With voxel clouds, where the ray first meets cloud: the shell's entry may lie far
      // from a voxel cloud, and the light volume's voxels there would draw facets on it.
      if (below_share < 0.0f) {
        below_share = below_light_share(lit_pos, length(lit_pos) - frame.radii_m.x);
        below = cloud_ground_light_ratio(below_share, ground_light_texel.r, ground_light_texel.gba,
                                         sun_ground, sky_ground);
      }
      // What the cloud between the sample and the light lets through: the sunlight it has
      // scattered forward, no longer a beam but a diffuse flux, and the sky's light through
      // the same cloud; from below, the light of the ground around, itself under the
      // clouds' shadow, less the higher the sample is in the layer.
      float diffuse = sunlit.y, t_d = sunlit.z;
      vec3 luminance = albedo * (sun_light * (energy + diffuse) + ambient_above * t_d +
                                 ambient_below * below * (1.0f - h));
      float step_t = exp(-lit_sigma_t * lit_step_m);
      vec3 air = air_transmittance(eye_alt_m, length(lit_pos) - frame.radii_m.x, t);
      // Energy-conserving integration over the step (Hillaire 2016).
      scattered += transmittance * air * luminance * (1.0f - step_t);
      haze += transmittance.x * (1.0f - air.g) * (1.0f - step_t);
      weighted_t += t * transmittance.x * (1.0f - step_t);
      transmittance *= step_t;
      t += lit_step_m;
    }
    if (transmittance.x < 0.01f) transmittance = vec3(0.0f);
  }
  float t_mean = (transmittance.r + transmittance.g + transmittance.b) / 3.0f;
  if (cirrus_covers) t_mean = 0.0f;
  float opacity = 1.0f - (MARCH_MODE == 1 ? transmittance.g : transmittance.x);
  // Where the pixel's content is, for reprojection: the cloud's opacity-weighted distance,
  // else the terrain or the ground, else the middle of the cloud shell along the ray.
  float empty_m = surface_m > 0.0f ? surface_m : 0.5f * (segment.x + segment.y);
  float distance_m = opacity > 1e-3f ? weighted_t / opacity : empty_m;
  write_sample(block, scattered, t_mean, haze, shadow, distance_m);
}

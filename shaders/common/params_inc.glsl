// The one definition of every GPU struct, included by GLSL and by C++ (src/render/gpu_params.h).
// Every member is a vec4, ivec4 or mat4, so std140 and std430 layouts equal the C++ layout
// (static_asserts on size in C++). Lengths in metres in a planet-centred frame: origin at the
// planet centre, +z through the ground point below the start position, x east, y north there.
#ifndef NEPHELE_PARAMS_INC
#define NEPHELE_PARAMS_INC

#include "common/push_constants_inc.glsl"

#ifdef __cplusplus
namespace nephele::gpu {
using glm::ivec4;
using glm::mat4;
using glm::vec4;
#endif

const int LIGHT_VOLUME_XY = 160;  // light volume voxels per horizontal axis
const int LIGHT_VOLUME_Z = 32;    // light volume voxels across the cloud layer
// The light volume is built from the top down in groups of this many layers, each reading the
// layer this far above it (light_volume.comp). A group of 4 or 8 resampled the depths 7 or 3
// times on their way down, which blurred the shadows (the suite's storm 17.9 -> 21.3 or 18.4%
// off the path tracer, with Catmull-Rom 19.2 or 18.4; 16: 17.7).
const int LIGHT_VOLUME_LAYERS_UP = 16;

// The volumetric cloud layers (render/frame_params.cpp fills them): 0 the main layer (clouds),
// then high_clouds when it is there and the [[cloud_layers]] that are, in the slots from 1 on.
// Their clouds never overlap; the clouds pass marches one shell from the lowest bottom to the
// highest top (FrameParams::radii_m.zw) and takes each sample's layer by its band.
const int CLOUD_LAYERS = 6;  // clouds, high_clouds, [[cloud_layers]] (kMaxCloudLayers)

// The image layers compose blends over the clouds (render/image_layers.h; the bindings layers
// and layers_out): one 2D array at the frame's size, RGBA 32-bit float, a layer each.
// LAYER_SURFACES: the terrain or the host's geometry nearer (terrain.comp, host_scene.comp),
// rgb its radiance per unit key-light illuminance before the air in front, a its distance (m;
// 0 where the ray meets none). LAYER_PARTICLES: the particle clouds, rgb premultiplied
// radiance, a opacity; LAYER_PARTICLE_DEPTH: x their opacity-weighted distance (km) times the
// opacity; both drawn into the top-left particle_light.yz share of the layer.
// LAYER_PRECIPITATION: the rain and snow particles near the camera (precipitation_particles.vert),
// a their opacity, r their distance (km) times it.
const int LAYER_SURFACES = 0;
const int LAYER_PARTICLES = 1;
const int LAYER_PARTICLE_DEPTH = 2;
const int LAYER_PRECIPITATION = 3;
const int IMAGE_LAYERS = 4;

struct CloudLayerGpu {
  vec4 radii_m;  // x bottom, y top radius (m, planet frame; a layer that is off lies beyond
                 // the atmosphere); zw where it reads the weather map (offset, in tiles)
  vec4 shape;    // x coverage [0, 1], y density [0, 1], z type [0, 1], w precipitation [0, 1]
  vec4 wind;     // xy its displacement by the wind (wind x time, m); zw its wind (m/s)
  vec4 band_m;   // x, y the radii (m) between which it is the layer drawn: its shell, less what
                 // lies nearer a neighbour's clouds (layer 0 wherever no other's is); z its
                 // forecast share (0 forecast_share's x, 1 its y); w (layer 0's) the number
                 // of slots in use, from 0 on
};

// Voxel clouds (render/modules/voxel_clouds/voxel_clouds.h, shaders/voxel_field_inc.glsl): each cloud's grid
// is cut into bricks of VOXEL_BRICK^3 voxels; the bricks near its surface are stored in one
// atlas texture (VOXEL_BRICK_TEXELS per edge: a brick's voxels and the next one's first, so
// trilinear filtering stays inside a brick; VOXEL_ATLAS_BRICKS^2 bricks per layer) and a page
// table texture holds, per brick, its atlas index (>= 0) or, for an empty brick, minus its
// distance from the cloud (voxels). Atlas texels: x density [0, 1], y signed distance (voxels).
const int MAX_VOXEL_CLOUDS = 16;
const int VOXEL_BRICK = 8;
const int VOXEL_BRICK_TEXELS = 9;
const int VOXEL_ATLAS_BRICKS = 16;

struct VoxelCloudGpu {
  // Rows of the map from the planet frame to grid coordinates (voxels, voxel centres at
  // i + 0.5): u = (dot(to_grid_x.xyz, p - anchor_m.xyz) + to_grid_x.w, ...).
  vec4 to_grid_x;
  vec4 to_grid_y;
  vec4 to_grid_z;
  vec4 anchor_m;  // xyz the cloud's anchor (planet frame, m); w density field per grid density
  vec4 dims;      // xyz the grid's voxels; w the voxel's edge in the scene (m)
  ivec4 bricks;   // xyz its page table (bricks per axis); w its first layer in the page table
};

struct FrameParams {
  vec4 camera_pos_m;        // xyz camera position (m, planet frame); w tan(vertical fov / 2)
  vec4 camera_forward;      // xyz unit view direction; w aspect (width / height)
  vec4 camera_right;        // xyz unit right vector; w the image's shift along it (camera_ray)
  vec4 camera_up;           // xyz unit up vector (image up); w the image's shift along it
  vec4 sun_dir;             // xyz unit vector towards the key light: the sun, or the moon when
                            // the moon lights the sky more (render/key_light.h); w cos(sun
                            // angular radius)
  vec4 sun_illuminance;     // rgb the key light's illuminance at the top of the atmosphere;
                            // w 1 when the key light is the moon
  vec4 sun_at_clouds;       // rgb sunlight reaching the middle of the cloud layer; w unused
  vec4 ambient_at_clouds;   // rgb irradiance / pi on a horizontal surface facing up at the
                            // middle of the cloud layer (cosine-weighted mean sky radiance)
  vec4 ambient_below_clouds;  // rgb the same facing down (the lit ground, the air below)
  vec4 ground_sky_light;    // rgb sky irradiance on the ground / pi (radiance of a white
                            // Lambertian ground lit by the sky alone)
  vec4 radii_m;             // x planet, y atmosphere top, z cloud bottom, w cloud top (m)
  vec4 rayleigh;            // rgb sigma_s at sea level (1/m); w scale height (m)
  vec4 mie;                 // x sigma_s (1/m), y sigma_t (1/m), z scale height (m), w g
  vec4 cloud_shape;         // x the view's angle per cloud pixel (rad; 0: the detail noise's
                            // finest level everywhere), y the cloud profile's half extent (m;
                            // cloud_profile.comp); z sigma_t at density 1 (1/m), w albedo
  vec4 cloud_light;         // x view attenuation, y light attenuation, z powder strength, w ambient
  vec4 cloud_phase;         // x g forward, y g backward, z forward lobe weight, w the lighting: 0 seed, 1 two-stream, 2 diffusion
  // What the clouds are made of (clouds.optics; common/droplets_inc.glsl). cloud_genus_sigma:
  // sigma_t at density field 1 of stratus, stratocumulus, altocumulus and cumulus as a share
  // of cloud_shape.z (the largest genus'; all 1 with the seed's optics), blended by the local
  // type (cloud_genus_blend); cloud_droplets: x cumulonimbus' share, y 1 for the droplets' Mie
  // phase (cloud_mie: mie_fit of their diameter) instead of cloud_phase's lobes, z the phase's
  // mean cosine, w the asymmetry the diffuse light is carried with (cloud_transport_g).
  vec4 cloud_genus_sigma;
  vec4 cloud_droplets;
  vec4 cloud_mie;
  CloudLayerGpu cloud_layers[CLOUD_LAYERS];
  // The wind (seed 002; common/clouds_inc.glsl, cloud_wind_offset): xy its growth from a
  // layer's bottom to its top (m/s), z skew (s), w the time the shear has acted
  // (shear_time_s(time_s), s)
  vec4 cloud_wind;
  vec4 cloud_detail_wind;   // xyz the detail noise's displacement relative to the shapes (m);
                            // w curl distortion (m)
  vec4 cloud_flow;          // x flow map speed (m/s), y cycle (s), z phase fract(time / cycle),
                            // w 1 / the flow map's period (1/m)
  vec4 cirrus;              // x radius of the cirrus sheet (m, planet frame), y coverage [0, 1],
                            // z type [0, 1], w vertical optical depth where densest
  vec4 cirrus_wind;         // xy displacement (m) = its wind * time; zw unit vector along the
                            // wind (its streaks' axis)
  vec4 cloud_noise;         // x 1/base period, y 1/detail period, z 1/weather period (1/m), w erosion
  vec4 wind_offset_m;       // xy the main layer's displacement at its bottom (m) = wind *
                            // time: the light volume's frame; zw its change since the last frame
  vec4 prev_camera_pos_m;   // the previous frame's camera, as camera_pos_m ... camera_up
  vec4 prev_camera_forward;
  vec4 prev_camera_right;
  vec4 prev_camera_up;
  vec4 light_volume;        // xy centre in cloud space (m), z half extent (m), w 1 when in use
  ivec4 size;               // x width, y height, z frame index, w noise seed
  ivec4 steps;              // x primary steps, y light steps, z sky view samples, w PROJECTION_*
  vec4 sun_transmittance;   // rgb transmittance from the camera towards the sun's centre (0 when
                            // the planet hides it): the sun disk's colour; w unused
  vec4 sky_view_up;         // sky-view LUT frame (common/sky_view_inc.glsl): xyz local zenith at
                            // the camera, w elevation of the planet's horizon (rad, <= 0)
  vec4 sky_view_forward;    // xyz horizontal unit vector towards the key light's azimuth;
                            // w unused
  vec4 second_light;        // the sky's other light (render/frame_params.h, SkyLights): xyz
                            // unit vector towards it, w its illuminance in units of the key
                            // light's (0: none)
  ivec4 cloud_grid;         // x, y cloud buffer size (pixels); z march stride s (one pixel of
                            // each s x s block is marched per frame); w 1 if the history is
                            // valid, 2 if it is but the lighting changed (an edit's rebuilt
                            // light): a marched pixel starts its mean afresh
  ivec4 march_offset;       // xy the pixel of each block marched this frame; z jitter index;
                            // w image pixels per cloud pixel (per axis)
  ivec4 march_entering;     // what the previous frame did not see, marched this frame
                            // (entering_inc.glsl): x, y the columns (from, how many), z, w the
                            // rows; 0 wide: none
  vec4 moon_dir;            // xyz unit vector towards the moon; w cos(moon angular radius),
                            // 2 when the scene has no moon (no date)
  vec4 moon_sun_dir;        // xyz unit vector from the moon towards the sun (its phase); w the
                            // earthshine's radiance on the moon's night side, as a share of the
                            // full moon's
  vec4 moon_radiance;       // rgb the full moon's disk radiance reaching the camera, in units
                            // of sun_illuminance (transmittance included); w unused
  vec4 star_east;           // rows of the rotation from J2000 equatorial unit vectors to the
  vec4 star_north;          // camera's east-north-up (precession, sidereal time, latitude);
  vec4 star_up;             // w unused
  vec4 stars;               // x the sun's illuminance (stars' irradiance is relative to it),
                            // y number of stars, z solid angle of a pixel (sr), w unused
  vec4 ozone;               // rgb ozone sigma_a at the layer's peak (1/m); w peak altitude (m)
  vec4 sky_model;           // x ozone half width (m), y ground albedo, z SKY_MODEL_*, w Preetham
                            // turbidity
  ivec4 sky_options;        // x how multiple scattering reaches view rays (MS_ANGULAR or
                            // MS_ISOTROPIC, atmosphere_lut_inc.glsl); yzw unused
  // Time-of-day keyframes (seed 003; nephele/conditions.h), colours per unit key-light
  // illuminance (compose multiplies by sun_illuminance):
  vec4 conditions_sky;       // rgb sky colour; w mode: 0 off, 1 artist, 2 overlay
  vec4 conditions_sky_fog;   // rgb fog on the sky; w star visibility (1 when off)
  vec4 conditions_fog_deg;   // x, y sky fog start and end elevation; z, w the discs' (deg)
  vec4 conditions_disk_fog;  // rgb fog on the sun and moon discs; w fog near (m)
  vec4 conditions_fog;       // rgb fog on clouds and ground; w fog far (m)
  vec4 conditions_light;     // rgb the key light on the ground (artist mode); w unused
  vec4 output_image;         // x exposure (linear scale before the tone map, tonemap.comp);
                             // y the tone map (TONEMAP_*, output.tonemap); zw the image's first
                             // pixel in the whole image (a tile's window; 0 0). (The film layer
                             // and a band's first row are push constants, DispatchConstants.)
  // The light volume being built (light_volume.comp), a band of its rows each frame while the
  // clouds pass reads the last one completed (light_volume): xy its centre in cloud space (m),
  // z half extent (m). (The band is a push constant, DispatchConstants.)
  vec4 light_volume_build;
  // The evolving weather (render/modules/weather/weather.h): states at steps of the weather's time
  // scale / WEATHER_STEPS, step s in layer s mod 3. weather_build: x the first step computed
  // this frame, y how many (consecutive), z the first row, w the rows (weather.comp);
  // weather_blend: x the share of the later state in the map, y, z the layers of the earlier
  // and the later state (weather_blend.comp).
  ivec4 weather_build;
  vec4 weather_blend;
  // A forecast's cover around the observer (binding forecast_cover; weather/grib.h), fixed to
  // the ground: x its texture's scale (1/m; 0 without a forecast), y half a texel (the reads stay
  // on the map, holding its edge beyond it); zw unused.
  vec4 forecast;
  // The frame of the sky-view LUT and aerial-perspective volume being built (as sky_view_up
  // and sky_view_forward are the frame of the pair read; render/modules/sky_view/sky_view.h).
  vec4 sky_view_build_up;
  vec4 sky_view_build_forward;
  // The rows built this frame: x the LUT's first, y its count (of kSkyViewHeight), z the
  // volume's first, w its count (of AP_SIZE_V).
  ivec4 sky_view_rows;
  ivec4 voxel_info;  // x voxel clouds, y VOXEL_MARCH_*, z VOXEL_SHADOW_*, w unused
  // x the SDF cone's half-angle tangent (the seed's LightTangent), y the distance (m) over
  // which the noise clouds fade in away from a voxel region, z how much the detail noise
  // erodes a voxel cloud's surface [0, 1], w the detail noise's frequency there, as a multiple
  // of the noise clouds'
  vec4 voxel_light;
  // The reference path tracer (path_trace.comp): the medium of voxel cloud 0 in vacuum (the
  // lab scene). x sigma_t (1/m) at grid density 1, y albedo, z Henyey-Greenstein g, w the
  // majorant (1/m): sigma_t's largest value.
  vec4 path_medium;
  vec4 path_light;  // xyz unit direction towards the sun (planet frame), w its irradiance (W/m^2)
  // (The seed, the bounces and a dispatch's samples are the path tracer's push constants.)
  // xyz the camera in the lab's own frame (m: x east, y north, z up, from voxel cloud 0's
  // anchor; the cloud's to_grid rows map that frame, its anchor_m.xyz is not used): small
  // numbers, full float precision, where the planet frame's are 0.5 m apart; w 1 to use the
  // bricks as the majorant grid, 0 one majorant for the whole box
  vec4 path_eye_m;
  // The planet's voxel clouds for the path tracer's majorant grid: x the largest extinction
  // their density fields add (1/m), y, z the radii (m, planet frame) between which their boxes
  // lie (y > z: none)
  vec4 path_voxels;
  // The noise clouds' majorant grid (path_majorant, render/path_majorant.h): xy its corner
  // (planet frame, m), z its cells' edge (m), w 1 when in use
  vec4 path_grid;
  // Particle clouds (particles.vert): x albedo, y Henyey-Greenstein g, z 1 for Harris and
  // Lastra's Rayleigh phase instead, w a particle's opacity at its centre
  vec4 particle_shading;
  // x the multiply scattered light's strength (diffuse_strength); yz the share of the image
  // layers' width and height their layer is drawn at (ParticleCloudsParams::layer_resolution);
  // w unused
  vec4 particle_light;
  // The classical models (classic_clouds.comp, seed 004): Blinn's x optical depth tau along the
  // vertical, y albedo omega, z his phase function's x or g, w its kind (BLINN_PHASE_*)
  vec4 classic_blinn;
  // x 1: the seed's printing of the formulas; y Gardner's clouds (0 cumulus ellipsoids, 1 a
  // stratus plane); z his texture's terms; w the layer's coverage
  vec4 classic_options;
  // Gardner: x FX_1 = FY_1 (rad/m), y T1 (the threshold at an ellipsoid's centre), z T2 (at
  // its edge), w D (the texture's range from clear to opaque)
  vec4 classic_gardner;
  // Gardner: x f (ambient), y t (texture), z s (specular), w the cumulus cells' spacing (m)
  vec4 classic_gardner_shading;
  // Gardner's sky plane: x its altitude (m), y the texture's stretch (FY_1 / FX_1: 1 for stratus,
  // more for cirrus's streaks), z its greatest opacity; w unused
  vec4 classic_gardner_plane;
  // Bloom (bloom.comp): x the share of the light spread, y the threshold (the image's units,
  // cd/m^2), z the Gaussian's sigma (pixels), w its taps each side (R; the weights are
  // normalised over -R..R)
  vec4 bloom;
  // Light shafts: x the method (LIGHT_SHAFTS_*: quality.light_shafts), y the screen-space rays'
  // samples, z their strength, w their decay per sample
  vec4 light_shafts;
  // Kajiya and Von Herzen: x Romberg's levels, y 1 for the brute-force reference march instead
  vec4 classic_kajiya;
  // Nishita and Nakamae (render/modules/metaball_clouds/metaball_clouds.h): the voxel grid's corner (xyz, ENU
  // on a flat earth, m) and its voxels' edge (w, m); its size in voxels (xyz); x sigma_t at
  // density 1 (1/m), y albedo, z the scattering orders (1 or 2), w 1: sky light
  vec4 classic_nishita;
  vec4 classic_nishita_grid;
  vec4 classic_nishita_light;
  // The terrain (render/modules/terrain/terrain.h, terrain_inc.glsl): its rectangle (x west, y north
  // edge, z, w extent east-west, north-south, m); x its lowest, y its highest height (m above
  // the ground), z 1 when there is one, w the snow's lower edge (m; 0 none); the bare ground's
  // albedo (rgb; w 1: from the albedo map instead); its grid (xy points) and pyramid of maxima (z its top level, w the width of
  // its level 1, where the levels above start)
  vec4 terrain_rect;
  vec4 terrain_shape;
  vec4 terrain_albedo;
  ivec4 terrain_grid;
  // The host's scene (nephele::HostScene, render/modules/host_scene/host_scene.h): its projection's inverse
  // (clip to view space, m); x 1 when there is one, y 1 for reversed depth (far at 0), z its
  // depth's texel format (HOST_DEPTH_*), w its colour's (HOST_COLOR_*); x where its colour starts
  // in host_texels (words), y its colour's scale, zw unused
  mat4 host_inverse_projection;
  vec4 host_scene;
  vec4 host_layout;
  // The cloud shadow map for the host (render/modules/host_lighting/host_lighting.h): x its west, y its north
  // edge (ENU m), z its side (m), w the altitude of its plane, the cloud shell's bottom (m);
  // x its texels a side, y 1 when it is made; z the environment cube map's face (texels a
  // side), w unused
  vec4 host_shadow_map;
  ivec4 host_shadow_grid;
  VoxelCloudGpu voxel_clouds[MAX_VOXEL_CLOUDS];
};

// The reference path tracer's majorant grid for the noise clouds (path_majorant): cells of
// FrameParams::path_grid.z metres, PATH_GRID_XY per horizontal axis around the camera; in
// height, each layer's shell (padded PATH_SHELL_PAD_M above and below) in PATH_GRID_BINS
// shells, layer l's bins at depth l * PATH_GRID_BINS.
// FrameParams::host_scene.zw: how host_scene.comp reads the host's depth and colour texels.
const int HOST_DEPTH_FLOAT32 = 0;  // D32_SFLOAT, D32_SFLOAT_S8_UINT (the depth aspect's copy)
const int HOST_DEPTH_UNORM24 = 1;  // X8_D24_UNORM_PACK32, D24_UNORM_S8_UINT: the low 24 bits
const int HOST_DEPTH_UNORM16 = 2;  // D16_UNORM: two texels a word
const int HOST_COLOR_HALF4 = 0;    // R16G16B16A16_SFLOAT
const int HOST_COLOR_FLOAT4 = 1;   // R32G32B32A32_SFLOAT

const int LIGHT_SHAFTS_OFF = 0;
const int LIGHT_SHAFTS_VOLUMETRIC = 1;  // the air's single scattering shadowed (compose.comp)
const int LIGHT_SHAFTS_SCREEN = 2;      // seed 002's screen-space god rays (god_rays.comp)

const int PATH_GRID_XY = 256;
const int PATH_GRID_BINS = 8;
const float PATH_SHELL_PAD_M = 100.0f;
// The texels (rgba32f) of one path in progress in path_state (path_trace.comp, PtPath).
const int PATH_STATE_TEXELS = 12;

// FrameParams::voxel_info.y, z (nephele::VoxelMarch, VoxelShadow).
const int VOXEL_MARCH_PLAIN = 0;
const int VOXEL_MARCH_THREE_PHASE = 1;
const int VOXEL_SHADOW_LIGHT_MARCH = 0;
const int VOXEL_SHADOW_SDF_CONE = 1;

// Steps of the evolving weather per clouds.weather_evolution_s (10 s at an hour): the map is
// blended linearly between states that far apart, where the weather's clusters move 1/360
// of a noise cell.
const int WEATHER_STEPS = 360;

// FrameParams::steps.w: how the clouds pass turns its pixels into rays.
const int PROJECTION_CAMERA = 0;    // the camera's perspective
const int PROJECTION_SKY_DOME = 1;  // the observer's upper hemisphere (sky_dome_ray)

// FrameParams::sky_model.z: what fills the sky.
const int SKY_MODEL_HILLAIRE = 0;   // Hillaire 2020 LUTs (the default)
const int SKY_MODEL_PREETHAM = 1;   // Preetham et al. 1999 analytic sky (seed 002)
const int SKY_MODEL_REFERENCE = 2;  // brute force per pixel, no tables (slow; for checking)
// The reference sky is computed in square tiles of REFERENCE_TILE pixels, REFERENCE_SAMPLES
// steps along each view ray (sky_reference_psi.comp, sky_reference.comp).
const int REFERENCE_TILE = 32;
const int REFERENCE_SAMPLES = 48;

// One particle of the particle clouds as particles.vert draws it.
struct ParticleGpu {
  vec4 position_radius;  // xyz from the camera (m, the planet frame's axes), w radius (m)
  vec4 shading;          // x the light reaching it (CPU lighting, [0, 1]), y its texture, zw unused
};
// The push constants (DrawConstants, DispatchConstants): common/push_constants_inc.glsl.

// An impostor's quad (impostor.vert): a cloud's image from the atlas, facing the camera.
struct ImpostorGpu {
  vec4 center_half;  // xyz the quad's centre from the camera (m), w unused
  vec4 right;        // xyz the quad's half width along its image's right (m), w the new image's
                     // weight (cross-fade)
  vec4 up;           // xyz its half height along its image's up (m), w the cloud's distance (km)
  vec4 image_new;    // direct: the image's texels (x0, y0, x1, y1); tiles: x its first entry in
                     // impostor_tile_slots, y its tiles across, z, w its width and height (texels)
  vec4 image_old;    // the same for the image fading out (weight 1 - right.w)
  ivec4 info;        // x IMPOSTOR_DIRECT or IMPOSTOR_TILES, y the tile side (texels)
};
const int IMPOSTOR_DIRECT = 0;
const int IMPOSTOR_TILES = 1;
// One tile for impostor_tiles.comp to fill: x its slot, y, z its column and row in the
// impostor's grid of tiles, w the tile side; source: xy the impostor's image's corner in the
// scratch image, z, w its width and height (texels).
struct ImpostorTileJob {
  ivec4 tile;
  ivec4 source;
};

// The particle clouds' lighting on the device (particle_light.comp; the CPU's is
// particles/particle_lighting.h): one workgroup a cloud splats the cloud's particles, sorted
// nearest the light first on the host, into a buffer in shared memory.
// One particle as seen from the light.
struct ParticleSplatGpu {
  vec4 splat;  // xy its centre, z its radius (buffer texels); w its index in its cloud (exact
               // in a float below 2^24)
};
// One cloud: its splats and where its particles' lights go.
struct ParticleLightCloudGpu {
  ivec4 range;   // x its first splat in particle_splats, y its splats; x is also its first
                 // particle's light in particle_lights
  vec4 shading;  // x the forward share f, y a particle's opacity at its centre
};

// The particles' procedural textures (render/modules/particle_clouds/particle_clouds.cpp).
const int PARTICLE_TEXTURES = 4;
const int PARTICLE_TEXTURE_SIZE = 64;

// One star of the catalogue (data/stars.csv), as stars.comp reads it.
struct StarGpu {
  vec4 dir_j2000;           // xyz unit vector, J2000 equatorial; w V magnitude
  vec4 irradiance;          // rgb irradiance at the top of the atmosphere per unit solar
                            // illuminance; w B-V
};

#ifdef __cplusplus
}  // namespace nephele::gpu
#endif

#endif

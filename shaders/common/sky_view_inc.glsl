// Sky-view look-up table (Hillaire 2020, "A Scalable and Production Ready Sky and Atmosphere
// Rendering Technique", section 5.3): the sky seen from the camera as a latitude/longitude table
// in a local frame at the camera, filled by sky_view.comp and sampled bilinearly by compose.comp.
// u: azimuth phi relative to the key light's azimuth, u = 0.5 + phi / (2 pi) over the full
// circle (u = 0.5 towards the key light, u = 0 and 1 away from it; the texture wraps in u). The
// sky lit by one light is mirror-symmetric about its vertical plane, but the table also holds the
// second light (FrameParams::second_light: the twilight sun under a moon key, or the moon under a
// sun key), which is not in that plane.
// v: elevation l relative to the planet's horizon seen from the camera,
// v = 0.5 + 0.5 sign(l) sqrt(|l| / range), range the angle from the horizon to the zenith
// (above) or to the nadir (below), as in Hillaire's code: texels crowd at the horizon, where
// the sky changes fastest, and the horizon is exactly the row boundary v = 0.5.
// Pure functions, also compiled as C++ (src/render/glsl.h).
#ifndef NEPHELE_SKY_VIEW_INC
#define NEPHELE_SKY_VIEW_INC

struct SkyViewFrame {
  vec3 up;                      // local zenith at the camera
  vec3 forward;                 // horizontal, towards the key light's azimuth (u = 0.5)
  vec3 side;                    // up x forward
  float horizon_elevation_rad;  // elevation of the planet's horizon seen from the camera, <= 0
};

// The frame at `eye` (planet frame, m) for the sun in unit direction `sun`.
SkyViewFrame sky_view_frame(vec3 eye, vec3 sun, float planet_radius_m) {
  SkyViewFrame f;
  f.up = normalize(eye);
  vec3 horizontal = sun - dot(sun, f.up) * f.up;
  if (dot(horizontal, horizontal) < 1e-12f) {
    // Sun at the zenith or nadir: the sky is symmetric about the up axis, any azimuth will do.
    vec3 axis = abs(f.up.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
    horizontal = axis - dot(axis, f.up) * f.up;
  }
  f.forward = normalize(horizontal);
  f.side = cross(f.up, f.forward);
  // The horizon dips acos(R / r) below the horizontal; asin(sqrt(r^2 - R^2) / r) is the same
  // angle and stays accurate in float for r close to R.
  float r = length(eye);
  float height_m = max(r - planet_radius_m, 0.0f);
  f.horizon_elevation_rad = -asin(min(sqrt(height_m * (r + planet_radius_m)) / r, 1.0f));
  return f;
}

// The frame as FrameParams carries it: computed once a frame on the CPU (with the function
// above compiled as C++), so every pass and pixel uses the same one.
SkyViewFrame sky_view_frame_from(vec4 up_and_horizon_elevation, vec4 forward) {
  SkyViewFrame f;
  f.up = vec3(up_and_horizon_elevation);
  f.forward = vec3(forward);
  f.side = cross(f.up, f.forward);
  f.horizon_elevation_rad = up_and_horizon_elevation.w;
  return f;
}

// Angles (rad) from the horizon up to the zenith and down to the nadir.
float sky_view_range_above(SkyViewFrame f) { return 0.5f * PI - f.horizon_elevation_rad; }
float sky_view_range_below(SkyViewFrame f) {
  return max(0.5f * PI + f.horizon_elevation_rad, 1e-6f);
}

// LUT coordinates in [0, 1]^2 of unit direction `dir`; v < 0.5 exactly when `dir` is below
// the horizon.
vec2 sky_view_uv(SkyViewFrame f, vec3 dir) {
  float x = dot(dir, f.forward);
  float y = dot(dir, f.side);
  float z = dot(dir, f.up);
  // asin rather than atan for the elevation: it loses accuracy only next to the zenith (a few
  // 1e-4 rad, a thirtieth of a texel), none at the horizon.
  float u = x * x + y * y > 1e-14f ? 0.5f + atan(y, x) / (2.0f * PI) : 0.5f;
  float l = asin(clamp(z, -1.0f, 1.0f)) - f.horizon_elevation_rad;
  float v = l >= 0.0f ? 0.5f + 0.5f * sqrt(l / sky_view_range_above(f))
                      : 0.5f - 0.5f * sqrt(-l / sky_view_range_below(f));
  return vec2(u, v);
}

// Unit direction of LUT coordinates `uv` (the inverse of sky_view_uv).
vec3 sky_view_dir(SkyViewFrame f, vec2 uv) {
  float s = 2.0f * uv.y - 1.0f;
  float l = s >= 0.0f ? sky_view_range_above(f) * s * s : -sky_view_range_below(f) * s * s;
  float elevation = f.horizon_elevation_rad + l;
  float azimuth = 2.0f * PI * (uv.x - 0.5f);
  return cos(elevation) * (cos(azimuth) * f.forward + sin(azimuth) * f.side) +
         sin(elevation) * f.up;
}

// The direction whose sky the LUT texel at `uv` holds, for the camera at `eye`: the texel
// centre's, moved away from the horizon while ray_sphere, which decides whether a ray ends on
// the ground, puts it on the other side of the planet's edge than the mapping does. (Close to
// the ground the rows next to the horizon pass the edge by less than a metre, within float
// rounding of planet-scale positions.)
vec3 sky_view_texel_dir(SkyViewFrame f, vec2 uv, vec3 eye, float planet_radius_m) {
  bool below = uv.y < 0.5f;
  vec3 dir = sky_view_dir(f, uv);
  for (int i = 0; i < 8 && (ray_sphere(eye, dir, planet_radius_m).x > 0.0f) != below; ++i) {
    uv.y = 0.5f + 1.41421356f * (uv.y - 0.5f);  // twice the angle from the horizon
    dir = sky_view_dir(f, uv);
  }
  return dir;
}

// Texture coordinates in the LUT image, which stacks two tables of `rows` rows each (table 0:
// rows [0, rows), table 1: rows [rows, 2 rows)), for LUT coordinates `uv`. v stays half a
// texel away from the horizon on uv's side of it and from the table's ends, so the bilinear
// filter never blends ground into sky nor one table into the other; u wraps (the sampler
// repeats), so the columns at u = 0 and u = 1 blend across the anti-key-light azimuth.
// sky_view_v_clamped is the aerial-perspective volume's (rows at (k + 1/2) / rows);
// sky_view_texcoord the sky-view LUT's (sky_view_row_v).
float sky_view_v_clamped(vec2 uv, float rows) {
  float half_texel = 0.5f / rows;
  return uv.y < 0.5f ? clamp(uv.y, half_texel, 0.5f - half_texel)
                     : clamp(uv.y, 0.5f + half_texel, 1.0f - half_texel);
}

// The LUT's rows (sky_view.comp) on each side of the horizon: row k of the n = rows / 2 rows
// of a side (k = 0 next to the horizon) holds s = (k + 1/2) / (n - 1/2) of the way (in
// sky_view_uv's sqrt-spaced v) from the horizon to the zenith or nadir, so its last row is the
// zenith (nadir) itself, the same direction at every azimuth: the sky does not jump across it.
// (Rows at (k + 1/2) / n, as in Hillaire's code, put the last row 88.35 degrees up with 108
// rows; the few degrees above it read it at their own azimuth, and the two sides of the
// zenith differed by up to 6.8%.) The first row stays half a row off the horizon.
float sky_view_row_v(int row, int rows) {
  int n = rows / 2;
  bool above = row >= n;
  float k = float(above ? row - n : n - 1 - row);
  float s = (k + 0.5f) / (float(n) - 0.5f);
  return above ? 0.5f + 0.5f * s : 0.5f - 0.5f * s;
}

// The inverse, between rows: the row coordinate (in [0, 1] over the table's rows) of LUT
// coordinate v, kept within the rows of v's side of the horizon.
float sky_view_row_coordinate(float v, float rows) {
  float n = 0.5f * rows;
  float k = clamp(abs(2.0f * v - 1.0f) * (n - 0.5f) - 0.5f, 0.0f, n - 1.0f);
  return (v >= 0.5f ? n + k + 0.5f : n - k - 0.5f) / rows;
}

vec2 sky_view_texcoord(vec2 uv, float rows, float table) {
  return vec2(uv.x, 0.5f * (table + sky_view_row_coordinate(uv.y, rows)));
}

// Aerial-perspective volume (Hillaire 2020, section 5.4): the in-scattered radiance and the
// transmittance between the camera and points along each direction, up to AP_MAX_DISTANCE_M.
// Hillaire's volume follows the camera frustum; this one uses the sky-view LUT's directions
// (u, v above) as its first two axes, so it depends on the camera's position and the sun only
// and is rebuilt with the sky-view LUT, not when the camera turns. Slice k (0-based) ends at
// AP_MAX_DISTANCE_M ((k + 1) / AP_SLICES)^2: fine slices near the camera.
const int AP_SIZE_U = 48;
const int AP_SIZE_V = 64;
const int AP_SLICES = 32;
const float AP_MAX_DISTANCE_M = 400000.0f;

float aerial_perspective_slice_end_m(int slice) {
  float s = float(slice + 1) / float(AP_SLICES);
  return AP_MAX_DISTANCE_M * s * s;
}

// Texture coordinate along the slices of the point `distance_m` from the camera: the slice
// ends are texel centres, distances short of the first one clamp to it.
float aerial_perspective_w(float distance_m) {
  float slice = sqrt(max(distance_m, 0.0f) / AP_MAX_DISTANCE_M) * float(AP_SLICES) - 1.0f;
  return clamp((slice + 0.5f) / float(AP_SLICES), 0.5f / float(AP_SLICES),
               1.0f - 0.5f / float(AP_SLICES));
}

#endif

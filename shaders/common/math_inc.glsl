// Pure math shared by the shaders and by C++ tests (src/render/glsl.h compiles this file as C++:
// keep to the GLSL subset GLM accepts — float literals with f, no swizzles, no out parameters).
#ifndef NEPHELE_MATH_INC
#define NEPHELE_MATH_INC

const float PI = 3.14159265358979f;

// NaN gives 0 (clamp leaves NaN undefined): a table lookup never reads with a NaN coordinate.
float saturate(float x) { return x >= 0.0f ? min(x, 1.0f) : 0.0f; }

// a / b rounded down (b > 0, |a| < 2^24, where the float quotient is exact enough), also for
// negative a. Not with GLSL's integer % or /, whose results for a negative operand are left to
// the device (an H100 wrapped noise cell -1 elsewhere than lavapipe and the CPU, and drew other
// clouds); a - b floor_div(a, b) is a mod b in [0, b).
int floor_div(int a, int b) { return int(floor(float(a) / float(b))); }
ivec3 floor_div(ivec3 a, int b) { return ivec3(floor(vec3(a) / float(b))); }

// Linear map of v from [lo, hi] to [new_lo, new_hi] (seed 000, listing B.1); not clamped.
float remap(float v, float lo, float hi, float new_lo, float new_hi) {
  return new_lo + (v - lo) / (hi - lo) * (new_hi - new_lo);
}

// Where a ray from the origin along unit `dir` passes closest to the segment from `a` to
// a + e (relative to the ray's origin): x the distance along the ray (>= 0), y how far it
// misses the segment, z the segment's parameter there, in [0, 1].
vec3 ray_segment_closest(vec3 dir, vec3 a, vec3 e) {
  float b = dot(dir, e), c = dot(e, e), da = dot(dir, a), ea = dot(e, a);
  float det = c - b * b;
  float u = det > 1e-10f * c ? clamp((b * da - ea) / det, 0.0f, 1.0f) : 0.0f;
  vec3 p = a + e * u;
  float t = max(dot(dir, p), 0.0f);
  return vec3(t, length(p - dir * t), u);
}

// Ray-sphere intersection (seed 000, 2.1-2.5): the roots t0 <= t1 of
// |origin + t dir - centre|^2 = r^2 for a sphere centred at the origin, dir a unit vector.
// Written in the numerically stable form (Haines et al., Ray Tracing Gems ch. 7): the
// discriminant is r^2 - |f|^2 with f the perpendicular from the centre to the ray, and the
// roots come from q = -b - sign(b) sqrt(disc) as t = c/q and t = q, so rays from the ground
// of a 6360 km planet keep metre accuracy in float. A miss returns (-1, -1).
vec2 ray_sphere(vec3 origin, vec3 dir, float radius) {
  float b = dot(origin, dir);
  vec3 f = origin - b * dir;
  float f_len = length(f);
  float disc = (radius - f_len) * (radius + f_len);
  if (disc < 0.0f) return vec2(-1.0f, -1.0f);
  float o_len = length(origin);
  float c = (o_len - radius) * (o_len + radius);
  float q = -b - (b >= 0.0f ? 1.0f : -1.0f) * sqrt(disc);
  if (q == 0.0f) return vec2(0.0f, 0.0f);
  float t_a = c / q;
  float t_b = q;
  return vec2(min(t_a, t_b), max(t_a, t_b));
}

// Direction of the camera ray through pixel (x, y) of a width x height image, row 0 at the top.
// `shift` moves the image's centre on the image plane at distance 1 (right, up): the image is a
// window (a tile) of a larger one, whose pixels it then shares exactly.
vec3 camera_ray(vec3 forward, vec3 right, vec3 up, float tan_half_fov, float aspect, float x,
                float y, float width, float height, vec2 shift) {
  float sx = shift.x + (2.0f * (x + 0.5f) / width - 1.0f) * tan_half_fov * aspect;
  float sy = shift.y + (1.0f - 2.0f * (y + 0.5f) / height) * tan_half_fov;
  return normalize(forward + sx * right + sy * up);
}

vec3 camera_ray(vec3 forward, vec3 right, vec3 up, float tan_half_fov, float aspect, float x,
                float y, float width, float height) {
  return camera_ray(forward, right, up, tan_half_fov, aspect, x, y, width, height, vec2(0.0f));
}

// The sky dome's ray through cell (x, y) of a width x height grid: the cells split the upper
// hemisphere around `zenith` into equal solid angles (rows uniform in the cosine of the zenith
// angle, columns in azimuth), so counting cells measures a share of the sky as an observer
// reports it (oktas).
vec3 sky_dome_ray(vec3 zenith, float x, float y, float width, float height) {
  vec3 any_axis = abs(zenith.z) < 0.9f ? vec3(0.0f, 0.0f, 1.0f) : vec3(1.0f, 0.0f, 0.0f);
  vec3 east = normalize(cross(any_axis, zenith));
  vec3 north = cross(zenith, east);
  float cos_zenith = (y + 0.5f) / height;
  float sin_zenith = sqrt(max(1.0f - cos_zenith * cos_zenith, 0.0f));
  float azimuth = 6.2831853f * (x + 0.5f) / width;
  return sin_zenith * (cos(azimuth) * east + sin(azimuth) * north) + cos_zenith * zenith;
}

// Inverse of camera_ray: the continuous pixel coordinates (pixel centres at integers) where the
// unit direction `dir` meets the image; (-1e9, -1e9) for directions behind the camera.
vec2 camera_pixel(vec3 forward, vec3 right, vec3 up, float tan_half_fov, float aspect, vec3 dir,
                  float width, float height, vec2 shift) {
  float z = dot(dir, forward);
  if (z <= 1e-6f) return vec2(-1e9f, -1e9f);
  float sx = (dot(dir, right) / z - shift.x) / (tan_half_fov * aspect);
  float sy = (dot(dir, up) / z - shift.y) / tan_half_fov;
  return vec2((sx + 1.0f) * 0.5f * width - 0.5f, (1.0f - sy) * 0.5f * height - 0.5f);
}

vec2 camera_pixel(vec3 forward, vec3 right, vec3 up, float tan_half_fov, float aspect, vec3 dir,
                  float width, float height) {
  return camera_pixel(forward, right, up, tan_half_fov, aspect, dir, width, height, vec2(0.0f));
}

// Interleaved gradient noise (Jimenez 2014): a per-pixel value in [0, 1) for ray jitter.
// Koschmieder's constant -ln(0.02) = 3.912: an object at the visibility V is seen with 2% of
// its contrast, exp(-sigma_t V) = 0.02 (the threshold at 550 nm). The fog, the haze, rain and
// snow, and the host's visibility all convert with it.
const float KOSCHMIEDER = 3.912f;

float interleaved_gradient_noise(float x, float y) {
  return fract(52.9829189f * fract(0.06711056f * x + 0.00583715f * y));
}

#endif

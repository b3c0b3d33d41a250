// The sun's disk as the camera sees it (compose.comp) and as the reference path tracer's camera
// rays meet it (path_trace.comp). Pure; GLSL and C++.
#ifndef NEPHELE_SUN_DISK_INC
#define NEPHELE_SUN_DISK_INC

// Solar disk radiance per unit illuminance, with limb darkening I(m)/I(1) = 1 - u (1 - m),
// m = cos of the angle at the sun's surface, u = 0.6 (a visible-band average); normalised so
// the disk integrates to the illuminance.
float sun_disk(vec3 dir, vec3 sun, float cos_radius) {
  float cos_angle = dot(dir, sun);
  // No disk at radius 0 (a direction within 0.02 deg of the sun rounds to cos 1).
  if (cos_angle < cos_radius || cos_radius >= 1.0f) return 0.0f;
  float sin_radius_sq = 1.0f - cos_radius * cos_radius;
  float r = sqrt(saturate((1.0f - cos_angle * cos_angle) / max(sin_radius_sq, 1e-12f)));
  float m = sqrt(1.0f - r * r);
  const float u = 0.6f;
  float solid_angle = 2.0f * PI * (1.0f - cos_radius);
  return (1.0f - u * (1.0f - m)) / ((1.0f - u / 3.0f) * solid_angle);
}

#endif

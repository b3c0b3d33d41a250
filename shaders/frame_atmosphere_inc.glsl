// The frame's atmosphere (FrameParams) as common/atmosphere_inc.glsl's struct. GLSL only.
#ifndef NEPHELE_FRAME_ATMOSPHERE_INC
#define NEPHELE_FRAME_ATMOSPHERE_INC

#extension GL_GOOGLE_include_directive : require
#include "common/phase_inc.glsl"
#include "common/atmosphere_inc.glsl"
#include "common/bindings_inc.glsl"

Atmosphere frame_atmosphere() {
  Atmosphere a;
  a.planet_radius_m = frame.radii_m.x;
  a.top_radius_m = frame.radii_m.y;
  a.rayleigh_sigma_s = frame.rayleigh.rgb;
  a.rayleigh_height_m = frame.rayleigh.w;
  a.mie_sigma_s = frame.mie.x;
  a.mie_sigma_t = frame.mie.y;
  a.mie_height_m = frame.mie.z;
  a.mie_g = frame.mie.w;
  a.ozone_sigma_a = frame.ozone.rgb;
  a.ozone_center_m = frame.ozone.w;
  a.ozone_half_width_m = frame.sky_model.x;
  return a;
}

// The sky light on the ground below the camera per unit key-light illuminance (the radiance
// of a white Lambertian ground lit by the sky alone).
vec3 frame_ground_sky() {
  return frame.ground_sky_light.rgb / max(frame.sun_illuminance.rgb, vec3(1e-20f));
}

// The sun's light (as it reaches the clouds) on a horizontal ground of normal `up`, per unit
// key-light illuminance (the radiance of a white Lambertian ground lit by the sun alone).
vec3 frame_ground_sun(vec3 up) {
  return frame.sun_at_clouds.rgb / max(frame.sun_illuminance.rgb, vec3(1e-20f)) *
         max(dot(up, frame.sun_dir.xyz), 0.0f) / PI;
}

#endif

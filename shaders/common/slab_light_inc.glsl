// The light a slab medium under the clouds (the ground fog, rain and snow) scatters towards the
// eye at one point, per unit of sigma_s and of the key light's illuminance. Pure, also compiled
// as C++ (src/render/glsl.h conventions; needs clouds_inc.glsl and math_inc.glsl).
#ifndef NEPHELE_SLAB_LIGHT_INC
#define NEPHELE_SLAB_LIGHT_INC

// The sun's beam through the medium above (`tau_sun` to the sun), scattered by `phase` (the
// phase function's value towards the eye); the sun's diffuse light as a two-stream slab of
// asymmetry `g` has it (cloud_diffuse_transmittance): going down, what the medium above has
// scattered on, and going up, what the medium below (`tau_below`) reflects (a conservative
// slab reflects what it does not let through), each a flux of mu_sun times the sun's,
// scattered evenly ((down + up) / 2 pi); and `sky_rgb`, the sky's and the ground's light as an
// even field, through the column above (`tau_up`) as diffuse light. `sun_rgb`: the sunlight
// at the medium's top per unit of the key light's illuminance; `mu_sun` the sine of the sun's
// elevation.
vec3 slab_medium_light(vec3 sun_rgb, float mu_sun, vec3 sky_rgb, float phase, float g,
                       float tau_sun, float tau_below, float tau_up) {
  float direct = exp(-tau_sun);
  float down = cloud_diffuse_transmittance(tau_sun, g);  // the sun's light reaching the point
  float up = down * (1.0f - cloud_diffuse_transmittance(tau_below, g));
  float diffuse = (max(down - direct, 0.0f) + up) * max(mu_sun, 0.0f) / (2.0f * PI);
  vec3 sky = sky_rgb * cloud_diffuse_transmittance(tau_up, g);
  return sun_rgb * (direct * phase + diffuse) + sky;
}

#endif

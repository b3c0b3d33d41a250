// nephele — internal: the star catalogue (data/stars.csv, embedded) and the rotation that
// places it in the sky of a date and place.
#pragma once

#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace nephele {

struct Star {
  glm::vec3 dir_j2000;   // unit vector, J2000 equatorial (x to the equinox, z to the pole)
  float vmag;            // V magnitude
  float b_v;             // B-V colour index
  glm::vec3 irradiance;  // rgb at the top of the atmosphere, per unit solar illuminance
};

// The Yale Bright Star Catalogue, 9,096 stars, brightest first.
const std::vector<Star>& star_catalogue();

// rgb of a star of colour index B-V with luminance 1, relative to the sun's colour (white):
// a black body of the temperature of Ballesteros (2012), T = 4600 K (1 / (0.92 (B-V) + 1.7) +
// 1 / (0.92 (B-V) + 0.62)), sampled at 610, 550 and 465 nm over the sun's (5778 K).
glm::vec3 star_color(float b_v);

// Rotation from J2000 equatorial unit vectors to east-north-up at latitude `lat_deg` for the
// Julian day `jd_ut`: precession to the date, then the local sidereal time `lst_deg`.
glm::mat3 enu_from_j2000(double jd_ut, double lat_deg, double lst_deg);

}  // namespace nephele

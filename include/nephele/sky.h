// nephele — the sky's bodies: where the sun and the moon are for a date, a time and a place
// (libnova), and the sun direction a scene uses.
#pragma once

#include <optional>
#include <string_view>

#include <glm/vec3.hpp>

#include "nephele/scene.h"

namespace nephele {

// Julian day (UT) of an ISO 8601 date and time: "2026-06-21T18:30:00Z", fractional seconds
// and a "+HH:MM" / "-HH:MM" offset allowed. nullopt when the text is not one (or names a
// day that does not exist).
std::optional<double> julian_day_from_iso8601(std::string_view text);

// A body seen from a place on the earth: topocentric, geometric (no refraction).
struct SkyPosition {
  double elevation_deg = 0.0;  // above the horizon
  double azimuth_deg = 0.0;    // from north through east, [0, 360)
  double distance_km = 0.0;    // from the observer's planet centre (the earth's)
  glm::vec3 direction{0.0f, 0.0f, 1.0f};  // ENU unit vector towards the body
};

struct Ephemeris {
  double jd_ut = 0.0;  // the instant (Julian day, UT)
  SkyPosition sun;
  SkyPosition moon;
  double moon_illuminated_fraction = 0.0;  // (1 + cos phase angle) / 2
  double local_sidereal_time_deg = 0.0;    // hour angle of the vernal equinox at the place
};

// Sun and moon for Julian day `jd_ut` at latitude/longitude (deg, east positive) and
// `altitude_m` above sea level. The moon includes its parallax (up to ~1 deg); both are
// precessed to the date (libnova returns J2000 coordinates).
Ephemeris compute_ephemeris(double jd_ut, double lat_deg, double lon_deg, double altitude_m);

// The scene's ephemeris at its time (`time` + `time_s`) and place (location, observer at
// location.altitude_m + the camera's height); nullopt when the scene has no valid `time`.
std::optional<Ephemeris> scene_ephemeris(const Scene& scene);

// The unit direction (ENU) towards the sun that the scene is rendered with: the ephemeris's
// when sun.from_time is set, else sun.direction.
glm::vec3 scene_sun_direction(const Scene& scene);
// The same with the scene's ephemeris already computed (scene_ephemeris(scene)).
glm::vec3 scene_sun_direction(const Scene& scene, const std::optional<Ephemeris>& ephemeris);

}  // namespace nephele

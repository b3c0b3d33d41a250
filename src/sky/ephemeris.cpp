// nephele — sun and moon positions with libnova (Meeus's algorithms).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>

#include <glm/geometric.hpp>
#include <libnova/earth.h>
#include <libnova/julian_day.h>
#include <libnova/lunar.h>
#include <libnova/parallax.h>
#include <libnova/precession.h>
#include <libnova/sidereal_time.h>
#include <libnova/solar.h>
#include <libnova/transform.h>

#include "nephele/scene_io.h"
#include "nephele/sky.h"

namespace nephele {

namespace {

constexpr double kAuKm = 149597870.7;

bool leap_year(int y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

int days_in_month(int y, int m) {
  static const int days[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return m == 2 && leap_year(y) ? 29 : days[m - 1];
}

// Horizontal position of equatorial coordinates of the date, azimuth from north.
SkyPosition horizontal(ln_equ_posn equ, ln_lnlat_posn observer, double jd, double distance_km) {
  ln_hrz_posn hrz;
  ln_get_hrz_from_equ(&equ, &observer, jd, &hrz);
  SkyPosition p;
  p.elevation_deg = hrz.alt;
  p.azimuth_deg = std::fmod(hrz.az + 180.0, 360.0);  // libnova measures azimuth from south
  p.distance_km = distance_km;
  p.direction = sun_direction_from_angles(p.elevation_deg, p.azimuth_deg);
  return p;
}

// Illuminated fraction of the moon from equatorial positions (Meeus, Astronomical
// Algorithms, 48.2-48.3): the elongation psi, then the phase angle i seen from the moon.
// (libnova's ln_get_lunar_disk uses the shorter series of 48.4, about 0.007 off.)
double illuminated_fraction(ln_equ_posn sun, double sun_km, ln_equ_posn moon, double moon_km) {
  const double d = M_PI / 180.0;
  const double cos_psi = std::sin(sun.dec * d) * std::sin(moon.dec * d) +
                         std::cos(sun.dec * d) * std::cos(moon.dec * d) * std::cos((sun.ra - moon.ra) * d);
  const double psi = std::acos(std::clamp(cos_psi, -1.0, 1.0));
  const double i = std::atan2(sun_km * std::sin(psi), moon_km - sun_km * std::cos(psi));
  return 0.5 * (1.0 + std::cos(i));
}

}  // namespace

std::optional<double> julian_day_from_iso8601(std::string_view text) {
  const std::string s(text);
  int year, month, day, hour, minute, used = 0;
  if (std::sscanf(s.c_str(), "%4d-%2d-%2dT%2d:%2d%n", &year, &month, &day, &hour, &minute, &used) != 5 ||
      used != 16)
    return std::nullopt;
  double seconds = 0.0;
  size_t i = 16;
  if (i < s.size() && s[i] == ':') {
    size_t start = ++i;
    while (i < s.size() && (std::isdigit(static_cast<unsigned char>(s[i])) || s[i] == '.')) ++i;
    const std::string digits = s.substr(start, i - start);  // "SS" or "SS.fff"
    if (digits.size() < 2 || !std::isdigit(static_cast<unsigned char>(digits[0])) ||
        !std::isdigit(static_cast<unsigned char>(digits[1])) ||
        (digits.size() > 2 && (digits[2] != '.' || digits.size() == 3 ||
                               digits.find('.', 3) != std::string::npos)))
      return std::nullopt;
    seconds = std::stod(digits);
  }
  double offset_h = 0.0;
  if (i < s.size() && s[i] == 'Z') {
    ++i;
  } else if (i < s.size() && (s[i] == '+' || s[i] == '-')) {
    int oh, om, n = 0;
    if (std::sscanf(s.c_str() + i + 1, "%2d:%2d%n", &oh, &om, &n) != 2 || n != 5 || oh > 14 || om > 59)
      return std::nullopt;
    offset_h = (s[i] == '-' ? -1.0 : 1.0) * (oh + om / 60.0);
    i += 6;
  } else {
    return std::nullopt;  // a time without a zone is ambiguous
  }
  if (i != s.size() || month < 1 || month > 12 || day < 1 || day > days_in_month(year, month) ||
      hour > 23 || minute > 59 || seconds >= 61.0)
    return std::nullopt;
  ln_date date{year, month, day, hour, minute, seconds};
  return ln_get_julian_day(&date) - offset_h / 24.0;
}

Ephemeris compute_ephemeris(double jd, double lat_deg, double lon_deg, double altitude_m) {
  ln_lnlat_posn observer{lon_deg, lat_deg};
  Ephemeris e;
  e.jd_ut = jd;

  ln_equ_posn sun_j2000, sun;
  ln_get_solar_equ_coords(jd, &sun_j2000);
  ln_get_equ_prec(&sun_j2000, jd, &sun);
  e.sun = horizontal(sun, observer, jd, ln_get_earth_solar_dist(jd) * kAuKm);

  ln_equ_posn moon_j2000, moon, parallax;
  ln_get_lunar_equ_coords(jd, &moon_j2000);
  ln_get_equ_prec(&moon_j2000, jd, &moon);
  const double moon_km = ln_get_lunar_earth_dist(jd);
  ln_get_parallax(&moon, moon_km / kAuKm, &observer, altitude_m, jd,
                  &parallax);
  moon.ra += parallax.ra;
  moon.dec += parallax.dec;
  // Seen from the place, as the positions are (the parallax moves the moon by up to 1 deg
  // against the sun: up to 0.009 in the fraction).
  e.moon_illuminated_fraction = illuminated_fraction(sun, e.sun.distance_km, moon, moon_km);
  e.moon = horizontal(moon, observer, jd, moon_km);
  e.local_sidereal_time_deg =
      std::fmod(ln_get_apparent_sidereal_time(jd) * 15.0 + lon_deg + 360.0, 360.0);
  return e;
}

std::optional<Ephemeris> scene_ephemeris(const Scene& scene) {
  if (scene.time.empty()) return std::nullopt;
  const std::optional<double> jd = julian_day_from_iso8601(scene.time);
  if (!jd) return std::nullopt;
  return compute_ephemeris(*jd + double(scene.time_s) / 86400.0, scene.location.lat_deg,
                           scene.location.lon_deg,
                           scene.location.altitude_m + scene.camera.position_m.z);
}

glm::vec3 scene_sun_direction(const Scene& scene, const std::optional<Ephemeris>& ephemeris) {
  return ephemeris && scene.sun.from_time ? ephemeris->sun.direction
                                          : glm::normalize(scene.sun.direction);
}

glm::vec3 scene_sun_direction(const Scene& scene) {
  return scene_sun_direction(scene, scene.sun.from_time ? scene_ephemeris(scene) : std::nullopt);
}

}  // namespace nephele

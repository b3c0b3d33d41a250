// Sun and moon positions (libnova) against an independent astronomy library (astropy).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "nephele/sky.h"

namespace nephele {
namespace {

struct Row {
  std::string utc;
  double lat_deg, lon_deg, altitude_m;
  double sun_el, sun_az, moon_el, moon_az, fraction;
};

std::vector<Row> reference_rows() {
  std::ifstream file(NEPHELE_SOURCE_DIR "/tests/data/ephemeris_reference.csv");
  std::vector<Row> rows;
  std::string line;
  while (std::getline(file, line)) {
    if (line.empty() || line[0] == '#' || line.starts_with("utc")) continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream in(line);
    Row r;
    in >> r.utc >> r.lat_deg >> r.lon_deg >> r.altitude_m >> r.sun_el >> r.sun_az >> r.moon_el >>
        r.moon_az >> r.fraction;
    if (in) rows.push_back(r);
  }
  return rows;
}

// Azimuth difference in degrees, wrapped to [-180, 180].
double azimuth_diff(double a, double b) {
  double d = std::fmod(a - b + 540.0, 360.0) - 180.0;
  return d;
}

TEST(Ephemeris, SunAndMoonMatchTheReference) {
  const std::vector<Row> rows = reference_rows();
  ASSERT_EQ(rows.size(), 48u);
  double worst_sun = 0.0, worst_moon = 0.0, worst_fraction = 0.0;
  for (const Row& r : rows) {
    SCOPED_TRACE(r.utc);
    const std::optional<double> jd = julian_day_from_iso8601(r.utc);
    ASSERT_TRUE(jd.has_value());
    const Ephemeris e = compute_ephemeris(*jd, r.lat_deg, r.lon_deg, r.altitude_m);
    // Azimuth is compared as the arc it spans on the sky (it loses meaning at the zenith).
    const double sun_el = std::abs(e.sun.elevation_deg - r.sun_el);
    const double sun_az = std::abs(azimuth_diff(e.sun.azimuth_deg, r.sun_az));
    const double moon_el = std::abs(e.moon.elevation_deg - r.moon_el);
    const double moon_az = std::abs(azimuth_diff(e.moon.azimuth_deg, r.moon_az));
    EXPECT_LT(sun_el, 0.05);
    EXPECT_LT(sun_az * std::cos(r.sun_el * M_PI / 180.0), 0.05);
    EXPECT_LT(moon_el, 0.1);
    EXPECT_LT(moon_az * std::cos(r.moon_el * M_PI / 180.0), 0.1);
    EXPECT_NEAR(e.moon_illuminated_fraction, r.fraction, 0.01);
    worst_sun = std::max({worst_sun, sun_el, sun_az * std::cos(r.sun_el * M_PI / 180.0)});
    worst_moon = std::max({worst_moon, moon_el, moon_az * std::cos(r.moon_el * M_PI / 180.0)});
    worst_fraction = std::max(worst_fraction, std::abs(e.moon_illuminated_fraction - r.fraction));
  }
  std::printf("worst: sun %.4f deg, moon %.4f deg, illuminated fraction %.4f\n", worst_sun,
              worst_moon, worst_fraction);
}

TEST(Ephemeris, DirectionIsTheUnitVectorOfTheAngles) {
  const Ephemeris e = compute_ephemeris(*julian_day_from_iso8601("2026-06-21T18:30:00Z"), 48.85,
                                        2.35, 35.0);
  const double el = e.sun.elevation_deg * M_PI / 180.0, az = e.sun.azimuth_deg * M_PI / 180.0;
  EXPECT_NEAR(e.sun.direction.x, std::cos(el) * std::sin(az), 1e-6);
  EXPECT_NEAR(e.sun.direction.y, std::cos(el) * std::cos(az), 1e-6);
  EXPECT_NEAR(e.sun.direction.z, std::sin(el), 1e-6);
  EXPECT_NEAR(e.sun.distance_km, 1.5205e8, 0.002e8);  // near aphelion
  EXPECT_NEAR(e.moon.distance_km, 384400.0, 25000.0);
}

TEST(Ephemeris, Iso8601) {
  // J2000.0 is 2000-01-01T12:00:00 TT = JD 2451545.0; as UT here (the scale is the caller's).
  EXPECT_DOUBLE_EQ(*julian_day_from_iso8601("2000-01-01T12:00:00Z"), 2451545.0);
  EXPECT_NEAR(*julian_day_from_iso8601("2000-01-01T12:00:00.5Z"), 2451545.0 + 0.5 / 86400, 1e-9);
  EXPECT_NEAR(*julian_day_from_iso8601("2000-01-01T14:00:00+02:00"), 2451545.0, 1e-9);
  EXPECT_NEAR(*julian_day_from_iso8601("2000-01-01T07:30:00-04:30"), 2451545.0, 1e-9);
  EXPECT_NEAR(*julian_day_from_iso8601("2024-02-29T00:00Z"), 2460369.5, 1e-9);
  for (const char* bad : {"", "2026-06-21", "2026-06-21T18:30:00", "2026-13-01T00:00:00Z",
                          "2026-02-29T00:00:00Z", "2026-06-31T00:00:00Z", "2026-06-21T24:00:00Z",
                          "2026-06-21T18:60:00Z", "2026-06-21T18:30:00Zjunk", "21/06/2026 18:30",
                          "2026-06-21T18:30:00+25:00", "2026-06-21T18:30:5.5Z",
                          "2026-06-21T18:30:05.5.5Z", "2026-06-21T18:30:05.Z"})
    EXPECT_FALSE(julian_day_from_iso8601(bad).has_value()) << bad;
}

}  // namespace
}  // namespace nephele

// nephele — star catalogue and star field rotation.
#include "sky/stars.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include <glm/geometric.hpp>
#include <libnova/precession.h>

#include "nephele_embedded.h"

namespace nephele_data {  // defined by the generated embedded_data.cpp
extern const EmbeddedFile kFiles[];
extern const size_t kFileCount;
}  // namespace nephele_data

namespace nephele {

namespace {

constexpr double kSunVmag = -26.74;
constexpr double kDeg = M_PI / 180.0;

glm::dvec3 unit_from_ra_dec(double ra_deg, double dec_deg) {
  return {std::cos(dec_deg * kDeg) * std::cos(ra_deg * kDeg),
          std::cos(dec_deg * kDeg) * std::sin(ra_deg * kDeg), std::sin(dec_deg * kDeg)};
}

double planck(double wavelength_nm, double t_kelvin) {
  const double l = wavelength_nm * 1e-9;
  return 1.0 / (std::pow(l, 5.0) * (std::exp(1.4388e-2 / (l * t_kelvin)) - 1.0));
}

std::vector<Star> parse_catalogue() {
  const EmbeddedFile* file =
      find_embedded(nephele_data::kFiles, nephele_data::kFileCount, "stars.csv");
  std::vector<Star> stars;
  if (!file) return stars;
  std::istringstream in(std::string(reinterpret_cast<const char*>(file->data), file->size));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 'h') continue;
    int hr;
    double ra, dec, vmag, b_v;
    if (std::sscanf(line.c_str(), "%d,%lf,%lf,%lf,%lf", &hr, &ra, &dec, &vmag, &b_v) != 5) continue;
    Star s;
    s.dir_j2000 = glm::vec3(unit_from_ra_dec(ra, dec));
    s.vmag = float(vmag);
    s.b_v = float(b_v);
    s.irradiance = star_color(s.b_v) * float(std::pow(10.0, -0.4 * (vmag - kSunVmag)));
    stars.push_back(s);
  }
  return stars;
}

}  // namespace

const std::vector<Star>& star_catalogue() {
  static const std::vector<Star> stars = parse_catalogue();
  return stars;
}

glm::vec3 star_color(float b_v) {
  const double bv = std::clamp(double(b_v), -0.4, 2.5);
  const double t = 4600.0 * (1.0 / (0.92 * bv + 1.7) + 1.0 / (0.92 * bv + 0.62));
  const double nm[3] = {610.0, 550.0, 465.0};
  glm::dvec3 rgb;
  for (int i = 0; i < 3; ++i) rgb[i] = planck(nm[i], t) / planck(nm[i], 5778.0);
  return glm::vec3(rgb / glm::dot(rgb, glm::dvec3(0.2126, 0.7152, 0.0722)));
}

glm::mat3 enu_from_j2000(double jd_ut, double lat_deg, double lst_deg) {
  // Precession: where the J2000 axes point among the coordinates of the date.
  glm::dmat3 precession;
  const double axes[3][2] = {{0.0, 0.0}, {90.0, 0.0}, {0.0, 90.0}};
  for (int i = 0; i < 3; ++i) {
    ln_equ_posn j2000{axes[i][0], axes[i][1]}, date;
    ln_get_equ_prec(&j2000, jd_ut, &date);
    precession[i] = unit_from_ra_dec(date.ra, date.dec);  // column i
  }
  // Equatorial of the date to east-north-up: hour angle H = LST - RA.
  const double c = std::cos(lst_deg * kDeg), s = std::sin(lst_deg * kDeg);
  const double sp = std::sin(lat_deg * kDeg), cp = std::cos(lat_deg * kDeg);
  // (x, y, z) equatorial -> (cos d cos H, -cos d sin H, sin d) = rotation about z by -LST.
  const glm::dmat3 hour(glm::dvec3(c, -s, 0.0), glm::dvec3(s, c, 0.0), glm::dvec3(0.0, 0.0, 1.0));
  // (a, b, z) -> east b, north -sin(lat) a + cos(lat) z, up cos(lat) a + sin(lat) z.
  const glm::dmat3 horizon(glm::dvec3(0.0, -sp, cp), glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, cp, sp));
  return glm::mat3(horizon * hour * precession);
}

}  // namespace nephele

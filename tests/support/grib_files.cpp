#include "support/grib_files.h"

#include <eccodes.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace nephele::test {

namespace {
void check(int error, const char* what) {
  if (error != 0)
    throw std::runtime_error(std::string("ecCodes: ") + what + ": " +
                             codes_get_error_message(error));
}
}  // namespace

void write_grib(const std::string& path, const std::vector<GribField>& fields) {
  std::remove(path.c_str());
  for (const GribField& f : fields) {
    codes_handle* h = codes_grib_handle_new_from_samples(
        nullptr, f.level_hpa > 0 ? "regular_ll_pl_grib2" : "regular_ll_sfc_grib2");
    if (!h) throw std::runtime_error("ecCodes: no GRIB2 sample");
    const GribGrid& g = f.grid;
    const long ni = std::lround((g.east_deg - g.west_deg) / g.step_deg) + 1;
    const long nj = std::lround((g.north_deg - g.south_deg) / g.step_deg) + 1;
    check(codes_set_long(h, "Ni", ni), "Ni");
    check(codes_set_long(h, "Nj", nj), "Nj");
    check(codes_set_long(h, "jScansPositively", 0), "jScansPositively");
    check(codes_set_double(h, "latitudeOfFirstGridPointInDegrees", g.north_deg), "lat first");
    check(codes_set_double(h, "longitudeOfFirstGridPointInDegrees", g.west_deg), "lon first");
    check(codes_set_double(h, "latitudeOfLastGridPointInDegrees", g.south_deg), "lat last");
    check(codes_set_double(h, "longitudeOfLastGridPointInDegrees", g.east_deg), "lon last");
    check(codes_set_double(h, "iDirectionIncrementInDegrees", g.step_deg), "di");
    check(codes_set_double(h, "jDirectionIncrementInDegrees", g.step_deg), "dj");
    if (f.parameter_number >= 0) {
      check(codes_set_long(h, "discipline", 0), "discipline");
      check(codes_set_long(h, "parameterCategory", 6), "category");
      check(codes_set_long(h, "parameterNumber", f.parameter_number), "number");
      if (f.surface >= 0) {
        check(codes_set_long(h, "typeOfFirstFixedSurface", f.surface), "surface");
        codes_set_missing(h, "scaleFactorOfFirstFixedSurface");
        codes_set_missing(h, "scaledValueOfFirstFixedSurface");
      }
    } else {
      size_t length = f.short_name.size();
      check(codes_set_string(h, "shortName", f.short_name.c_str(), &length), "shortName");
    }
    if (f.level_hpa > 0) check(codes_set_long(h, "level", f.level_hpa), "level");
    check(codes_set_long(h, "dataDate", f.date), "dataDate");
    check(codes_set_long(h, "dataTime", f.time), "dataTime");
    check(codes_set_long(h, "forecastTime", f.step_h), "forecastTime");
    std::vector<double> values(size_t(ni * nj));
    for (long j = 0; j < nj; ++j)
      for (long i = 0; i < ni; ++i)
        values[size_t(j * ni + i)] =
            f.value(g.north_deg - double(j) * g.step_deg, g.west_deg + double(i) * g.step_deg) *
            f.scale;
    check(codes_set_double_array(h, "values", values.data(), values.size()), "values");
    check(codes_write_message(h, path.c_str(), "a"), "write");
    codes_handle_delete(h);
  }
}

}  // namespace nephele::test

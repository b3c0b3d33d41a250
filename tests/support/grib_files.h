// GRIB files for the forecast's tests, written with ecCodes from its own samples
// (regular_ll_sfc_grib2, regular_ll_pl_grib2): cloud cover fields on a regular
// latitude/longitude grid, in ECMWF's or the WMO's parameters.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace nephele::test {

struct GribGrid {
  double north_deg = 60.0, south_deg = 30.0, west_deg = -10.0, east_deg = 30.0, step_deg = 0.5;
};

struct GribField {
  // ecCodes' short name ("lcc", "tcc", "cc", "t") or, with parameter_number >= 0, the WMO
  // parameter (discipline 0, category 6) of that number on the surface type `surface` (214
  // the low cloud layer, 10 the entire atmosphere, ...).
  std::string short_name = "lcc";
  long parameter_number = -1;
  long surface = -1;
  long level_hpa = 0;                             // > 0: on that pressure level
  long date = 20261203, time = 1200, step_h = 0;  // validity: date, time + step
  double scale = 1.0;  // the file's values are value(...) x scale (100 for %)
  GribGrid grid;
  std::function<double(double lat_deg, double lon_deg)> value = [](double, double) { return 0.5; };
};

// Appends each field as one message to a new file at `path`.
void write_grib(const std::string& path, const std::vector<GribField>& fields);

}  // namespace nephele::test

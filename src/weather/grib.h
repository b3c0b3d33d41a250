// nephele — cloud cover from a GRIB forecast (GRIB2 or GRIB1, read with ecCodes): total, low,
// medium and high cloud cover, and cloud cover on pressure levels where the file has it, on a
// regular latitude/longitude (or Gaussian) grid. The fields valid at the scene's time (blended
// linearly between the two validity times around it) are resampled onto a square of the ground
// centred on the observer (the scene's location), fixed to the ground: a forecast's field neither
// repeats nor drifts with the wind as the procedural weather map does. The weather state takes the
// layers from it (weather_from_grib) and the clouds read the map (render/modules/weather).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "nephele/scene.h"
#include "weather/weather_state.h"

namespace nephele::weather {

// The map around the observer: kForecastMapSize^2 texels over 2 kForecastHalfExtentM a side
// (4.7 km texels, finer than any global model's grid), as far as the horizon of a cloud top at
// 7 km.
constexpr int kForecastMapSize = 128;
constexpr float kForecastHalfExtentM = 300e3f;

// The cover fields, by the layer of cloud they describe.
enum CoverField { kTotalCover, kLowCover, kMediumCover, kHighCover, kCoverFields };
const char* cover_field_name(int field);  // "total", "low", "medium", "high"

struct GribCover {
  std::string path;
  // ISO 8601, UTC: the fields' validity time, and where the scene's lies between two, the next
  // one and how far towards it the fields are blended (0 to 1; 0 and "" otherwise).
  std::string valid_time, valid_time_next;
  float blend = 0.0f;
  int messages = 0;        // in the file
  int valid_times = 0;     // distinct validity times of cloud cover in the file
  std::array<bool, kCoverFields> has{};
  std::array<float, kCoverFields> at_observer{};  // [0, 1]
  // Cloud cover on pressure levels at the observer, by increasing altitude: (altitude above
  // sea level in the standard atmosphere (m), cover [0, 1]).
  std::vector<std::pair<float, float>> profile;
  // The observer's box: kForecastMapSize^2 texels, rows from the south, columns from the west;
  // each the cover [0, 1] of the low, medium and high layers and the total. A file with total
  // cover alone gives it as the low layer's.
  std::vector<std::array<float, kCoverFields>> map;
  // The share of the box the grid covers (beyond it the grid's edge is held).
  float box_covered = 0.0f;
  std::string grid;  // "regular_ll 0.25 x 0.25 deg, 41 x 33 points"
};

// Reads `path` and resamples the cloud cover valid at `jd_ut` (a Julian day: between two
// validity times, blended linearly; before the first or after the last, that one; none: the
// earliest in the file) around latitude/longitude (deg) on a sphere of `planet_radius_m`.
// Throws InputError, one line naming the file and what is wrong: not readable, not GRIB, no
// cloud cover field (listing what it holds), a grid that is not a regular latitude/longitude
// or Gaussian one, or one that does not cover the observer.
GribCover read_grib_cover(const std::string& path, double lat_deg, double lon_deg,
                          std::optional<double> jd_ut, double planet_radius_m);

// read_grib_cover for the scene's weather.grib, location, time (+ time_s) and planet, read
// once per file and place (a file rewritten is read again).
std::shared_ptr<const GribCover> grib_cover(const Scene& scene);

// The weather the forecast gives over `base` (what it does not give is kept): the low layer
// from low cover (stratocumulus where it is 5 oktas or more, else cumulus), the high volumetric
// layer from medium cover (altocumulus), the sheet from high cover (cirrus, cirrostratus from
// 6 oktas). Each layer's cover is its greatest in the box (the map scales it down elsewhere);
// where the file has cover on pressure levels, a layer's base and top are the levels' it
// spans, else its genus' own. `ground_m` the ground's altitude above sea level.
WeatherState weather_from_grib(const GribCover& cover, const WeatherState& base, float ground_m);

// The map as the clouds read it (binding forecast_cover): per texel the low layer's, the high
// volumetric layer's and the sheet's coverage as a share of the layer's own (its greatest),
// with the coverage from oktas for the layers' types (coverage_for_oktas), RGBA 8 bits, rows
// from the south.
std::vector<std::array<uint8_t, 4>> forecast_texels(const GribCover& cover, const Scene& scene);

// Applies scene.weather.grib (after a METAR, before the wind and visibility keys): its layers,
// and the scene's time where it has none. Throws InputError ("weather.grib: ...") and leaves
// the scene unchanged. Nothing without a file.
void apply_grib(Scene& scene);

// What --verbose prints: the file, its grid and time, the cover at the observer and in the box,
// the layers drawn.
std::vector<std::string> describe_grib(const Scene& scene);

}  // namespace nephele::weather

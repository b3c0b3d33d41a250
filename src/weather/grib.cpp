#include "weather/grib.h"

#include <eccodes.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <tuple>

#include "nephele/error.h"
#include "nephele/sky.h"

namespace nephele::weather {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kLevelCover = -1;  // cloud cover on a pressure level
constexpr int kNotCover = -2;

// Low, middle and high clouds' altitudes above the ground (WMO's étages in mid-latitudes).
constexpr float kMiddleFromM = 2000.0f, kHighFromM = 7000.0f;

// A field on a latitude/longitude grid: latitudes and longitudes increasing, values[j * ni + i]
// (NaN where the file has none).
struct Grid {
  std::vector<double> lats, lons;
  std::vector<float> values;
  bool periodic = false;  // the longitudes go round the earth
};

struct Message {
  int field = kNotCover;
  float level_hpa = 0.0f;
  double jd = 0.0;
  std::string time;
  Grid grid;
};

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw InputError("weather.grib '" + shorten_path_for_message(path) + "': " + why);
}

void quiet(const codes_context*, int, const char*) {}

struct Handle {
  codes_handle* h = nullptr;
  ~Handle() {
    if (h) codes_handle_delete(h);
  }
  long get_long(const char* key, long otherwise = -1) const {
    long v = 0;
    return codes_is_defined(h, key) && codes_get_long(h, key, &v) == 0 ? v : otherwise;
  }
  std::string get_string(const char* key) const {
    char text[256] = {};
    size_t length = sizeof(text);
    return codes_is_defined(h, key) && codes_get_string(h, key, text, &length) == 0 ? text : "";
  }
  std::vector<double> get_doubles(const char* key) const {
    size_t n = 0;
    if (codes_get_size(h, key, &n) != 0) return {};
    std::vector<double> v(n);
    if (codes_get_double_array(h, key, v.data(), &n) != 0) return {};
    v.resize(n);
    return v;
  }
};

// Which cover a message holds: by its GRIB2 parameter (discipline 0, category 6 cloud: WMO's
// 1 total, 3-5 low, medium, high, 22 cloud cover on a level; ECMWF's local 192-195 and 32) and
// level type (NCEP gives total cover in the low, middle and high cloud layers, 214, 224, 234),
// else by ecCodes' short name (GRIB1 too).
int classify(const Handle& m, float& level_hpa) {
  const std::string short_name = m.get_string("shortName");
  const std::string level_type = m.get_string("typeOfLevel");
  const bool isobaric = level_type == "isobaricInhPa" || level_type == "isobaricInPa";
  if (isobaric) {
    const long level = m.get_long("level", 0);
    level_hpa = level_type == "isobaricInPa" ? float(level) / 100.0f : float(level);
  }
  int field = kNotCover;
  if (m.get_long("edition") == 2 && m.get_long("discipline") == 0 &&
      m.get_long("parameterCategory") == 6) {
    const long number = m.get_long("parameterNumber");
    const long surface = m.get_long("typeOfFirstFixedSurface");
    if (number == 1 || number == 192)
      field = surface == 214   ? kLowCover
              : surface == 224 ? kMediumCover
              : surface == 234 ? kHighCover
              : isobaric       ? kLevelCover
                               : kTotalCover;
    else if (number == 3 || number == 193)
      field = kLowCover;
    else if (number == 4 || number == 194)
      field = kMediumCover;
    else if (number == 5 || number == 195)
      field = kHighCover;
    else if ((number == 22 || number == 32) && isobaric)
      field = kLevelCover;
  }
  if (field == kNotCover) {
    if (short_name == "tcc" || short_name == "tcdc")
      field = level_type == "lowCloudLayer"      ? kLowCover
              : level_type == "middleCloudLayer" ? kMediumCover
              : level_type == "highCloudLayer"   ? kHighCover
              : isobaric                         ? kLevelCover
                                                 : kTotalCover;
    else if (short_name == "lcc")
      field = kLowCover;
    else if (short_name == "mcc")
      field = kMediumCover;
    else if (short_name == "hcc")
      field = kHighCover;
    else if ((short_name == "cc" || short_name == "ccl") && isobaric)
      field = kLevelCover;
  }
  return field;
}

std::vector<double> distinct(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  std::vector<double> out;
  for (double x : v)
    if (out.empty() || x - out.back() > 1e-6) out.push_back(x);
  return out;
}

size_t index_of(const std::vector<double>& axis, double x) {
  return size_t(std::lower_bound(axis.begin(), axis.end(), x - 1e-6) - axis.begin());
}

Grid read_grid(const Handle& m, const std::string& path, int number) {
  const std::string type = m.get_string("gridType");
  const std::string where = "message " + std::to_string(number);
  if (type != "regular_ll" && type != "regular_gg")
    refuse(path, where + ": grid type '" + type +
                     "': only regular latitude/longitude or Gaussian grids are read");
  std::vector<double> lats = m.get_doubles("latitudes"), lons = m.get_doubles("longitudes");
  std::vector<double> values = m.get_doubles("values");
  if (values.empty() || lats.size() != values.size() || lons.size() != values.size())
    refuse(path, where + ": its values and coordinates could not be read");
  // Longitudes from the westernmost, within one turn of it.
  const double west = *std::min_element(lons.begin(), lons.end());
  for (double& lon : lons) lon = west + std::fmod(lon - west + 720.0, 360.0);
  Grid g;
  g.lats = distinct(lats);
  g.lons = distinct(lons);
  if (g.lats.size() * g.lons.size() != values.size() || g.lats.size() < 2 || g.lons.size() < 2)
    refuse(path, where + ": its " + std::to_string(values.size()) +
                     " points are no latitude/longitude grid of at least 2 x 2");
  const double step = g.lons[1] - g.lons[0];
  g.periodic = g.lons.back() - g.lons.front() + step > 359.999;
  const bool bitmap = m.get_long("bitmapPresent", 0) == 1;
  double missing = 9999.0;
  if (bitmap) codes_get_double(m.h, "missingValue", &missing);
  bool percent = m.get_string("units") == "%";
  g.values.assign(values.size(), std::numeric_limits<float>::quiet_NaN());
  for (size_t k = 0; k < values.size(); ++k) {
    if (bitmap && values[k] == missing) continue;
    if (values[k] > 1.5) percent = true;  // a fraction never exceeds 1
    g.values[index_of(g.lats, lats[k]) * g.lons.size() + index_of(g.lons, lons[k])] =
        float(values[k]);
  }
  const float scale = percent ? 0.01f : 1.0f;
  for (float& v : g.values)
    if (!std::isnan(v)) v = std::clamp(v * scale, 0.0f, 1.0f);
  return g;
}

// The longitude as the grid counts it, or none outside it.
std::optional<double> grid_lon(const Grid& g, double lon) {
  const double west = g.lons.front();
  lon = west + std::fmod(std::fmod(lon - west, 360.0) + 360.0, 360.0);
  if (g.periodic || lon <= g.lons.back() + 1e-6) return lon;
  return std::nullopt;
}

bool covers(const Grid& g, double lat, double lon) {
  return lat >= g.lats.front() - 1e-6 && lat <= g.lats.back() + 1e-6 && grid_lon(g, lon);
}

// Bilinear between the grid's points (round the earth where it goes round; the edge held
// beyond it); points without a value are left out.
float sample(const Grid& g, double lat, double lon) {
  const auto bracket = [](const std::vector<double>& axis, double x, size_t& i0, double& f) {
    x = std::clamp(x, axis.front(), axis.back());
    i0 = std::min(size_t(std::upper_bound(axis.begin(), axis.end(), x) - axis.begin()),
                  axis.size() - 1) -
         1;
    f = (x - axis[i0]) / (axis[i0 + 1] - axis[i0]);
  };
  size_t j0, i0, i1;
  double fy, fx;
  bracket(g.lats, lat, j0, fy);
  const double west = g.lons.front();
  double x = west + std::fmod(std::fmod(lon - west, 360.0) + 360.0, 360.0);
  if (g.periodic && x > g.lons.back()) {  // between the last column and the first
    i0 = g.lons.size() - 1;
    i1 = 0;
    fx = (x - g.lons.back()) / (west + 360.0 - g.lons.back());
  } else {
    if (!g.periodic && x > g.lons.back())  // east of the grid, or west of it
      x = x - g.lons.back() < west + 360.0 - x ? g.lons.back() : west;
    bracket(g.lons, x, i0, fx);
    i1 = i0 + 1;
  }
  const size_t ni = g.lons.size();
  double sum = 0.0, weight = 0.0;
  for (int k = 0; k < 4; ++k) {
    const size_t j = j0 + size_t(k >> 1), i = (k & 1) ? i1 : i0;
    const double w = ((k >> 1) ? fy : 1.0 - fy) * ((k & 1) ? fx : 1.0 - fx);
    const float v = g.values[j * ni + i];
    if (std::isnan(v) || w <= 0.0) continue;
    sum += w * v;
    weight += w;
  }
  return weight > 0.0 ? float(sum / weight) : 0.0f;
}

std::string grid_text(const Handle& m, const Grid& g) {
  char text[160];
  std::snprintf(text, sizeof(text),
                "%s, %zu x %zu points, latitudes %.2f to %.2f, longitudes %.2f to %.2f",
                m.get_string("gridType").c_str(), g.lons.size(), g.lats.size(), g.lats.front(),
                g.lats.back(), g.lons.front(), g.lons.back());
  return text;
}

// The altitude (m above sea level) of a pressure in the standard atmosphere's troposphere.
float standard_altitude_m(float p_hpa) {
  return 44330.8f * (1.0f - std::pow(p_hpa / 1013.25f, 0.190263f));
}

}  // namespace

const char* cover_field_name(int field) {
  static const char* const kNames[] = {"total", "low", "medium", "high"};
  return field >= 0 && field < kCoverFields ? kNames[field] : "level";
}

GribCover read_grib_cover(const std::string& path, double lat_deg, double lon_deg,
                          std::optional<double> jd_ut, double planet_radius_m) {
  // A regular file only: a device (/dev/zero) or a pipe would be read for ever.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    refuse(path, "is not a regular file");
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) refuse(path, "cannot be read");
  codes_context_set_logging_proc(codes_context_get_default(), quiet);
  GribCover out;
  out.path = path;
  std::vector<Message> messages;
  std::set<std::string> others;
  std::string grid_description;
  int error = 0;
  try {
    for (;;) {
      Handle m;
      m.h = codes_handle_new_from_file(nullptr, file, PRODUCT_GRIB, &error);
      if (!m.h) break;
      ++out.messages;
      Message msg;
      msg.field = classify(m, msg.level_hpa);
      if (msg.field == kNotCover) {
        if (others.size() < 8) others.insert(m.get_string("shortName"));
        continue;
      }
      char time[64];
      const long date = m.get_long("validityDate", 0), clock = m.get_long("validityTime", 0);
      std::snprintf(time, sizeof(time), "%04ld-%02ld-%02ldT%02ld:%02ld:00Z", date / 10000,
                    date / 100 % 100, date % 100, clock / 100, clock % 100);
      msg.time = time;
      const std::optional<double> jd = julian_day_from_iso8601(time);
      if (!jd)
        refuse(path, "message " + std::to_string(out.messages) + ": validity time " + time +
                         " is no date");
      msg.jd = *jd;
      msg.grid = read_grid(m, path, out.messages);
      if (grid_description.empty()) grid_description = grid_text(m, msg.grid);
      messages.push_back(std::move(msg));
    }
  } catch (...) {
    std::fclose(file);
    throw;
  }
  std::fclose(file);
  if (error != 0 && out.messages == 0)
    refuse(path, std::string("not a GRIB file (ecCodes: ") + codes_get_error_message(error) + ")");
  if (out.messages == 0) refuse(path, "holds no GRIB message");
  if (error != 0)
    refuse(path, "message " + std::to_string(out.messages + 1) +
                     " is damaged (ecCodes: " + codes_get_error_message(error) + ")");
  if (messages.empty()) {
    std::string held;
    for (const std::string& name : others) held += (held.empty() ? "" : ", ") + name;
    refuse(path,
           "no cloud cover field (total, low, medium or high: tcc, lcc, mcc, hcc, or cc "
           "on pressure levels) in its " +
               std::to_string(out.messages) + " messages (they hold " + held + ")");
  }
  // The validity times around the scene's: between two, each field is blended linearly in time
  // (a model's output steps are hours apart, and a sequence must not jump at the half-way
  // point); before the first or after the last, that one; without a time, the earliest.
  std::set<double> times;
  for (const Message& m : messages) times.insert(m.jd);
  out.valid_times = int(times.size());
  double t0 = *times.begin(), t1 = t0;
  if (jd_ut) {
    const auto after = times.upper_bound(*jd_ut);
    if (after == times.end()) {
      t0 = t1 = *times.rbegin();
    } else if (after != times.begin()) {
      t1 = *after;
      t0 = *std::prev(after);
      out.blend = float((*jd_ut - t0) / (t1 - t0));
    }
  }
  struct AtTime {
    std::array<const Grid*, kCoverFields> fields{};
    std::vector<const Message*> levels;
  };
  AtTime at[2];
  for (const Message& m : messages)
    for (int k = 0; k < 2; ++k) {
      if (std::abs(m.jd - (k == 0 ? t0 : t1)) > 1e-6) continue;
      (k == 0 ? out.valid_time : out.valid_time_next) = m.time;
      if (m.field == kLevelCover)
        at[k].levels.push_back(&m);
      else if (!at[k].fields[size_t(m.field)])
        at[k].fields[size_t(m.field)] = &m.grid;
    }
  if (out.blend == 0.0f) out.valid_time_next.clear();
  out.grid = grid_description;
  // The observer must be on every field's grid.
  const auto check_covers = [&](const Grid& g) {
    if (!covers(g, lat_deg, lon_deg)) {
      char text[200];
      std::snprintf(text, sizeof(text),
                    "its grid (latitudes %.2f to %.2f, longitudes %.2f to %.2f) does not cover the "
                    "observer at latitude %.4f, longitude %.4f (location.lat_deg, lon_deg)",
                    g.lats.front(), g.lats.back(), g.lons.front(), g.lons.back(), lat_deg, lon_deg);
      refuse(path, text);
    }
  };
  for (AtTime& a : at) {
    for (const Grid* g : a.fields)
      if (g) check_covers(*g);
    for (const Message* m : a.levels) check_covers(m->grid);
    // Total cover alone stands for the low layer's.
    if (a.fields[kTotalCover] && !a.fields[kLowCover] && !a.fields[kMediumCover] &&
        !a.fields[kHighCover])
      a.fields[kLowCover] = a.fields[kTotalCover];
  }
  // A field's cover at a place: blended where both times hold it, else the one that does.
  const float w = out.blend;
  const auto cover_at = [&](int f, double lat, double lon) {
    const Grid* a = at[0].fields[size_t(f)];
    const Grid* b = at[1].fields[size_t(f)];
    if (a && b && w > 0.0f) return (1.0f - w) * sample(*a, lat, lon) + w * sample(*b, lat, lon);
    return sample(a ? *a : *b, lat, lon);
  };
  std::array<const Grid*, kCoverFields> fields{};
  for (int f = 0; f < kCoverFields; ++f) {
    fields[size_t(f)] = at[0].fields[size_t(f)] ? at[0].fields[size_t(f)] : at[1].fields[size_t(f)];
    out.has[size_t(f)] = fields[size_t(f)] != nullptr;
    if (fields[size_t(f)]) out.at_observer[size_t(f)] = cover_at(f, lat_deg, lon_deg);
  }
  for (const Message* m : at[0].levels) {
    float cover = sample(m->grid, lat_deg, lon_deg);
    for (const Message* n : at[1].levels)
      if (w > 0.0f && n->level_hpa == m->level_hpa)
        cover = (1.0f - w) * cover + w * sample(n->grid, lat_deg, lon_deg);
    out.profile.emplace_back(standard_altitude_m(m->level_hpa), cover);
  }
  std::sort(out.profile.begin(), out.profile.end());
  // The box around the observer, on the tangent plane (equirectangular: within 0.2% at 300 km).
  const int n = kForecastMapSize;
  out.map.assign(size_t(n) * size_t(n), {});
  const double deg = 180.0 / kPi;
  const double cos_lat = std::max(std::cos(lat_deg / deg), 1e-3);
  const Grid* any = nullptr;
  for (const Grid* g : fields) any = any ? any : g;
  int inside = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double east = ((i + 0.5) / n - 0.5) * 2.0 * kForecastHalfExtentM;
      const double north = ((j + 0.5) / n - 0.5) * 2.0 * kForecastHalfExtentM;
      const double lat = std::clamp(lat_deg + north / planet_radius_m * deg, -90.0, 90.0);
      const double lon = lon_deg + east / (planet_radius_m * cos_lat) * deg;
      auto& texel = out.map[size_t(j) * size_t(n) + size_t(i)];
      for (int f = 0; f < kCoverFields; ++f)
        if (fields[size_t(f)]) texel[size_t(f)] = cover_at(f, lat, lon);
      if (any && covers(*any, lat, lon)) ++inside;
    }
  out.box_covered = float(inside) / float(n * n);
  return out;
}

std::shared_ptr<const GribCover> grib_cover(const Scene& scene) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const GribCover>> cache;
  const std::string& path = scene.weather.grib;
  std::error_code ec;
  const auto written = std::filesystem::last_write_time(path, ec);
  const std::optional<double> jd =
      scene.time.empty() ? std::nullopt : julian_day_from_iso8601(scene.time);
  const std::optional<double> now =
      jd ? std::optional<double>(*jd + double(scene.time_s) / 86400.0) : std::nullopt;
  char key[512];
  std::snprintf(key, sizeof(key), "%s|%lld|%.6f|%.6f|%.6f|%.1f", path.c_str(),
                ec ? -1LL : (long long)written.time_since_epoch().count(),
                double(scene.location.lat_deg), double(scene.location.lon_deg), now ? *now : -1.0,
                1000.0 * double(scene.atmosphere.planet_radius_km));
  std::lock_guard lock(mutex);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  auto cover = std::make_shared<const GribCover>(
      read_grib_cover(path, scene.location.lat_deg, scene.location.lon_deg, now,
                      1000.0 * double(scene.atmosphere.planet_radius_km)));
  if (cache.size() >= 16) cache.clear();
  cache[key] = cover;
  return cover;
}

namespace {

// A layer's cloud base and top above the ground from the levels of its étage with cover
// (at least 5%), or none.
std::optional<glm::vec2> levels_span(const GribCover& cover, float ground_m, float from_m,
                                     float to_m) {
  std::optional<glm::vec2> span;
  for (size_t k = 0; k < cover.profile.size(); ++k) {
    const float above = cover.profile[k].first - ground_m;
    if (above < from_m || above >= to_m || cover.profile[k].second < 0.05f) continue;
    // Half-way to the levels on either side.
    const float below_m =
        k > 0 ? 0.5f * (cover.profile[k - 1].first - ground_m + above) : above - 250.0f;
    const float over_m = k + 1 < cover.profile.size()
                             ? 0.5f * (cover.profile[k + 1].first - ground_m + above)
                             : above + 250.0f;
    if (!span) span = glm::vec2(below_m, over_m);
    span->x = std::min(span->x, below_m);
    span->y = std::max(span->y, over_m);
  }
  if (span) span->x = std::max(span->x, 100.0f);
  return span;
}

float greatest(const GribCover& cover, int field) {
  float most = 0.0f;
  for (const auto& texel : cover.map) most = std::max(most, texel[size_t(field)]);
  return most;
}

}  // namespace

WeatherState weather_from_grib(const GribCover& cover, const WeatherState& base, float ground_m) {
  WeatherState s = base;
  std::optional<glm::vec2> low_clouds_m, high_clouds_m;  // where each layer's clouds are
  const auto volumetric = [&](CloudLayer& layer, int field, Genus genus, glm::vec2 cloud_m,
                              float from_m, float to_m) -> std::optional<glm::vec2> {
    if (!cover.has[size_t(field)]) return std::nullopt;
    const float most = greatest(cover, field);
    layer.genus = genus;
    layer.type = -1.0f;
    layer.coverage_oktas = 8.0f * most;
    const glm::vec2 span = levels_span(cover, ground_m, from_m, to_m).value_or(cloud_m);
    const float type = genus_type(genus);
    const glm::vec2 shell =
        cloud_shell_m(type, coverage_for_oktas(layer.coverage_oktas, type), span.x, span.y);
    layer.base_m = shell.x;
    layer.top_m = shell.y;
    return span;
  };
  const bool low_deck = greatest(cover, kLowCover) >= 0.625f;
  low_clouds_m = volumetric(s.low, kLowCover, low_deck ? Genus::Stratocumulus : Genus::Cumulus,
                            low_deck ? glm::vec2(1000.0f, 1800.0f) : glm::vec2(1200.0f, 2700.0f),
                            0.0f, kMiddleFromM);
  high_clouds_m = volumetric(s.high, kMediumCover, Genus::Altocumulus, glm::vec2(3500.0f, 4500.0f),
                             kMiddleFromM, kHighFromM);
  if (s.low.top_m > s.high.base_m) {
    if (low_clouds_m && high_clouds_m) {
      // The shells hold more than the clouds: they meet half way between the low clouds' tops
      // and the high clouds' bases (as a report's layers do, metar_weather.cpp).
      const float meet_m = 0.5f * (low_clouds_m->y + high_clouds_m->x);
      s.low.top_m = std::min(s.low.top_m, meet_m);
      s.high.base_m = std::max(s.high.base_m, meet_m);
    } else {
      s.high.base_m = s.low.top_m;  // clear of the low layer
    }
    s.high.top_m = std::max(s.high.top_m, s.high.base_m + 1000.0f);
  }
  if (cover.has[kHighCover]) {
    const float most = greatest(cover, kHighCover);
    s.sheet.genus = most >= 0.75f ? Genus::Cirrostratus : Genus::Cirrus;
    s.sheet.type = -1.0f;
    s.sheet.coverage_oktas = 8.0f * most;
    const glm::vec2 span =
        levels_span(cover, ground_m, kHighFromM, 20000.0f).value_or(glm::vec2(9000.0f));
    s.sheet.base_m = s.sheet.top_m =
        std::max({0.5f * (span.x + span.y), s.high.top_m, s.low.top_m});
  }
  return s;
}

std::vector<std::array<uint8_t, 4>> forecast_texels(const GribCover& cover, const Scene& scene) {
  const auto share = [](float coverage, float own) {
    return own > 0.0f ? std::clamp(coverage / own, 0.0f, 1.0f) : 0.0f;
  };
  const auto unorm = [](float v) {
    return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
  };
  std::vector<std::array<uint8_t, 4>> texels(cover.map.size());
  for (size_t k = 0; k < cover.map.size(); ++k) {
    const auto& c = cover.map[k];
    const float low = cover.has[kLowCover]
                          ? share(coverage_for_oktas(8.0f * c[kLowCover], scene.clouds.type),
                                  scene.clouds.coverage)
                          : 1.0f;
    const float high =
        cover.has[kMediumCover]
            ? share(coverage_for_oktas(8.0f * c[kMediumCover], scene.high_clouds.type),
                    scene.high_clouds.coverage)
            : 1.0f;
    const float sheet =
        cover.has[kHighCover]
            ? share(sheet_coverage_for_oktas(8.0f * c[kHighCover], scene.cirrus.type),
                    scene.cirrus.coverage)
            : 1.0f;
    texels[k] = {unorm(low), unorm(high), unorm(sheet), 255};
  }
  return texels;
}

void apply_grib(Scene& scene) {
  if (scene.weather.grib.empty()) return;
  const std::shared_ptr<const GribCover> cover = grib_cover(scene);
  Scene result = scene;
  apply_weather(weather_from_grib(*cover, weather_state(scene), scene.location.altitude_m), result);
  if (result.time.empty()) result.time = cover->valid_time;
  scene = result;
}

std::vector<std::string> describe_grib(const Scene& scene) {
  if (scene.weather.grib.empty()) return {};
  const std::shared_ptr<const GribCover> cover = grib_cover(scene);
  std::vector<std::string> lines;
  char text[320];
  char blend[96] = "";
  if (cover->blend > 0.0f)
    std::snprintf(blend, sizeof(blend), ", %.2f of the way to %s", double(cover->blend),
                  cover->valid_time_next.c_str());
  std::snprintf(text, sizeof(text),
                "weather.grib: %s: %d messages, %s; cloud cover valid %s%s (of %d times)",
                shorten_path_for_message(cover->path).c_str(), cover->messages, cover->grid.c_str(),
                cover->valid_time.c_str(), blend, cover->valid_times);
  lines.push_back(text);
  for (int f = 0; f < kCoverFields; ++f) {
    if (!cover->has[size_t(f)]) continue;
    std::snprintf(text, sizeof(text),
                  "  %s cover: %.0f%% at the observer, up to %.0f%% within %.0f km",
                  cover_field_name(f), 100.0 * cover->at_observer[size_t(f)],
                  100.0 * greatest(*cover, f), kForecastHalfExtentM / 1000.0);
    lines.push_back(text);
  }
  for (const auto& [altitude_m, c] : cover->profile) {
    std::snprintf(text, sizeof(text), "  cover %.0f%% at %.0f m (pressure level)", 100.0 * c,
                  double(altitude_m));
    lines.push_back(text);
  }
  // The layers drawn, as the scene holds them after apply_grib.
  const WeatherState state = weather_state(scene);
  for (const auto& [slot, layer, field] : {std::tuple{"low", &state.low, kLowCover},
                                           {"high", &state.high, kMediumCover},
                                           {"sheet", &state.sheet, kHighCover}}) {
    if (!cover->has[size_t(field)]) continue;
    std::snprintf(text, sizeof(text),
                  "  %s layer: %s, %.0f-%.0f m above the ground, up to %.1f oktas", slot,
                  to_string(layer->genus), double(layer->base_m), double(layer->top_m),
                  double(layer->coverage_oktas));
    lines.push_back(text);
  }
  if (cover->box_covered < 1.0f) {
    std::snprintf(
        text, sizeof(text),
        "  the grid covers %.0f%% of the %.0f km box around the observer; its edge is held beyond",
        100.0 * cover->box_covered, 2.0 * kForecastHalfExtentM / 1000.0);
    lines.push_back(text);
  }
  return lines;
}

}  // namespace nephele::weather

// nephele — the weather state and its application to the scene (weather_state.h).
#include "weather/weather_state.h"

#include <algorithm>
#include <cmath>
#include <glm/trigonometric.hpp>
#include <iterator>

#include "nephele/error.h"
#include "render/glsl.h"
#include "render/modules/precipitation/precipitation.h"
#include "scene/scene_fields.h"

namespace nephele::weather {
namespace {

using scene_detail::format_float;

// The volumetric genera in the order of clouds.type's scale (0, 0.25, ... 1), and the sheet's
// in cirrus.type's (0, 0.5, 1).
constexpr Genus kVolumetric[] = {Genus::Stratus, Genus::Stratocumulus, Genus::Altocumulus,
                                 Genus::Cumulus, Genus::Cumulonimbus};
constexpr Genus kSheet[] = {Genus::Cirrus, Genus::Cirrostratus, Genus::Cirrocumulus};

template <size_t N>
int index_of(const Genus (&list)[N], Genus genus) {
  const auto it = std::find(std::begin(list), std::end(list), genus);
  return it == std::end(list) ? -1 : int(it - std::begin(list));
}

// The genus of list nearest to `type` on a scale from 0 to 1.
template <size_t N>
Genus nearest(const Genus (&list)[N], float type) {
  const int i = int(std::lround(std::clamp(type, 0.0f, 1.0f) * float(N - 1)));
  return list[i];
}

[[noreturn]] void fail(const std::string& field, const std::string& value, const std::string& why) {
  throw InputError("weather." + field + " = " + value + ": " + why);
}

// Checks a layer and returns its position on the type scale of `list`.
template <size_t N>
float checked_type(const std::string& name, const CloudLayer& layer, const Genus (&list)[N],
                   const char* allowed, bool sheet) {
  const int i = index_of(list, layer.genus);
  if (i < 0)
    fail(name + ".genus", to_string(layer.genus), std::string("this layer draws ") + allowed);
  if (!(layer.coverage_oktas >= 0.0f && layer.coverage_oktas <= 8.0f))
    fail(name + ".coverage_oktas", format_float(layer.coverage_oktas), "must be in [0, 8]");
  if (!sheet && !(layer.base_m < layer.top_m))
    fail(name + ".base_m", format_float(layer.base_m),
         "must be below " + name + ".top_m (" + format_float(layer.top_m) + ")");
  if (layer.type >= 0.0f) {
    if (!(layer.type <= 1.0f))
      fail(name + ".type", format_float(layer.type),
           "must be in [0, 1], or < 0 for the genus's own");
    return layer.type;
  }
  return genus_type(layer.genus);
}

// The sky covered (the dome's share with cloud T < 0.5, FrameStats::sky_cover_fraction) by a
// layer's clouds.coverage, measured at 48 x 32 on lavapipe (stop 77, `nephele render
// --stats-json` with the default scene's seed and the high layer and the cirrus off) for each
// genus in the shell a report gives it (coverage_for_oktas).
constexpr float kCoverages[] = {0.0f,  0.30f, 0.35f, 0.40f, 0.45f, 0.50f,
                                0.55f, 0.60f, 0.65f, 0.70f, 0.80f, 1.0f};
constexpr size_t kCoverageSteps = std::size(kCoverages);
struct CoverCurve {
  float type;
  float sky[kCoverageSteps];
};
constexpr CoverCurve kCoverCurves[] = {
    {0.0f, {0, 0.0020f, 0.0217f, 0.0957f, 0.2061f, 0.3599f, 0.7144f, 0.9360f, 0.9978f, 1, 1, 1}},
    {0.25f, {0, 0.0029f, 0.0251f, 0.1121f, 0.2512f, 0.5022f, 0.7019f, 0.9043f, 0.9924f, 1, 1, 1}},
    {0.5f,
     {0, 0.0034f, 0.0222f, 0.1069f, 0.2454f, 0.4380f, 0.6372f, 0.8174f, 0.9424f, 0.9902f, 1, 1}},
    {0.75f,
     {0, 0.0037f, 0.0239f, 0.0886f, 0.2241f, 0.4272f, 0.6406f, 0.8364f, 0.9436f, 0.9854f, 1, 1}},
    {0.875f, {0, 0.0525f, 0.1794f, 0.3660f, 0.5981f, 0.8374f, 0.9705f, 1, 1, 1, 1, 1}},
    {1.0f, {0, 0.1619f, 0.4778f, 0.7522f, 0.9172f, 0.9895f, 1, 1, 1, 1, 1, 1}},
};

// The sky covered at `coverage` for `type`: each genus' curve, linear in coverage between its
// measured steps and in type between genera.
float sky_cover(float coverage, float type) {
  const auto curve = [coverage](const CoverCurve& c) {
    const float x = std::clamp(coverage, 0.0f, 1.0f);
    size_t k = 1;
    while (k + 1 < kCoverageSteps && kCoverages[k] < x) ++k;
    const float t = (x - kCoverages[k - 1]) / (kCoverages[k] - kCoverages[k - 1]);
    return c.sky[k - 1] + std::clamp(t, 0.0f, 1.0f) * (c.sky[k] - c.sky[k - 1]);
  };
  const float x = std::clamp(type, 0.0f, 1.0f);
  size_t k = 1;
  while (k + 1 < std::size(kCoverCurves) && kCoverCurves[k].type < x) ++k;
  const CoverCurve& a = kCoverCurves[k - 1];
  const CoverCurve& b = kCoverCurves[k];
  const float t = (x - a.type) / (b.type - a.type);
  return curve(a) + t * (curve(b) - curve(a));
}

// The sky covered by the cirrus sheet's cirrus.coverage at the default optical depth (0.3) and
// altitude (9 km), measured as the volumetric curves are (stop 79) for each sheet genus: a
// cirrostratus veil covers the dome from a coverage of 0.2 (near the horizon its slant optical
// depth passes the dome's threshold, 0.69, everywhere), cirrus streaks from 0.6-0.7.
struct SheetCurve {
  std::vector<std::pair<float, float>> points;  // (coverage, sky covered), increasing
};
const SheetCurve kSheetCurves[] = {
    {{{0, 0},
      {0.2f, 0},
      {0.25f, 0.009f},
      {0.3f, 0.0537f},
      {0.35f, 0.1914f},
      {0.4f, 0.3857f},
      {0.45f, 0.5649f},
      {0.5f, 0.7017f},
      {0.55f, 0.8125f},
      {0.6f, 0.8828f},
      {0.65f, 0.9277f},
      {0.7f, 0.9619f},
      {0.8f, 0.9932f},
      {0.9f, 0.9985f},
      {1, 1}}},  // cirrus
    {{{0, 0},
      {0.02f, 0},
      {0.04f, 0.0037f},
      {0.06f, 0.0354f},
      {0.08f, 0.0972f},
      {0.1f, 0.2278f},
      {0.12f, 0.418f},
      {0.14f, 0.6206f},
      {0.16f, 0.8174f},
      {0.18f, 0.9277f},
      {0.2f, 0.9824f},
      {0.3f, 1},
      {1, 1}}},  // cirrostratus
    {{{0, 0},
      {0.3f, 0.008f},
      {0.35f, 0.0208f},
      {0.4f, 0.0586f},
      {0.45f, 0.1289f},
      {0.5f, 0.2388f},
      {0.55f, 0.3782f},
      {0.6f, 0.5417f},
      {0.65f, 0.7004f},
      {0.7f, 0.8286f},
      {0.75f, 0.9204f},
      {0.8f, 0.9619f},
      {0.85f, 0.9861f},
      {0.9f, 0.9963f},
      {1, 1}}},  // cirrocumulus
};

float sheet_sky_cover(float coverage, float type) {
  const auto curve = [x = std::clamp(coverage, 0.0f, 1.0f)](const SheetCurve& c) {
    size_t k = 1;
    while (k + 1 < c.points.size() && c.points[k].first < x) ++k;
    const auto [x0, y0] = c.points[k - 1];
    const auto [x1, y1] = c.points[k];
    return y0 + std::clamp((x - x0) / (x1 - x0), 0.0f, 1.0f) * (y1 - y0);
  };
  const float x = std::clamp(type, 0.0f, 1.0f) * 2.0f;  // cirrus 0, cirrostratus 1, cirrocumulus 2
  const int k = std::min(int(x), 1);
  return curve(kSheetCurves[k]) +
         (x - float(k)) * (curve(kSheetCurves[k + 1]) - curve(kSheetCurves[k]));
}

// The least coverage whose sky cover reaches oktas / 8 (the curves rise, then stay at 1).
float coverage_reaching(float oktas, float type, float (*cover)(float, float)) {
  if (oktas <= 0.0f) return 0.0f;
  if (oktas >= 8.0f) return 1.0f;  // overcast: no hole
  const float share = oktas / 8.0f;
  float lo = 0.0f, hi = 1.0f;
  for (int i = 0; i < 40; ++i) {
    const float mid = 0.5f * (lo + hi);
    (cover(mid, type) < share ? lo : hi) = mid;
  }
  return hi;
}

// The two volumetric layers (CloudParams, HighCloudParams) as a state's layer, and back.
template <typename Params>
CloudLayer volumetric_layer(const Params& p) {
  return {nearest(kVolumetric, p.type),
          p.type,
          p.bottom_altitude_m,
          p.top_altitude_m,
          oktas_for_coverage(p.coverage, p.type),
          p.density,
          0.0f};
}

// A layer's coverage is left exactly as it is when its oktas are the ones it gives.
template <typename Params>
void set_volumetric_layer(Params& p, const CloudLayer& layer, float type) {
  if (type != p.type || layer.coverage_oktas != oktas_for_coverage(p.coverage, p.type))
    p.coverage = coverage_for_oktas(layer.coverage_oktas, type);
  p.type = type;
  p.bottom_altitude_m = layer.base_m;
  p.top_altitude_m = layer.top_m;
  p.density = layer.density;
}

}  // namespace

float genus_type(Genus genus) {
  if (const int i = index_of(kVolumetric, genus); i >= 0)
    return float(i) / float(std::size(kVolumetric) - 1);
  return float(index_of(kSheet, genus)) / float(std::size(kSheet) - 1);
}

bool is_sheet_genus(Genus genus) {
  return index_of(kSheet, genus) >= 0;
}

float oktas_for_coverage(float coverage, float type) {
  return coverage >= 1.0f ? 8.0f : std::min(8.0f * sky_cover(coverage, type), 7.999f);
}

float coverage_for_oktas(float oktas, float type) {
  return coverage_reaching(oktas, type, sky_cover);
}

float oktas_for_sheet_coverage(float coverage, float type) {
  return coverage >= 1.0f ? 8.0f : std::min(8.0f * sheet_sky_cover(coverage, type), 7.999f);
}

float sheet_coverage_for_oktas(float oktas, float type) {
  return coverage_reaching(oktas, type, sheet_sky_cover);
}

const char* to_string(PrecipitationKind kind) {
  switch (kind) {
    case PrecipitationKind::None:
      return "none";
    case PrecipitationKind::Rain:
      return "rain";
    case PrecipitationKind::Drizzle:
      return "drizzle";
    case PrecipitationKind::Snow:
      return "snow";
    case PrecipitationKind::Sleet:
      return "sleet";
  }
  return "unknown";
}

const char* to_string(Genus genus) {
  switch (genus) {
    case Genus::Stratus:
      return "stratus";
    case Genus::Stratocumulus:
      return "stratocumulus";
    case Genus::Altocumulus:
      return "altocumulus";
    case Genus::Cumulus:
      return "cumulus";
    case Genus::Cumulonimbus:
      return "cumulonimbus";
    case Genus::Cirrus:
      return "cirrus";
    case Genus::Cirrostratus:
      return "cirrostratus";
    case Genus::Cirrocumulus:
      return "cirrocumulus";
  }
  return "unknown";
}

glm::vec2 wind_at(const std::vector<WindLevel>& levels, float altitude_m) {
  if (levels.empty()) return glm::vec2(0.0f);
  if (altitude_m <= levels.front().altitude_m) return levels.front().wind_mps;
  for (size_t i = 1; i < levels.size(); ++i)
    if (altitude_m == levels[i].altitude_m) {
      return levels[i].wind_mps;
    } else if (altitude_m < levels[i].altitude_m) {
      const WindLevel& a = levels[i - 1];
      const WindLevel& b = levels[i];
      const float t = (altitude_m - a.altitude_m) / (b.altitude_m - a.altitude_m);
      return a.wind_mps + t * (b.wind_mps - a.wind_mps);
    }
  return levels.back().wind_mps;
}

float clear_air_visibility_m(const AtmosphereParams& atmosphere) {
  // The air's own extinction at 550 nm: the Rayleigh coefficients' green channel.
  return glsl::KOSCHMIEDER / atmosphere.rayleigh_scattering_per_m.y;
}

float visibility_m(const AtmosphereParams& atmosphere) {
  return glsl::KOSCHMIEDER /
         (atmosphere.rayleigh_scattering_per_m.y + atmosphere.mie_extinction_per_m);
}

float visibility_m(const Scene& scene) {
  return glsl::KOSCHMIEDER / (glsl::KOSCHMIEDER / visibility_m(scene.atmosphere) +
                              precipitation_sigma_t_per_m(scene.precipitation));
}

glm::vec2 wind_towards(float from_deg) {
  const float a = glm::radians(from_deg);
  return -glm::vec2(std::sin(a), std::cos(a));
}

std::vector<WindLevel> surface_wind_levels(glm::vec2 towards, float speed_mps) {
  return {{0.0f, speed_mps * towards},
          {1000.0f, speed_mps * std::pow(100.0f, 1.0f / 7.0f) * towards}};
}

WeatherState weather_state(const Scene& scene) {
  WeatherState state;
  const CloudParams& c = scene.clouds;
  state.low = volumetric_layer(c);
  const HighCloudParams& h = scene.high_clouds;
  state.high = volumetric_layer(h);
  const CirrusParams& s = scene.cirrus;
  state.sheet = {nearest(kSheet, s.type),
                 s.type,
                 s.altitude_m,
                 s.altitude_m,
                 oktas_for_sheet_coverage(s.coverage, s.type),
                 0.0f,
                 s.optical_depth};
  std::vector<WindLevel> levels = {{c.bottom_altitude_m, c.wind_mps},
                                   {c.top_altitude_m, c.wind_mps + c.wind_shear_mps},
                                   {h.bottom_altitude_m, h.wind_mps},
                                   {s.altitude_m, s.wind_mps}};
  std::stable_sort(levels.begin(), levels.end(), [](const WindLevel& a, const WindLevel& b) {
    return a.altitude_m < b.altitude_m;
  });
  for (const WindLevel& level : levels)  // one wind an altitude: the first given
    if (state.wind.empty() || level.altitude_m > state.wind.back().altitude_m)
      state.wind.push_back(level);
  // The layers' winds as one profile, when they are one.
  const bool one_profile = wind_at(state.wind, c.bottom_altitude_m) == c.wind_mps &&
                           wind_at(state.wind, c.top_altitude_m) - c.wind_mps == c.wind_shear_mps &&
                           wind_at(state.wind, h.bottom_altitude_m) == h.wind_mps &&
                           wind_at(state.wind, s.altitude_m) == s.wind_mps;
  if (!one_profile) state.wind.clear();
  state.visibility_m = visibility_m(scene);
  state.storm_growth = c.precipitation;
  state.lightning_per_min = scene.lightning.flashes_per_min;
  const PrecipitationParams& p = scene.precipitation;
  if (p.rate_mm_per_h > 0.0f)
    for (PrecipitationKind kind : {PrecipitationKind::Rain, PrecipitationKind::Drizzle,
                                   PrecipitationKind::Snow, PrecipitationKind::Sleet})
      if (p.kind == to_string(kind)) {
        state.precipitation = kind;
        state.precipitation_mm_per_h = p.rate_mm_per_h;
      }
  return state;
}

void apply_weather(const WeatherState& state, Scene& scene) {
  // Everything is checked before the scene changes.
  const char* volumetric = "stratus, stratocumulus, altocumulus, cumulus or cumulonimbus";
  const float low_type = checked_type("low", state.low, kVolumetric, volumetric, false);
  const float high_type = checked_type("high", state.high, kVolumetric, volumetric, false);
  const float sheet_type =
      checked_type("sheet", state.sheet, kSheet, "cirrus, cirrostratus or cirrocumulus", true);
  for (size_t i = 1; i < state.wind.size(); ++i)
    if (!(state.wind[i].altitude_m > state.wind[i - 1].altitude_m))
      fail("wind[" + std::to_string(i) + "].altitude_m", format_float(state.wind[i].altitude_m),
           "must be above wind[" + std::to_string(i - 1) + "].altitude_m (" +
               format_float(state.wind[i - 1].altitude_m) + "): levels go up");
  const float clear_m = clear_air_visibility_m(scene.atmosphere);
  if (!(state.visibility_m >= kMinVisibilityM && state.visibility_m <= clear_m))
    fail("visibility_m", format_float(state.visibility_m),
         "must be in [" + format_float(kMinVisibilityM) + ", " + format_float(clear_m) +
             "] (the clear air's own, at sea level; fog is thicker than the haze can be)");
  if (!(state.precipitation_mm_per_h >= 0.0f && state.precipitation_mm_per_h <= 200.0f))
    fail("precipitation_mm_per_h", format_float(state.precipitation_mm_per_h),
         "must be in [0, 200]");
  PrecipitationParams precipitation = scene.precipitation;
  const bool falls =
      state.precipitation != PrecipitationKind::None && state.precipitation_mm_per_h > 0.0f;
  precipitation.rate_mm_per_h = falls ? state.precipitation_mm_per_h : 0.0f;
  if (falls) precipitation.kind = to_string(state.precipitation);
  if (precipitation.bottom_m >= state.low.base_m) precipitation.bottom_m = 0.0f;
  // The haze: what the visibility leaves after the precipitation's extinction and the air's.
  const float precipitation_sigma = precipitation_sigma_t_per_m(precipitation);

  CloudParams& c = scene.clouds;
  set_volumetric_layer(c, state.low, low_type);
  c.precipitation = state.storm_growth;
  scene.lightning.flashes_per_min = state.lightning_per_min;
  HighCloudParams& h = scene.high_clouds;
  set_volumetric_layer(h, state.high, high_type);
  CirrusParams& s = scene.cirrus;
  s.type = sheet_type;
  s.altitude_m = state.sheet.base_m;
  // Left exactly as it is when its oktas are the ones it gives.
  if (sheet_type != s.type ||
      state.sheet.coverage_oktas != oktas_for_sheet_coverage(s.coverage, s.type))
    s.coverage = sheet_coverage_for_oktas(state.sheet.coverage_oktas, sheet_type);
  s.optical_depth = state.sheet.optical_depth;
  if (!state.wind.empty()) {
    c.wind_mps = wind_at(state.wind, c.bottom_altitude_m);
    c.wind_shear_mps = wind_at(state.wind, c.top_altitude_m) - c.wind_mps;
    h.wind_mps = wind_at(state.wind, h.bottom_altitude_m);
    s.wind_mps = wind_at(state.wind, s.altitude_m);
  }
  // The haze: Mie extinction for the visibility, its single-scattering albedo kept (and left
  // exactly as it is when the visibility is the one it gives); none where the precipitation's
  // law alone hides more than the visibility says.
  const float visibility_before = visibility_m(scene);
  const float sigma_before = precipitation_sigma_t_per_m(scene.precipitation);
  scene.precipitation = precipitation;
  AtmosphereParams& a = scene.atmosphere;
  if (state.visibility_m == visibility_before && precipitation_sigma == sigma_before) return;
  const float albedo =
      a.mie_extinction_per_m > 0.0f ? a.mie_scattering_per_m / a.mie_extinction_per_m : 0.9f;
  a.mie_extinction_per_m = std::max(0.0f, glsl::KOSCHMIEDER / state.visibility_m -
                                              a.rayleigh_scattering_per_m.y - precipitation_sigma);
  a.mie_scattering_per_m = albedo * a.mie_extinction_per_m;
}

void apply_weather_keys(Scene& scene) {
  const WeatherReportParams& w = scene.weather;
  const bool direction = w.wind_from_deg >= 0.0f;
  const bool knots = w.wind_speed_kt >= 0.0f, mps = w.wind_speed_mps >= 0.0f;
  if (!direction && !knots && !mps && w.visibility_m <= 0.0f) return;
  if (knots && mps)
    throw InputError("weather.wind_speed_kt = " + format_float(w.wind_speed_kt) +
                     ": give the speed once, in knots or in m/s (weather.wind_speed_mps = " +
                     format_float(w.wind_speed_mps) + ")");
  if (direction && !knots && !mps)
    throw InputError("weather.wind_from_deg = " + format_float(w.wind_from_deg) +
                     ": needs a speed, weather.wind_speed_kt or weather.wind_speed_mps");
  if (!direction && (knots || mps))
    throw InputError(std::string(knots ? "weather.wind_speed_kt = " : "weather.wind_speed_mps = ") +
                     format_float(knots ? w.wind_speed_kt : w.wind_speed_mps) +
                     ": needs the direction it blows from, weather.wind_from_deg");
  WeatherState state = weather_state(scene);
  if (direction) {
    const float speed_mps = knots ? w.wind_speed_kt * 0.514444f : w.wind_speed_mps;
    state.wind = surface_wind_levels(wind_towards(w.wind_from_deg), speed_mps);
  }
  if (w.visibility_m > 0.0f) state.visibility_m = w.visibility_m;
  apply_weather(state, scene);  // its errors name weather.visibility_m, as the key is named
}

// The scene's shell [bottom, top] (m) in which clouds of `type` fill [base, top]: each type
// fills its own part of the shell's height (clouds_inc.glsl's profiles: a stratus the lowest
// fifth, an altocumulus a band in the middle), so the shell is set from where they are.
glm::vec2 cloud_shell_m(float type, float base_m, float top_m) {
  const float x = std::clamp(type, 0.0f, 1.0f) * float(glsl::CLOUD_GENERA - 1);
  const int lo = std::min(int(x), glsl::CLOUD_GENERA - 2);
  const float rise =
      glm::mix(glsl::cloud_genus_profile(lo).x, glsl::cloud_genus_profile(lo + 1).x, x - float(lo));
  const float fill_top = glsl::cloud_type_top(type);
  const float height = (top_m - base_m) / (fill_top - rise);
  const float bottom = std::max(base_m - rise * height, 0.0f);
  return {bottom, bottom + height};
}

}  // namespace nephele::weather

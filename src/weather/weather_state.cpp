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

// Where x lies among n increasing abscissae (x_at(i)): the segment from k - 1 to k (k >= 1) and
// how far along it, in [0, 1] (held at the ends): the measured curves' linear interpolation.
struct Bracket {
  size_t k;
  float t;
};
template <typename At>
Bracket bracket(size_t n, float x, At x_at) {
  size_t k = 1;
  while (k + 1 < n && x_at(k) < x) ++k;
  return {k, std::clamp((x - x_at(k - 1)) / (x_at(k) - x_at(k - 1)), 0.0f, 1.0f)};
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
// layer's clouds.coverage, measured at 48 x 32 on lavapipe (stop 81, `nephele render
// --stats-json` with the default scene's seed and the high layer and the cirrus off) for each
// genus with its clouds where a report puts them (stratus 150-550 m, stratocumulus 460-1060,
// altocumulus 2439-3039, cumulus 1220-2420, towering cumulus 910-4910, cumulonimbus 910-9000),
// in the shell cloud_shell_m gives at each coverage. A stratus deck at 150 m leaves a sliver of
// the horizon under it (0.998 at coverage 0.7-0.8, 0.990 at 1; taken as the 0.998 before it,
// and 1 at 1, where coverage_for_oktas puts 8 oktas).
constexpr float kCoverages[] = {0.0f,  0.30f, 0.35f, 0.40f, 0.45f, 0.50f,
                                0.55f, 0.60f, 0.65f, 0.70f, 0.80f, 1.0f};
constexpr size_t kCoverageSteps = std::size(kCoverages);
struct CoverCurve {
  float type;
  float sky[kCoverageSteps];
};
constexpr CoverCurve kCoverCurves[] = {
    {0.0f,
     {0, 0.0024f, 0.0256f, 0.0955f, 0.2109f, 0.3518f, 0.7905f, 0.9900f, 0.9978f, 0.9983f, 0.9983f,
      1}},
    {0.25f, {0, 0.0078f, 0.0564f, 0.1819f, 0.3250f, 0.5928f, 0.7993f, 0.9624f, 0.9988f, 1, 1, 1}},
    {0.5f,
     {0, 0.0076f, 0.0503f, 0.1880f, 0.3589f, 0.5557f, 0.7302f, 0.8774f, 0.9705f, 0.9968f, 1, 1}},
    {0.75f,
     {0, 0.0178f, 0.0911f, 0.2502f, 0.4573f, 0.6677f, 0.8381f, 0.9458f, 0.9822f, 0.9988f, 1, 1}},
    {0.875f, {0, 0.1079f, 0.3269f, 0.5745f, 0.7864f, 0.9348f, 0.9932f, 1, 1, 1, 1, 1}},
    {1.0f, {0, 0.1802f, 0.5176f, 0.7998f, 0.9409f, 0.9917f, 1, 1, 1, 1, 1, 1}},
};

// The sky covered at `coverage` for `type`: each genus' curve, linear in coverage between its
// measured steps and in type between genera.
float sky_cover(float coverage, float type) {
  const Bracket c = bracket(kCoverageSteps, std::clamp(coverage, 0.0f, 1.0f),
                            [](size_t i) { return kCoverages[i]; });
  const auto curve = [c](const CoverCurve& g) {
    return g.sky[c.k - 1] + c.t * (g.sky[c.k] - g.sky[c.k - 1]);
  };
  const Bracket g = bracket(std::size(kCoverCurves), std::clamp(type, 0.0f, 1.0f),
                            [](size_t i) { return kCoverCurves[i].type; });
  const float a = curve(kCoverCurves[g.k - 1]);
  return a + g.t * (curve(kCoverCurves[g.k]) - a);
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
    const Bracket b = bracket(c.points.size(), x, [&c](size_t i) { return c.points[i].first; });
    const float y0 = c.points[b.k - 1].second;
    return y0 + b.t * (c.points[b.k].second - y0);
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

std::optional<Genus> parse_genus(std::string_view name) {
  for (Genus g : kVolumetric)
    if (name == to_string(g)) return g;
  for (Genus g : kSheet)
    if (name == to_string(g)) return g;
  return std::nullopt;
}

// The type a [[cloud_layers]] layer draws its genus at.
static float cloud_layer_type(const CloudLayerParams& layer) {
  const std::optional<Genus> genus = parse_genus(layer.genus);
  return genus && !is_sheet_genus(*genus) ? genus_type(*genus) : genus_type(Genus::Stratocumulus);
}

glm::vec2 cloud_layer_shell_m(const CloudLayerParams& layer) {
  return cloud_shell_m(cloud_layer_type(layer), cloud_layer_coverage(layer), layer.base_m,
                       layer.top_m);
}

float cloud_layer_coverage(const CloudLayerParams& layer) {
  return coverage_for_oktas(layer.oktas, cloud_layer_type(layer));
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
  for (const CloudLayerParams& l : scene.cloud_layers)
    state.more.push_back({parse_genus(l.genus).value_or(Genus::Stratocumulus), -1.0f, l.base_m,
                          l.top_m, l.oktas, l.density, 0.0f});
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
  for (const CloudLayerParams& l : scene.cloud_layers) levels.push_back({l.base_m, l.wind_mps});
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
                           wind_at(state.wind, s.altitude_m) == s.wind_mps &&
                           std::all_of(scene.cloud_layers.begin(), scene.cloud_layers.end(),
                                       [&](const CloudLayerParams& l) {
                                         return wind_at(state.wind, l.base_m) == l.wind_mps;
                                       });
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
  if (state.more.size() > size_t(kMaxCloudLayers - 2))
    fail("more", std::to_string(state.more.size()) + " layers",
         "at most " + std::to_string(kMaxCloudLayers - 2) + " besides low and high");
  for (size_t i = 0; i < state.more.size(); ++i)
    checked_type("more[" + std::to_string(i) + "]", state.more[i], kVolumetric, volumetric, false);
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
  std::vector<CloudLayerParams> more(state.more.size());
  for (size_t i = 0; i < more.size(); ++i) {
    const CloudLayer& from = state.more[i];
    more[i].genus = to_string(from.genus);
    more[i].base_m = from.base_m;
    more[i].top_m = from.top_m;
    more[i].oktas = from.coverage_oktas;
    more[i].density = from.density;
    // A new layer moves with the low one's wind when the state gives no profile.
    more[i].wind_mps = i < scene.cloud_layers.size() ? scene.cloud_layers[i].wind_mps : c.wind_mps;
  }
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
    for (CloudLayerParams& l : more) l.wind_mps = wind_at(state.wind, l.base_m);
  }
  scene.cloud_layers = std::move(more);
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

namespace {

// Where each genus' clouds are in its shell (height fractions), by the layer's clouds.coverage:
// from the lowest to the highest height at which at least a tenth as much of the layer's area
// is cloud as at its cloudiest height, measured with Renderer::cloud_profile (64 bins of a
// 2000 m shell, the default scene's seed; bin centres, so within 0.008; the same within a bin
// for 500 and 8000 m shells). The genus profiles (clouds_inc.glsl) rise from and end at the
// outer corners of their trapezoids, but the coverage's threshold cuts the weak ends: a
// cumulus at 0.45 fills 0.07-0.31 of its shell, not 0-0.8, and the more of the sky it covers,
// the higher its towers reach.
constexpr float kFillCoverages[] = {0.30f, 0.35f, 0.40f, 0.45f, 0.50f, 0.55f,
                                    0.60f, 0.70f, 0.80f, 0.90f, 1.00f};
constexpr size_t kFillSteps = std::size(kFillCoverages);
struct FillCurve {
  float type;
  float bottom[kFillSteps], top[kFillSteps];
};
constexpr FillCurve kFillCurves[] = {
    {0.0f,
     {.055f, .055f, .055f, .055f, .055f, .039f, .039f, .039f, .039f, .023f, .023f},
     {.117f, .117f, .117f, .133f, .133f, .133f, .133f, .148f, .164f, .164f, .180f}},
    {0.25f,
     {.086f, .086f, .086f, .070f, .070f, .070f, .070f, .055f, .039f, .039f, .039f},
     {.273f, .273f, .273f, .289f, .289f, .289f, .305f, .320f, .336f, .352f, .352f}},
    {0.5f,
     {.414f, .414f, .414f, .414f, .414f, .398f, .398f, .383f, .367f, .352f, .352f},
     {.586f, .586f, .586f, .586f, .602f, .602f, .617f, .633f, .648f, .648f, .648f}},
    {0.75f,
     {.070f, .070f, .070f, .070f, .070f, .055f, .055f, .055f, .039f, .039f, .039f},
     {.258f, .289f, .289f, .305f, .336f, .367f, .414f, .477f, .555f, .602f, .602f}},
    {0.875f,
     {.070f, .070f, .055f, .055f, .055f, .055f, .055f, .039f, .039f, .039f, .039f},
     {.289f, .336f, .367f, .414f, .445f, .477f, .570f, .680f, .898f, .914f, .914f}},
    {1.0f,
     {.055f, .055f, .055f, .055f, .055f, .039f, .039f, .039f, .023f, .023f, .023f},
     {.914f, .914f, .914f, .914f, .930f, .930f, .930f, .945f, .961f, .961f, .961f}},
};

}  // namespace

glm::vec2 cloud_fill(float type, float coverage) {
  const Bracket c = bracket(kFillSteps, std::clamp(coverage, kFillCoverages[0], 1.0f),
                            [](size_t i) { return kFillCoverages[i]; });
  const auto at = [c](const FillCurve& g) {
    return glm::mix(glm::vec2(g.bottom[c.k - 1], g.top[c.k - 1]),
                    glm::vec2(g.bottom[c.k], g.top[c.k]), c.t);
  };
  const Bracket g = bracket(std::size(kFillCurves), std::clamp(type, 0.0f, 1.0f),
                            [](size_t i) { return kFillCurves[i].type; });
  return glm::mix(at(kFillCurves[g.k - 1]), at(kFillCurves[g.k]), g.t);
}

glm::vec2 clouds_in_shell_m(float type, float coverage, glm::vec2 shell_m) {
  return shell_m.x + cloud_fill(type, coverage) * (shell_m.y - shell_m.x);
}

glm::vec2 cloud_shell_m(float type, float coverage, float base_m, float top_m) {
  const glm::vec2 fill = cloud_fill(type, coverage);
  float height = (top_m - base_m) / (fill.y - fill.x);
  // A shell cannot begin below the ground: then the base is kept, and the tops are lower.
  if (base_m - fill.x * height < 0.0f) height = base_m / fill.x;
  const float bottom = std::max(base_m - fill.x * height, 0.0f);
  return {bottom, bottom + height};
}

}  // namespace nephele::weather

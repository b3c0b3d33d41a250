// nephele — from a weather report to the weather state (metar_weather.h).
#include "weather/metar_weather.h"

#include <libnova/julian_day.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "nephele/error.h"
#include "nephele/sky.h"
#include "render/glsl.h"

namespace nephele::weather {
namespace {

constexpr float kFootM = 0.3048f;
// A convective cloud's base lies about 125 m higher for each degree between the air's
// temperature and its dew point (the lifting condensation level, Espy's rule).
constexpr float kConvectiveBasePerDegM = 125.0f;
// Where the middle and the high genera begin in the temperate regions (WMO cloud atlas: 2 and
// 5-13 km; the cirrus sheet is drawn from 6 km).
constexpr float kMiddleBaseM = 2000.0f;
constexpr float kHighBaseM = 6000.0f;
constexpr float kTowerType = 0.875f;  // TCU: towering cumulus, half way to cumulonimbus

// The sky's cover a group reports, as the summation principle counts it (the sky covered up to
// its level): FEW 1-2, SCT 3-4, BKN 5-7, OVC 8; the middle of the range for the layer drawn.
struct Cover {
  int min = 0, max = 0;
  float drawn = 0.0f;
};
Cover cover_of(const std::string& cover) {
  if (cover == "FEW") return {1, 2, 1.5f};
  if (cover == "SCT") return {3, 4, 3.5f};
  if (cover == "BKN") return {5, 7, 6.0f};
  if (cover == "OVC") return {8, 8, 8.0f};
  return {3, 4, 3.5f};  // "///": a CB or TCU whose cover the station could not tell
}

// A group as a layer before the layers are fitted to the scene's.
struct Group {
  std::string text;
  Genus genus;
  float type;  // on clouds.type's scale
  float base_m, top_m;
  Cover cover;
};

// The depth of a genus' clouds (m), from its base: a fair-weather cumulus deeper the more of
// the sky it covers (humilis to mediocris).
float cloud_depth_m(Genus genus, float type, float base_m, const Cover& cover) {
  if (genus == Genus::Cumulonimbus) return std::max(9000.0f, base_m + 6000.0f) - base_m;
  if (type > 0.8f) return 4000.0f;  // towering cumulus
  switch (genus) {
    case Genus::Stratus:
      return 400.0f;
    case Genus::Stratocumulus:
      return 600.0f;
    case Genus::Altocumulus:
      return 600.0f;
    default:
      return cover.max <= 2 ? 800.0f : cover.max <= 4 ? 1200.0f : 1500.0f;  // cumulus
  }
}

Group group_of(const MetarCloud& c, std::optional<float> convective_base_m) {
  Group g;
  g.text = c.cover + (c.base_ft ? [&] {
    char digits[16];
    std::snprintf(digits, sizeof(digits), "%03d", *c.base_ft / 100);
    return std::string(digits);
  }() : std::string("///")) + c.type;
  g.cover = cover_of(c.cover);
  g.base_m = c.base_ft ? float(*c.base_ft) * kFootM : convective_base_m.value_or(1000.0f);
  const bool closed = c.cover == "BKN" || c.cover == "OVC";
  if (c.type == "CB") {
    g.genus = Genus::Cumulonimbus;
  } else if (c.type == "TCU") {
    g.genus = Genus::Cumulus;
  } else if (g.base_m >= kHighBaseM) {
    g.genus = closed ? Genus::Cirrostratus : Genus::Cirrus;
  } else if (g.base_m >= kMiddleBaseM) {
    g.genus = Genus::Altocumulus;
  } else if (closed) {
    g.genus = g.base_m < 300.0f ? Genus::Stratus : Genus::Stratocumulus;
  } else {
    // Fair-weather cumulus near the convective base; a low layer far from it is a sheet.
    const bool convective = !convective_base_m || std::abs(g.base_m - *convective_base_m) < 600.0f;
    g.genus = convective ? Genus::Cumulus : Genus::Stratocumulus;
  }
  g.type = c.type == "TCU" ? kTowerType : genus_type(g.genus);
  g.top_m = g.base_m + cloud_depth_m(g.genus, g.type, g.base_m, g.cover);
  return g;
}

// Two layers drawn as one: the span of both, the cover of the higher, the genus of the one
// that covers more (the higher where they tie), a cumulonimbus wherever there is one.
Group merged(const Group& a, const Group& b) {
  Group m = a.cover.drawn > b.cover.drawn ? a : b;
  if (a.genus == Genus::Cumulonimbus || b.genus == Genus::Cumulonimbus) {
    m.genus = Genus::Cumulonimbus;
    m.type = 1.0f;
  }
  m.text = a.text + " " + b.text;
  m.base_m = std::min(a.base_m, b.base_m);
  m.top_m = std::max(a.top_m, b.top_m);
  if (b.cover.drawn > a.cover.drawn || (b.cover.drawn == a.cover.drawn && b.base_m > a.base_m))
    m.cover = b.cover;
  else
    m.cover = a.cover;
  return m;
}

CloudLayer cloud_layer(const Group& g, float own_oktas, float density) {
  CloudLayer layer;
  layer.genus = g.genus;
  layer.type = g.type == genus_type(g.genus) ? -1.0f : g.type;
  const glm::vec2 shell =
      cloud_shell_m(g.type, coverage_for_oktas(own_oktas, g.type), g.base_m, g.top_m);
  layer.base_m = shell.x;
  layer.top_m = shell.y;
  layer.coverage_oktas = own_oktas;
  layer.density = density;
  return layer;
}

// A storm cell's flashes a minute for a thunderstorm of `intensity` (TS, -TS, +TS): a few a
// minute in an ordinary storm, ten and more in a severe one.
float flashes_per_min(const std::string& intensity) {
  return intensity == "-" ? 2.0f : intensity == "+" ? 15.0f : 6.0f;
}

// Precipitation (mm/h of water) by kind and intensity: rain light under 2.5, moderate to
// 7.6, heavy above (the AMS glossary's classes); drizzle a tenth of it; snow as melted water.
float rate_mm_per_h(const MetarWeather& w) {
  const float scale = w.intensity == "-" ? 0.4f : w.intensity == "+" ? 4.0f : 1.0f;
  if (w.has("RA") || w.has("GR") || w.has("GS") || w.has("PL")) return 4.0f * scale;
  if (w.has("SN") || w.has("SG")) return 1.5f * scale;
  if (w.has("DZ")) return 0.4f * scale;
  return 0.0f;
}

// What falls: snow (SN, snow grains SG), sleet (ice pellets PL, or rain and snow together),
// drizzle alone, else rain (RA, hail GR and small hail GS melting as they fall).
PrecipitationKind precipitation_kind(const MetarWeather& w) {
  const bool snow = w.has("SN") || w.has("SG");
  if (w.has("PL") || (snow && w.has("RA"))) return PrecipitationKind::Sleet;
  if (snow) return PrecipitationKind::Snow;
  if (w.has("DZ") && !w.has("RA") && !w.has("GR") && !w.has("GS"))
    return PrecipitationKind::Drizzle;
  return PrecipitationKind::Rain;
}
}  // namespace

ReportWeather weather_from_metar(const MetarReport& report, const WeatherState& base) {
  ReportWeather out;
  out.state = base;
  WeatherState& s = out.state;
  std::optional<float> convective_base_m;
  if (report.temperature_c && report.dew_point_c)
    convective_base_m =
        std::max(*report.temperature_c - *report.dew_point_c, 0.0f) * kConvectiveBasePerDegM;

  // The groups, lowest first; an obscured sky is a closed deck at its vertical visibility.
  std::vector<Group> groups;
  for (const MetarCloud& c : report.clouds)
    if (c.cover != "///" || !c.type.empty()) groups.push_back(group_of(c, convective_base_m));
  if (report.sky_obscured) {
    const float vv_m = float(report.vertical_visibility_ft.value_or(100)) * kFootM;
    groups.push_back({report.vertical_visibility_ft ? "VV" : "VV///",
                      Genus::Stratus,
                      0.0f,
                      std::max(vv_m, 15.0f),
                      std::max(vv_m, 15.0f) + 300.0f,
                      {8, 8, 8.0f}});
  }
  std::stable_sort(groups.begin(), groups.end(),
                   [](const Group& a, const Group& b) { return a.base_m < b.base_m; });
  for (const Group& g : groups) {
    out.oktas_min = std::max(out.oktas_min, g.cover.min);
    out.oktas_max = std::max(out.oktas_max, g.cover.max);
  }

  // The high sheet takes the cirrus-level group that covers most; the rest are volumetric.
  std::vector<Group> volumetric;
  std::optional<Group> sheet;
  for (const Group& g : groups) {
    if (!is_sheet_genus(g.genus)) {
      volumetric.push_back(g);
    } else if (!sheet || g.cover.drawn > sheet->cover.drawn) {
      if (sheet) out.notes.push_back(sheet->text + ": a second cirrus layer, drawn as " + g.text);
      sheet = g;
    }
  }
  // A cumulonimbus spans the others; otherwise layers whose clouds overlap are drawn as one,
  // and the two nearest while there are more than the scene holds.
  const auto overlapping = [](const Group& low, const Group& high) {
    return low.top_m > high.base_m;
  };
  const bool cumulonimbus = std::any_of(volumetric.begin(), volumetric.end(), [](const Group& g) {
    return g.genus == Genus::Cumulonimbus;
  });
  while (volumetric.size() > 1) {
    size_t k = 0;
    for (size_t j = 1; j + 1 < volumetric.size(); ++j)
      if (volumetric[j + 1].base_m - volumetric[j].top_m <
          volumetric[k + 1].base_m - volumetric[k].top_m)
        k = j;
    // clouds and the [[cloud_layers]]: high_clouds is left off.
    const bool too_many = volumetric.size() > size_t(kMaxCloudLayers - 1);
    if (!cumulonimbus && !too_many && !overlapping(volumetric[k], volumetric[k + 1])) break;
    const Group m = merged(volumetric[k], volumetric[k + 1]);
    out.notes.push_back(
        volumetric[k].text + " and " + volumetric[k + 1].text + ": drawn as one layer (" +
        (cumulonimbus ? "a cumulonimbus spans them"
         : too_many   ? std::to_string(kMaxCloudLayers - 1) + " volumetric layers at most"
                      : "their clouds overlap") +
        ")");
    volumetric.erase(volumetric.begin() + long(k), volumetric.begin() + long(k) + 2);
    volumetric.insert(volumetric.begin() + long(k), m);
  }

  // Each layer's own cover: the groups count the sky covered up to their level, so a layer
  // covers what the one below leaves: 1 - (1 - total) / (1 - below).
  float below = 0.0f;  // the sky covered below, [0, 1]
  const auto own = [&below](const Group& g) {
    const float total = std::max(g.cover.drawn / 8.0f, below);
    const float share = below >= 1.0f ? 0.0f : 1.0f - (1.0f - total) / (1.0f - below);
    below = total;
    return 8.0f * std::clamp(share, 0.0f, 1.0f);
  };
  // The lowest (or the cumulonimbus) is drawn by clouds, the others by [[cloud_layers]], which
  // take their clouds' own bases and tops (the renderer draws each layer up to half way to the
  // next one's clouds, so no shell is cut); high_clouds is left off, clear of the low layer.
  s.low.coverage_oktas = 0.0f;
  s.high.coverage_oktas = 0.0f;
  s.sheet.coverage_oktas = 0.0f;
  s.more.clear();
  for (size_t k = 0; k < volumetric.size(); ++k) {
    const Group& g = volumetric[k];
    const float oktas = own(g);
    std::string slot = "clouds";
    if (k == 0)
      s.low = cloud_layer(g, oktas, s.low.density);
    else {
      s.more.push_back({g.genus, -1.0f, g.base_m, g.top_m, oktas, s.low.density, 0.0f});
      slot = "cloud_layers[" + std::to_string(k - 1) + "]";
    }
    out.layers.push_back({g.text, slot, g.genus, g.type, g.base_m, g.top_m, g.cover.drawn, oktas});
  }
  s.high.base_m = std::max(s.high.base_m, s.low.top_m);
  s.high.top_m = std::max(s.high.top_m, s.high.base_m + 1000.0f);
  float tops_m = s.low.top_m;  // the volumetric clouds' highest top, under the sheet
  for (const CloudLayer& l : s.more) tops_m = std::max(tops_m, l.top_m);
  if (sheet) {
    const float oktas = own(*sheet);
    s.sheet.genus = sheet->genus;
    s.sheet.type = -1.0f;
    s.sheet.base_m = s.sheet.top_m = std::max(sheet->base_m, tops_m);
    s.sheet.coverage_oktas = oktas;
    out.layers.push_back({sheet->text, "cirrus", sheet->genus, -1.0f, sheet->base_m, sheet->base_m,
                          sheet->cover.drawn, oktas});
  }

  // The wind, where it blows from, at 10 m; the clouds' wind above the surface layer about
  // twice it (a 1/7 power law to 1 km).
  if (report.wind && !report.wind->missing) {
    const float speed = report.wind->speed_mps();
    glm::vec2 towards(0.0f);
    if (!report.wind->variable) {
      towards = wind_towards(float(report.wind->direction_deg));
    } else if (!s.wind.empty() && glm::length(s.wind.front().wind_mps) > 0.0f) {
      towards = glm::normalize(s.wind.front().wind_mps);  // variable: the scene's direction
    }
    s.wind = surface_wind_levels(towards, speed);
  }

  // The visibility sets the haze; 10 km or more keeps a clearer scene's.
  if (report.visibility && !report.visibility->missing) {
    const MetarVisibility& v = *report.visibility;
    float metres = v.at_least ? std::max(v.distance_m, base.visibility_m) : v.distance_m;
    if (metres < kMinVisibilityM) {
      out.notes.push_back("visibility " + std::to_string(int(metres)) + " m: the haze holds " +
                          std::to_string(int(kMinVisibilityM)) + " m at the least");
      metres = kMinVisibilityM;
    }
    s.visibility_m = metres;
  }

  // Precipitation and storms.
  s.precipitation = PrecipitationKind::None;
  s.precipitation_mm_per_h = 0.0f;
  s.storm_growth = 0.0f;
  s.lightning_per_min = 0.0f;
  for (const MetarWeather& w : report.weather) {
    if (w.intensity == "VC") continue;  // in the vicinity, not here
    const float rate = rate_mm_per_h(w);
    if (rate > s.precipitation_mm_per_h) {
      s.precipitation_mm_per_h = rate;
      s.precipitation = precipitation_kind(w);
    }
    if (w.descriptor == "TS") {
      s.storm_growth = std::max(s.storm_growth, w.intensity == "+" ? 1.0f : 0.7f);
      s.lightning_per_min = std::max(s.lightning_per_min, flashes_per_min(w.intensity));
    }
  }
  if (cumulonimbus) s.storm_growth = std::max(s.storm_growth, 0.4f);
  return out;
}

std::string report_time(const MetarReport& report, const std::string& scene_time) {
  const std::optional<double> jd =
      scene_time.empty() ? std::nullopt : julian_day_from_iso8601(scene_time);
  if (!jd)
    throw InputError("weather.metar: the report's day " + std::to_string(report.day) +
                     " needs the scene's month and year: set time (\"2026-06-21T12:00:00Z\")");
  ln_date date{};
  ln_get_date(*jd, &date);
  static constexpr int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  const bool leap = (date.years % 4 == 0 && date.years % 100 != 0) || date.years % 400 == 0;
  const int days = kDays[date.months - 1] + (date.months == 2 && leap ? 1 : 0);
  if (report.day > days)
    throw InputError("weather.metar: day " + std::to_string(report.day) + " of the report: " +
                     std::to_string(date.years) + "-" + std::to_string(date.months) +
                     " (the scene's month) has " + std::to_string(days) + " days");
  char text[32];
  std::snprintf(text, sizeof(text), "%04d-%02d-%02dT%02d:%02d:00Z", date.years, date.months,
                report.day, report.hour, report.minute);
  return text;
}

namespace {
MetarReport report_of(const Scene& scene) {
  MetarReport report;
  try {
    report = parse_metar(scene.weather.metar);
  } catch (const InputError& e) {
    throw InputError("weather.metar: " + std::string(e.what()));
  }
  if (report.nil) throw InputError("weather.metar: the report is NIL (none was made)");
  return report;
}
}  // namespace

void apply_metar(Scene& scene) {
  if (scene.weather.metar.empty()) return;
  const MetarReport report = report_of(scene);
  Scene result = scene;
  apply_weather(weather_from_metar(report, weather_state(scene)).state, result);
  if (!scene.time.empty()) result.time = report_time(report, scene.time);
  scene = result;
}

std::vector<std::string> describe_metar(const Scene& scene) {
  if (scene.weather.metar.empty()) return {};
  const MetarReport report = report_of(scene);
  const ReportWeather weather = weather_from_metar(report, weather_state(scene));
  std::vector<std::string> lines = {"weather.metar: " + describe(report)};
  char text[240];
  for (const ReportLayer& l : weather.layers) {
    std::snprintf(text, sizeof(text),
                  "  %s -> %s: %s, clouds %.0f-%.0f m above the station, %.1f oktas of its "
                  "own (%.1f up to it)",
                  l.groups.c_str(), l.slot.c_str(), to_string(l.genus), l.cloud_base_m,
                  l.cloud_top_m, l.own_oktas, l.total_oktas);
    lines.push_back(text);
  }
  if (weather.layers.empty()) lines.push_back("  no cloud layer");
  std::snprintf(text, sizeof(text), "  sky cover reported: %d-%d oktas", weather.oktas_min,
                weather.oktas_max);
  lines.push_back(text);
  for (const std::string& note : weather.notes) lines.push_back("  note: " + note);
  if (scene.time.empty())
    lines.push_back(
        "  note: the scene has no date (time): the report's day and time do not place the sun");
  return lines;
}

}  // namespace nephele::weather

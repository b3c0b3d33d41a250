// nephele — from a weather report to the weather state (metar.h, weather_state.h): each cloud
// group becomes a layer (its cover in oktas, its base above the station, its genus and
// thickness from the group, CB or TCU, its height and the temperature's spread from the dew
// point), the wind sets the clouds' winds, the visibility and the obscurations the haze, the
// precipitation the storms' growth, and the report's day and time the scene's clock.
#pragma once

#include <string>
#include <vector>

#include "nephele/scene.h"
#include "weather/metar.h"
#include "weather/weather_state.h"

namespace nephele::weather {

// A layer of the report as drawn: the groups it stands for, where its clouds are (their bases
// and tops above the station, m) and the sky cover they report.
struct ReportLayer {
  std::string groups;  // "FEW025", or "SCT040 BKN080" for groups drawn as one layer
  // The scene's layer that draws it: "clouds", "cloud_layers[0]" ... or "cirrus".
  std::string slot;
  Genus genus = Genus::Cumulus;
  float type = -1.0f;  // on clouds.type's scale; < 0: the genus's own
  float cloud_base_m = 0.0f, cloud_top_m = 0.0f;
  float total_oktas = 0.0f;  // the sky covered up to this layer (the groups' summation)
  float own_oktas = 0.0f;    // this layer's own share, given the layers below
};

struct ReportWeather {
  WeatherState state;
  std::vector<ReportLayer> layers;
  // The sky cover in oktas the report states: its highest cover group's range (FEW 1-2,
  // SCT 3-4, BKN 5-7, OVC and VV 8); 0-0 with no cloud (SKC, CLR, NSC, NCD, CAVOK).
  int oktas_min = 0, oktas_max = 0;
  std::vector<std::string> notes;  // what the renderer could not draw as reported
};

// The report's weather over `base` (the scene's own state: what the report does not give is
// kept).
ReportWeather weather_from_metar(const MetarReport& report, const WeatherState& base);

// The scene's time (ISO 8601) with its day and clock taken from the report's (a METAR gives no
// month or year). Throws InputError when the scene has no date or its month has no such day.
std::string report_time(const MetarReport& report, const std::string& scene_time);

// Parses scene.weather.metar and applies it to the scene: its weather (apply_weather) and, when
// the scene has a date, its day and time. Throws InputError ("weather.metar: metar: group 5
// ...") and leaves the scene unchanged. Nothing without a report.
void apply_metar(Scene& scene);

// What --verbose prints of the scene's report: the report as read, each layer drawn (its groups,
// genus, where its clouds are, its oktas), the sky cover reported, and what could not be drawn
// as reported. Empty without a report.
std::vector<std::string> describe_metar(const Scene& scene);

}  // namespace nephele::weather

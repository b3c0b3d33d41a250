// nephele — the weather as a simulator's weather model states it: cloud layers (genus, base,
// top, coverage in oktas), the wind by altitude, the visibility, the precipitation. One
// function applies it to the scene's clouds, high clouds, cirrus and atmosphere; another reads
// it back. Weather reports (METAR, GRIB) will fill it.
#pragma once

#include <glm/vec2.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "nephele/scene.h"

namespace nephele::weather {

// The genera the renderer draws, each by the layer that can draw it: the low volumetric layer
// (Scene::clouds), the high volumetric layer (Scene::high_clouds) or the cirrus sheet.
enum class Genus {
  Stratus,
  Stratocumulus,
  Altocumulus,
  Cumulus,
  Cumulonimbus,  // volumetric, by clouds.type
  Cirrus,
  Cirrostratus,
  Cirrocumulus,  // the sheet, by cirrus.type
};
const char* to_string(Genus genus);
// A genus' own place on its layer's type scale: clouds.type's (stratus 0 ... cumulonimbus 1)
// or cirrus.type's (cirrus 0, cirrostratus 0.5, cirrocumulus 1).
float genus_type(Genus genus);
// Whether the cirrus sheet draws it.
bool is_sheet_genus(Genus genus);

struct CloudLayer {
  Genus genus = Genus::Cumulus;
  // The renderer's continuous type scale ([0, 1], clouds.type or cirrus.type) when it lies
  // between genera; < 0: the genus's own value.
  float type = -1.0f;
  float base_m = 1500.0f;       // above the ground
  float top_m = 4000.0f;        // above the ground; the sheet's altitude is its base
  float coverage_oktas = 0.0f;  // [0, 8]; 0 = no layer
  float density = 0.5f;         // the volumetric layers' clouds.density, [0, 1]
  float optical_depth = 0.3f;   // the sheet's vertical optical depth, [0, 4]
};

// The wind at one altitude above the ground; between levels it is linear, beyond them constant.
struct WindLevel {
  float altitude_m = 0.0f;
  glm::vec2 wind_mps{0.0f};  // east, north
};

// What falls (Scene::precipitation.kind): rain, drizzle, snow or sleet (wet snow, ice pellets).
enum class PrecipitationKind { None, Rain, Drizzle, Snow, Sleet };
const char* to_string(PrecipitationKind kind);  // "none", "rain", "drizzle", "snow", "sleet"

struct WeatherState {
  CloudLayer low;                                                                  // Scene::clouds
  CloudLayer high{Genus::Altocumulus, -1.0f, 6000.0f, 7000.0f, 0.0f, 0.4f, 0.0f};  // high_clouds
  // More volumetric layers (Scene::cloud_layers, at most kMaxCloudLayers - 2), each at its
  // base's wind. Unlike low's and high's (the renderer's shells), their base_m and top_m are
  // where their clouds' bases and tops are, as a report gives them; their type is the genus'.
  std::vector<CloudLayer> more;
  CloudLayer sheet{Genus::Cirrus, -1.0f, 9000.0f, 9000.0f, 0.0f, 0.0f, 0.3f};      // cirrus
  // By altitude, increasing. Empty: the scene's winds are left as they are (weather_state
  // gives none when the scene's layers' winds are no single profile).
  std::vector<WindLevel> wind;
  // Meteorological visibility at sea level (m): the distance at which a black object's
  // contrast falls to 2% (Koschmieder: extinction at 550 nm = 3.912 / V), in the rain or snow
  // as reported: the haze takes what the precipitation's own extinction leaves of it.
  float visibility_m = 200000.0f;
  // What falls from the low layer, at what rate of water (Scene::precipitation); the
  // renderer's cumulonimbus growth (clouds.precipitation) is `storm_growth`.
  PrecipitationKind precipitation = PrecipitationKind::None;
  float precipitation_mm_per_h = 0.0f;
  float storm_growth = 0.0f;  // clouds.precipitation, [0, 1]
  float lightning_per_min = 0.0f;  // a storm cell's flashes a minute (lightning.flashes_per_min)
};

// The wind of `levels` at `altitude_m` (zero when there are none).
glm::vec2 wind_at(const std::vector<WindLevel>& levels, float altitude_m);

// The visibility the scene's haze and precipitation give, and the Mie extinction a visibility needs
// (1/m, at sea level, after the air's own Rayleigh extinction at 550 nm); the visibilities the
// atmosphere can hold are [kMinVisibilityM, clear_air_visibility_m(atmosphere)].
float visibility_m(const AtmosphereParams& atmosphere);
float visibility_m(const Scene& scene);  // with the precipitation's extinction
float clear_air_visibility_m(const AtmosphereParams& atmosphere);
constexpr float kMinVisibilityM = 400.0f;  // Mie extinction 0.0098/m: validation's 0.01 limit

// A volumetric layer's clouds.coverage for `oktas` of the sky covered, seen from the ground,
// for clouds of `type` (clouds.type's scale), and back: the procedural field's coverage is a
// threshold on the weather map, and the sky it covers rises steeply from none at 0.3 to all
// of it at 0.6-0.7, sooner for deep clouds whose sides fill the view. Measured (the dome's
// sky cover, 4096 directions) for each genus in the shell a report gives it: stratus
// 150-1970 m, stratocumulus 460-1890, altocumulus 2010-3440, cumulus 1220-2720, towering
// cumulus 910-5900, cumulonimbus 910-9000; between genera the curves blend. 8 oktas is a
// coverage of 1: a closed deck without holes.
float coverage_for_oktas(float oktas, float type);
float oktas_for_coverage(float coverage, float type);
// The same for the cirrus sheet's cirrus.coverage and type (cirrus 0, cirrostratus 0.5,
// cirrocumulus 1), measured at its default optical depth (0.3): a cirrostratus veil covers the
// whole dome from a coverage of 0.2.
float sheet_coverage_for_oktas(float oktas, float type);
float oktas_for_sheet_coverage(float coverage, float type);

// Where clouds of `type` (clouds.type's scale) at `coverage` are in their shell: (x) the
// height fraction of their bases, (y) of their tops (measured; the more of the sky they cover,
// the more of their genus' profile they fill).
glm::vec2 cloud_fill(float type, float coverage);
// The scene's shell [bottom, top] (m, above the ground) in which clouds of `type` at `coverage`
// have their bases at base_m and their tops at top_m. A shell that would begin below the ground
// begins at it and keeps the bases; the tops are then lower than asked.
glm::vec2 cloud_shell_m(float type, float coverage, float base_m, float top_m);
// Where the clouds of `type` at `coverage` in the shell `shell_m` have their bases and tops (m).
glm::vec2 clouds_in_shell_m(float type, float coverage, glm::vec2 shell_m);

// The genus named `name` ("stratus", ... "cirrocumulus", to_string's), if any.
std::optional<Genus> parse_genus(std::string_view name);
// A [[cloud_layers]] layer's shell [bottom, top] (m above ground; cloud_shell_m for its genus)
// and its clouds.coverage (coverage_for_oktas); a genus it cannot draw counts as stratocumulus
// (validation refuses it).
glm::vec2 cloud_layer_shell_m(const CloudLayerParams& layer);
float cloud_layer_coverage(const CloudLayerParams& layer);

// The wind at the ground, `speed_mps` blowing from `from_deg` (clockwise from north), as
// levels: at the ground, and 1.93 times it at 1 km and above (a 1/7 power law up to the
// clouds). `towards` the unit vector it blows to (east, north).
glm::vec2 wind_towards(float from_deg);
std::vector<WindLevel> surface_wind_levels(glm::vec2 towards, float speed_mps);

// The state today's scene describes.
WeatherState weather_state(const Scene& scene);
// Writes the state into the scene's clouds, high clouds, cirrus and atmosphere (the Mie term
// keeps its albedo; the volumetric layers' coverage from their oktas by coverage_for_oktas, the
// sheet's as oktas / 8). Throws InputError naming the field ("weather.low.genus = cirrus: ...")
// for a genus the layer cannot draw, oktas outside [0, 8], a base at or above a top, winds
// not increasing in altitude, a visibility outside what the atmosphere holds; the scene is
// unchanged then. validate_scene checks the result as for any scene.
void apply_weather(const WeatherState& state, Scene& scene);

// [weather]'s wind and visibility keys (WeatherReportParams) onto the scene's layers' winds and
// haze, after its report; nothing when none is given. Throws InputError naming the key for a
// direction without a speed, a speed without a direction or both speeds; the scene is
// unchanged then.
void apply_weather_keys(Scene& scene);

}  // namespace nephele::weather

// nephele — atmospheric conditions by time of day and weather (seed 003, section 4): an
// artist-tuned parameter set for eight times of the day, linearly interpolated by the hour,
// in two tables (good and bad weather) blended by a weather factor. Pure data and arithmetic:
// no Vulkan, no scene file; the renderer decides what to do with the result.
//
// Colour units: linear HDR radiance on the old radiance scale, where a clear daytime zenith sky
// is about 1.0 and direct sunlight on a white surface about 20; one unit is 6400 cd/m^2
// (kLegacyLuxPerUnit, nephele/exposure.h), so the sun's 20 is the solar constant. The
// values are what the scene should look like at one fixed exposure over the whole day: the
// eye's adaptation is baked in, so night is dark (about 1/50 of day) but not the physical
// 1e-6 of day, which no single exposure would show.
#pragma once

#include <array>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

namespace nephele {

// One set of atmospheric conditions ("P" in the seed). Every field is interpolated linearly.
struct ConditionSet {
  // Sky dome: the sky's colour, blended towards the fog colour near the horizon by linear fog
  // over elevation: fully fogged at or below sky_fog_start_deg, clear at or above
  // sky_fog_end_deg (degrees above the horizon, start < end).
  glm::vec3 sky_zenith_rgb{0.0f};
  glm::vec3 sky_fog_rgb{0.0f};
  float sky_fog_start_deg = 0.0f;
  float sky_fog_end_deg = 20.0f;
  // Sun and moon discs: fogged the same way so that at rise and set they dissolve into the
  // sky (the seed uses the sky fog's colour; kept separate so an artist may differ).
  glm::vec3 disk_fog_rgb{0.0f};
  float disk_fog_start_deg = 0.0f;
  float disk_fog_end_deg = 8.0f;
  // Stars' opacity, [0, 1]: 1 at night, 0 by day (they fade in and out at dusk and dawn).
  float star_visibility = 0.0f;
  // The three lights of the world and the clouds: the sun's and the moon's directional light
  // (radiance scale of the light, like SunParams::illuminance, per channel) and the sky's
  // ambient light (irradiance / pi on a horizontal surface: the radiance of a uniform sky that
  // would light it the same).
  glm::vec3 sun_light_rgb{0.0f};
  glm::vec3 moon_light_rgb{0.0f};
  glm::vec3 ambient_rgb{0.0f};
  // Linear fog on scene objects: none nearer than fog_near_m, full fog_rgb at fog_far_m and
  // beyond (metres from the camera, 0 <= near < far).
  glm::vec3 fog_rgb{0.0f};
  float fog_near_m = 1000.0f;
  float fog_far_m = 50000.0f;
};

// A set and the hour of the day (local solar time, [0, 24)) at which it holds exactly.
struct Keyframe {
  float hour = 0.0f;
  ConditionSet set;
};

inline constexpr int kKeyframeCount = 8;

// The seed's eight sets D0..D7: night, early morning, morning, late morning, day, early
// evening, evening, late evening. Hours strictly increasing in [0, 24); the day wraps from
// the last key back to the first (+24 h).
struct ConditionTable {
  std::array<Keyframe, kKeyframeCount> keys;
};

// "night", "early_morning", "morning", "late_morning", "day", "early_evening", "evening",
// "late_evening" for 0..7 (the keys' names in scene files and messages); "" otherwise.
const char* keyframe_name(int index);

// The default keys' hours: 0, 5, 7, 10, 13, 17, 19, 21 (a mid-latitude equinox-to-summer day;
// a user moves them to fit the season and place).
inline constexpr std::array<float, kKeyframeCount> kDefaultKeyframeHours = {
    0.0f, 5.0f, 7.0f, 10.0f, 13.0f, 17.0f, 19.0f, 21.0f};

// Hand-tuned defaults. Good: clear blue day, orange-red dawn and sunset horizons, dark blue
// night with stars fully visible. Bad: overcast and hazy; greyer, darker, nearer fog, the
// sun's light mostly diffuse, no stars.
ConditionTable default_good_weather();
ConditionTable default_bad_weather();

// The conditions at `hour` (local solar time; any finite value, taken modulo 24): linear
// between the two keys around it, wrapping across midnight from the last key to the first.
// Exactly the key's set at a key's hour. The table must pass validate_table; a non-finite
// hour gives the first key's set.
ConditionSet interpolate(const ConditionTable& table, float hour);

// Field by field a + (b - a) * t, exact at t = 0 and t = 1; t is not clamped.
ConditionSet mix_conditions(const ConditionSet& a, const ConditionSet& b, float t);

// The seed's P = w * good + (1 - w) * bad; `weather` is clamped to [0, 1] (1 = good weather).
ConditionSet blend(const ConditionSet& good, const ConditionSet& bad, float weather);

// blend(interpolate(good, hour), interpolate(bad, hour), weather).
ConditionSet conditions_at(const ConditionTable& good, const ConditionTable& bad, float hour,
                           float weather);

// Local mean solar time (hours, [0, 24)) at longitude `lon_deg` (east positive) for the
// Julian day `julian_day_ut`: UT hours + lon / 15. (Not the apparent solar time: the equation
// of time, up to about 16 minutes, is left out.)
float local_solar_hour(double julian_day_ut, double lon_deg);

// Linear fog amount in [0, 1] at elevation `elevation_deg` (degrees above the horizon): 1 at
// or below the start elevation, 0 at or above the end, linear between. For the sky dome and
// for the sun and moon discs respectively.
float sky_fog_factor(const ConditionSet& set, float elevation_deg);
float disk_fog_factor(const ConditionSet& set, float elevation_deg);

// Linear fog amount in [0, 1] on a scene object `distance_m` from the camera: 0 at or nearer
// than fog_near_m, 1 at or beyond fog_far_m.
float object_fog_factor(const ConditionSet& set, float distance_m);

// "" when the table is usable, else one line naming the first bad field as
// "<name>.<key>.<field>" (e.g. "conditions.good.evening.hour"), its value and what is allowed:
// hours finite, in [0, 24) and strictly increasing; colours finite and >= 0; star_visibility
// in [0, 1]; fog elevations finite, in [-90, 90], start < end; 0 <= fog_near_m < fog_far_m,
// both finite.
std::string validate_table(const ConditionTable& table, std::string_view name = "conditions");

}  // namespace nephele

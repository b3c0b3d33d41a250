// nephele — time-of-day and weather conditions (seed 003, section 4): defaults, interpolation,
// blending and checks.
#include "nephele/conditions.h"

#include <algorithm>
#include <cmath>

#include "scene/scene_fields.h"

namespace nephele {
namespace {

using scene_detail::format_float;

// mix_conditions() and the tests name every field; a new field must be added there too.
static_assert(sizeof(ConditionSet) == 28 * sizeof(float),
              "ConditionSet changed: update mix_conditions() and validate_table()");

glm::vec3 lerp3(const glm::vec3& a, const glm::vec3& b, float t) {
  // std::lerp is exact at t = 0 and t = 1, so a key's hour gives the key's values bit for bit.
  return {std::lerp(a.x, b.x, t), std::lerp(a.y, b.y, t), std::lerp(a.z, b.z, t)};
}

// 1 at or below `start`, 0 at or above `end`, linear between. A degenerate range (start >= end,
// which validate_table rejects) becomes a step at `start` instead of a division by zero.
float falloff(float x, float start, float end) {
  if (!(x > start)) return 1.0f;
  if (!(x < end)) return 0.0f;
  return (end - x) / (end - start);
}

// The seed fogs the sun and the moon with the sky fog's colour, so that at rise and set they
// melt into the sky behind them; the defaults keep that.
ConditionSet disk_fog_as_sky(ConditionSet set) {
  set.disk_fog_rgb = set.sky_fog_rgb;
  return set;
}

ConditionTable make_table(const std::array<ConditionSet, kKeyframeCount>& sets) {
  ConditionTable table;
  for (int i = 0; i < kKeyframeCount; ++i)
    table.keys[i] = Keyframe{kDefaultKeyframeHours[i], disk_fog_as_sky(sets[i])};
  return table;
}

// "(0.3, -0.1, 0.34)", as validate.cpp writes a scene key's vector.
std::string vector_text(const glm::vec3& v) {
  std::string text = "(";
  for (int c = 0; c < 3; ++c) {
    if (c > 0) text += ", ";
    text += format_float(v[c]);
  }
  return text + ")";
}

// Collects the first failure as "key = value: what is allowed".
class TableChecker {
 public:
  explicit TableChecker(std::string_view name) : name_(name) {}

  const std::string& error() const { return error_; }

  std::string key(int index, const char* field) const {
    return name_ + "." + keyframe_name(index) + "." + field;
  }

  void fail(const std::string& key, const std::string& value, const std::string& allowed) {
    if (error_.empty()) error_ = key + " = " + value + ": " + allowed;
  }

  // HDR colours, on the old radiance scale (6400 cd/m^2 a unit; at most 1e6).
  void colour(int index, const char* field, const glm::vec3& v) {
    for (int c = 0; c < 3; ++c)
      if (!(v[c] >= 0.0f && v[c] <= 1.0e6f)) {
        fail(key(index, field), vector_text(v), "every component must be in [0, 1e+06]");
        return;
      }
  }

  void in_range(int index, const char* field, float value, float min, float max) {
    if (!(value >= min && value <= max))
      fail(key(index, field), format_float(value),
           "must be in [" + format_float(min) + ", " + format_float(max) + "]");
  }

  void less_than(int index, const char* field, float value, const char* other_field,
                 float other) {
    if (!(value < other))
      fail(key(index, field), format_float(value),
           "must be < " + key(index, other_field) + " (" + format_float(other) + ")");
  }

 private:
  std::string name_;
  std::string error_;
};

}  // namespace

const char* keyframe_name(int index) {
  static const char* const names[kKeyframeCount] = {
      "night", "early_morning", "morning", "late_morning",
      "day",   "early_evening", "evening", "late_evening"};
  return index >= 0 && index < kKeyframeCount ? names[index] : "";
}

// Values are tuned by eye at one exposure for the whole day (see the header): the day's sun
// (20) and zenith (about 1 in blue) set the scale, the night is about 1/50 of the day. The
// sky's horizon colour (sky_fog_rgb) carries the dawn and sunset colours; the zenith stays blue
// and only darkens. Sun light reddens as the sun gets low (longer path through the air).
ConditionTable default_good_weather() {
  return make_table({{
      // night (00:00): dark blue sky, stars fully visible, moonlight the key light.
      {.sky_zenith_rgb = {0.004f, 0.008f, 0.022f},
       .sky_fog_rgb = {0.010f, 0.014f, 0.030f},
       .sky_fog_start_deg = 0.0f, .sky_fog_end_deg = 20.0f,
       .disk_fog_start_deg = 0.0f, .disk_fog_end_deg = 8.0f,
       .star_visibility = 1.0f,
       .sun_light_rgb = {0.0f, 0.0f, 0.0f},
       .moon_light_rgb = {0.30f, 0.36f, 0.48f},
       .ambient_rgb = {0.010f, 0.014f, 0.030f},
       .fog_rgb = {0.008f, 0.011f, 0.022f},
       .fog_near_m = 1500.0f, .fog_far_m = 40000.0f},
      // early morning (05:00): dawn, orange-red horizon under a still dark zenith, stars fading.
      {.sky_zenith_rgb = {0.05f, 0.06f, 0.14f},
       .sky_fog_rgb = {0.55f, 0.25f, 0.10f},
       .sky_fog_start_deg = 0.0f, .sky_fog_end_deg = 18.0f,
       .disk_fog_start_deg = 0.0f, .disk_fog_end_deg = 6.0f,
       .star_visibility = 0.4f,
       .sun_light_rgb = {2.0f, 0.7f, 0.2f},
       .moon_light_rgb = {0.15f, 0.18f, 0.24f},
       .ambient_rgb = {0.08f, 0.07f, 0.10f},
       .fog_rgb = {0.30f, 0.16f, 0.10f},
       .fog_near_m = 1500.0f, .fog_far_m = 35000.0f},
      // morning (07:00): low golden sun, pale peach horizon.
      {.sky_zenith_rgb = {0.18f, 0.28f, 0.55f},
       .sky_fog_rgb = {0.95f, 0.70f, 0.48f},
       .sky_fog_start_deg = 0.0f, .sky_fog_end_deg = 20.0f,
       .disk_fog_start_deg = 0.0f, .disk_fog_end_deg = 8.0f,
       .star_visibility = 0.0f,
       .sun_light_rgb = {10.0f, 7.0f, 4.2f},
       .moon_light_rgb = {0.0f, 0.0f, 0.0f},
       .ambient_rgb = {0.30f, 0.32f, 0.42f},
       .fog_rgb = {0.70f, 0.58f, 0.48f},
       .fog_near_m = 2000.0f, .fog_far_m = 50000.0f},
      // late morning (10:00): clear blue sky, nearly white sun.
      {.sky_zenith_rgb = {0.27f, 0.48f, 0.92f},
       .sky_fog_rgb = {0.80f, 0.90f, 1.05f},
       .sky_fog_start_deg = 0.0f, .sky_fog_end_deg = 25.0f,
       .disk_fog_start_deg = 0.0f, .disk_fog_end_deg = 8.0f,
       .star_visibility = 0.0f,
       .sun_light_rgb = {18.5f, 17.5f, 15.5f},
       .moon_light_rgb = {0.0f, 0.0f, 0.0f},
       .ambient_rgb = {0.40f, 0.52f, 0.80f},
       .fog_rgb = {0.70f, 0.78f, 0.90f},
       .fog_near_m = 3000.0f, .fog_far_m = 70000.0f},
      // day (13:00): the clearest and brightest; whitish haze at the horizon.
      {.sky_zenith_rgb = {0.30f, 0.55f, 1.00f},
       .sky_fog_rgb = {0.85f, 0.95f, 1.10f},
       .sky_fog_start_deg = 0.0f, .sky_fog_end_deg = 25.0f,
       .disk_fog_start_deg = 0.0f, .disk_fog_end_deg = 8.0f,
       .star_visibility = 0.0f,
       .sun_light_rgb = {20.0f, 19.5f, 18.5f},
       .moon_light_rgb = {0.0f, 0.0f, 0.0f},
       .ambient_rgb = {0.42f, 0.56f, 0.85f},
       .fog_rgb = {0.75f, 0.83f, 0.95f},
       .fog_near_m = 4000.0f, .fog_far_m = 80000.0f},
      // early evening (17:00): warmer, golden light, yellow-orange horizon.
      {.sky_zenith_rgb = {0.26f, 0.44f, 0.80f},
       .sky_fog_rgb = {0.95f, 0.82f, 0.62f},
       .sky_fog_start_deg = 0.0f, .sky_fog_end_deg = 22.0f,
       .disk_fog_start_deg = 0.0f, .disk_fog_end_deg = 8.0f,
       .star_visibility = 0.0f,
       .sun_light_rgb = {16.0f, 12.5f, 8.5f},
       .moon_light_rgb = {0.0f, 0.0f, 0.0f},
       .ambient_rgb = {0.38f, 0.42f, 0.58f},
       .fog_rgb = {0.80f, 0.70f, 0.58f},
       .fog_near_m = 3000.0f, .fog_far_m = 60000.0f},
      // evening (19:00): sunset, orange-red horizon and sunlight.
      {.sky_zenith_rgb = {0.14f, 0.16f, 0.34f},
       .sky_fog_rgb = {0.90f, 0.40f, 0.14f},
       .sky_fog_start_deg = 0.0f, .sky_fog_end_deg = 25.0f,
       .disk_fog_start_deg = 0.0f, .disk_fog_end_deg = 6.0f,
       .star_visibility = 0.0f,
       .sun_light_rgb = {7.0f, 2.6f, 0.8f},
       .moon_light_rgb = {0.06f, 0.07f, 0.10f},
       .ambient_rgb = {0.22f, 0.16f, 0.18f},
       .fog_rgb = {0.55f, 0.30f, 0.16f},
       .fog_near_m = 2000.0f, .fog_far_m = 45000.0f},
      // late evening (21:00): dusk, a dull red band low in the west, first stars.
      {.sky_zenith_rgb = {0.03f, 0.03f, 0.08f},
       .sky_fog_rgb = {0.22f, 0.08f, 0.06f},
       .sky_fog_start_deg = 0.0f, .sky_fog_end_deg = 20.0f,
       .disk_fog_start_deg = 0.0f, .disk_fog_end_deg = 8.0f,
       .star_visibility = 0.6f,
       .sun_light_rgb = {0.4f, 0.08f, 0.03f},
       .moon_light_rgb = {0.22f, 0.26f, 0.36f},
       .ambient_rgb = {0.03f, 0.03f, 0.06f},
       .fog_rgb = {0.12f, 0.06f, 0.05f},
       .fog_near_m = 1500.0f, .fog_far_m = 40000.0f},
  }});
}

// Overcast and hazy: near-grey colours, the sun's light mostly turned into ambient light, the
// sun and moon discs dissolved in the haze up to about 40 degrees, fog within kilometres, no
// stars. Every key is darker than the good weather's at the same hour.
ConditionTable default_bad_weather() {
  return make_table({{
      // night
      {.sky_zenith_rgb = {0.004f, 0.005f, 0.007f},
       .sky_fog_rgb = {0.006f, 0.007f, 0.009f},
       .sky_fog_start_deg = 0.0f, .sky_fog_end_deg = 40.0f,
       .disk_fog_start_deg = 5.0f, .disk_fog_end_deg = 45.0f,
       .star_visibility = 0.0f,
       .sun_light_rgb = {0.0f, 0.0f, 0.0f},
       .moon_light_rgb = {0.06f, 0.065f, 0.075f},
       .ambient_rgb = {0.006f, 0.007f, 0.009f},
       .fog_rgb = {0.005f, 0.006f, 0.008f},
       .fog_near_m = 200.0f, .fog_far_m = 6000.0f},
      // early morning
      {.sky_zenith_rgb = {0.03f, 0.03f, 0.04f},
       .sky_fog_rgb = {0.10f, 0.08f, 0.07f},
       .sky_fog_start_deg = 0.0f, .sky_fog_end_deg = 40.0f,
       .disk_fog_start_deg = 5.0f, .disk_fog_end_deg = 45.0f,
       .star_visibility = 0.0f,
       .sun_light_rgb = {0.3f, 0.2f, 0.15f},
       .moon_light_rgb = {0.03f, 0.03f, 0.04f},
       .ambient_rgb = {0.03f, 0.03f, 0.035f},
       .fog_rgb = {0.07f, 0.06f, 0.055f},
       .fog_near_m = 150.0f, .fog_far_m = 5000.0f},
      // morning
      {.sky_zenith_rgb = {0.14f, 0.15f, 0.17f},
       .sky_fog_rgb = {0.30f, 0.29f, 0.29f},
       .sky_fog_start_deg = 0.0f, .sky_fog_end_deg = 40.0f,
       .disk_fog_start_deg = 3.0f, .disk_fog_end_deg = 40.0f,
       .star_visibility = 0.0f,
       .sun_light_rgb = {2.0f, 1.7f, 1.4f},
       .moon_light_rgb = {0.0f, 0.0f, 0.0f},
       .ambient_rgb = {0.16f, 0.16f, 0.18f},
       .fog_rgb = {0.24f, 0.23f, 0.23f},
       .fog_near_m = 150.0f, .fog_far_m = 6000.0f},
      // late morning
      {.sky_zenith_rgb = {0.26f, 0.27f, 0.30f},
       .sky_fog_rgb = {0.40f, 0.41f, 0.43f},
       .sky_fog_start_deg = 0.0f, .sky_fog_end_deg = 40.0f,
       .disk_fog_start_deg = 3.0f, .disk_fog_end_deg = 40.0f,
       .star_visibility = 0.0f,
       .sun_light_rgb = {3.5f, 3.4f, 3.3f},
       .moon_light_rgb = {0.0f, 0.0f, 0.0f},
       .ambient_rgb = {0.26f, 0.27f, 0.30f},
       .fog_rgb = {0.34f, 0.35f, 0.37f},
       .fog_near_m = 200.0f, .fog_far_m = 8000.0f},
      // day
      {.sky_zenith_rgb = {0.30f, 0.31f, 0.34f},
       .sky_fog_rgb = {0.45f, 0.46f, 0.48f},
       .sky_fog_start_deg = 0.0f, .sky_fog_end_deg = 40.0f,
       .disk_fog_start_deg = 3.0f, .disk_fog_end_deg = 40.0f,
       .star_visibility = 0.0f,
       .sun_light_rgb = {4.0f, 3.9f, 3.8f},
       .moon_light_rgb = {0.0f, 0.0f, 0.0f},
       .ambient_rgb = {0.30f, 0.31f, 0.34f},
       .fog_rgb = {0.38f, 0.39f, 0.41f},
       .fog_near_m = 250.0f, .fog_far_m = 9000.0f},
      // early evening
      {.sky_zenith_rgb = {0.22f, 0.22f, 0.25f},
       .sky_fog_rgb = {0.36f, 0.35f, 0.35f},
       .sky_fog_start_deg = 0.0f, .sky_fog_end_deg = 40.0f,
       .disk_fog_start_deg = 3.0f, .disk_fog_end_deg = 40.0f,
       .star_visibility = 0.0f,
       .sun_light_rgb = {3.0f, 2.6f, 2.2f},
       .moon_light_rgb = {0.0f, 0.0f, 0.0f},
       .ambient_rgb = {0.22f, 0.22f, 0.24f},
       .fog_rgb = {0.30f, 0.29f, 0.29f},
       .fog_near_m = 200.0f, .fog_far_m = 7000.0f},
      // evening: a faint warm tint is all that is left of the sunset.
      {.sky_zenith_rgb = {0.08f, 0.075f, 0.085f},
       .sky_fog_rgb = {0.20f, 0.15f, 0.12f},
       .sky_fog_start_deg = 0.0f, .sky_fog_end_deg = 40.0f,
       .disk_fog_start_deg = 3.0f, .disk_fog_end_deg = 40.0f,
       .star_visibility = 0.0f,
       .sun_light_rgb = {1.0f, 0.6f, 0.35f},
       .moon_light_rgb = {0.01f, 0.01f, 0.012f},
       .ambient_rgb = {0.08f, 0.07f, 0.075f},
       .fog_rgb = {0.15f, 0.12f, 0.10f},
       .fog_near_m = 150.0f, .fog_far_m = 5000.0f},
      // late evening
      {.sky_zenith_rgb = {0.015f, 0.015f, 0.02f},
       .sky_fog_rgb = {0.03f, 0.025f, 0.025f},
       .sky_fog_start_deg = 0.0f, .sky_fog_end_deg = 40.0f,
       .disk_fog_start_deg = 5.0f, .disk_fog_end_deg = 45.0f,
       .star_visibility = 0.0f,
       .sun_light_rgb = {0.05f, 0.02f, 0.01f},
       .moon_light_rgb = {0.04f, 0.045f, 0.055f},
       .ambient_rgb = {0.015f, 0.015f, 0.02f},
       .fog_rgb = {0.02f, 0.018f, 0.018f},
       .fog_near_m = 150.0f, .fog_far_m = 5000.0f},
  }});
}

ConditionSet mix_conditions(const ConditionSet& a, const ConditionSet& b, float t) {
  ConditionSet r;
  r.sky_zenith_rgb = lerp3(a.sky_zenith_rgb, b.sky_zenith_rgb, t);
  r.sky_fog_rgb = lerp3(a.sky_fog_rgb, b.sky_fog_rgb, t);
  r.sky_fog_start_deg = std::lerp(a.sky_fog_start_deg, b.sky_fog_start_deg, t);
  r.sky_fog_end_deg = std::lerp(a.sky_fog_end_deg, b.sky_fog_end_deg, t);
  r.disk_fog_rgb = lerp3(a.disk_fog_rgb, b.disk_fog_rgb, t);
  r.disk_fog_start_deg = std::lerp(a.disk_fog_start_deg, b.disk_fog_start_deg, t);
  r.disk_fog_end_deg = std::lerp(a.disk_fog_end_deg, b.disk_fog_end_deg, t);
  r.star_visibility = std::lerp(a.star_visibility, b.star_visibility, t);
  r.sun_light_rgb = lerp3(a.sun_light_rgb, b.sun_light_rgb, t);
  r.moon_light_rgb = lerp3(a.moon_light_rgb, b.moon_light_rgb, t);
  r.ambient_rgb = lerp3(a.ambient_rgb, b.ambient_rgb, t);
  r.fog_rgb = lerp3(a.fog_rgb, b.fog_rgb, t);
  r.fog_near_m = std::lerp(a.fog_near_m, b.fog_near_m, t);
  r.fog_far_m = std::lerp(a.fog_far_m, b.fog_far_m, t);
  return r;
}

ConditionSet interpolate(const ConditionTable& table, float hour) {
  const auto& k = table.keys;
  if (!std::isfinite(hour)) return k[0].set;
  float h = std::fmod(hour, 24.0f);
  if (h < 0.0f) h += 24.0f;
  if (h >= 24.0f) h = 0.0f;  // -tiny + 24 rounds to 24

  // Linear from key a at hour h0 to key b at hour h1 > h0.
  auto between = [](const Keyframe& a, float h0, const Keyframe& b, float h1, float x) {
    if (!(h1 > h0)) return a.set;  // an invalid table; validate_table says why
    return mix_conditions(a.set, b.set, (x - h0) / (h1 - h0));
  };

  const Keyframe& first = k.front();
  const Keyframe& last = k.back();
  // Across midnight: from the last key to the first one a day later (the seed's night at both
  // ends of the day). Covers the hours before the first key when it is not at 0.
  if (h >= last.hour) return between(last, last.hour, first, first.hour + 24.0f, h);
  if (h < first.hour) return between(last, last.hour, first, first.hour + 24.0f, h + 24.0f);
  for (int i = 0; i + 1 < kKeyframeCount; ++i)
    if (h < k[i + 1].hour) return between(k[i], k[i].hour, k[i + 1], k[i + 1].hour, h);
  return last.set;  // unreachable for a valid table
}

ConditionSet blend(const ConditionSet& good, const ConditionSet& bad, float weather) {
  const float w = std::isfinite(weather) ? std::clamp(weather, 0.0f, 1.0f) : 1.0f;
  return mix_conditions(bad, good, w);
}

ConditionSet conditions_at(const ConditionTable& good, const ConditionTable& bad, float hour,
                           float weather) {
  return blend(interpolate(good, hour), interpolate(bad, hour), weather);
}

float local_solar_hour(double julian_day_ut, double lon_deg) {
  // Julian days begin at noon: JD x.5 is 0 h UT.
  const double day = julian_day_ut - 0.5;
  const double ut_hours = (day - std::floor(day)) * 24.0;
  double hours = std::fmod(ut_hours + lon_deg / 15.0, 24.0);
  if (hours < 0.0) hours += 24.0;
  const float result = static_cast<float>(hours);
  return result >= 24.0f ? 0.0f : result;  // 23.99999999 rounds to 24 in float
}

float sky_fog_factor(const ConditionSet& set, float elevation_deg) {
  return falloff(elevation_deg, set.sky_fog_start_deg, set.sky_fog_end_deg);
}

float disk_fog_factor(const ConditionSet& set, float elevation_deg) {
  return falloff(elevation_deg, set.disk_fog_start_deg, set.disk_fog_end_deg);
}

float object_fog_factor(const ConditionSet& set, float distance_m) {
  return 1.0f - falloff(distance_m, set.fog_near_m, set.fog_far_m);
}

std::string validate_table(const ConditionTable& table, std::string_view name) {
  TableChecker check(name);
  for (int i = 0; i < kKeyframeCount && check.error().empty(); ++i) {
    const Keyframe& key = table.keys[i];
    const ConditionSet& s = key.set;
    if (!(key.hour >= 0.0f && key.hour < 24.0f))
      check.fail(check.key(i, "hour"), format_float(key.hour), "must be in [0, 24)");
    else if (i > 0 && !(key.hour > table.keys[i - 1].hour))
      check.fail(check.key(i, "hour"), format_float(key.hour),
                 "must be > " + check.key(i - 1, "hour") + " (" +
                     format_float(table.keys[i - 1].hour) + "): hours strictly increase");
    check.colour(i, "sky_zenith_rgb", s.sky_zenith_rgb);
    check.colour(i, "sky_fog_rgb", s.sky_fog_rgb);
    check.in_range(i, "sky_fog_start_deg", s.sky_fog_start_deg, -90.0f, 90.0f);
    check.in_range(i, "sky_fog_end_deg", s.sky_fog_end_deg, -90.0f, 90.0f);
    check.less_than(i, "sky_fog_start_deg", s.sky_fog_start_deg, "sky_fog_end_deg",
                    s.sky_fog_end_deg);
    check.colour(i, "disk_fog_rgb", s.disk_fog_rgb);
    check.in_range(i, "disk_fog_start_deg", s.disk_fog_start_deg, -90.0f, 90.0f);
    check.in_range(i, "disk_fog_end_deg", s.disk_fog_end_deg, -90.0f, 90.0f);
    check.less_than(i, "disk_fog_start_deg", s.disk_fog_start_deg, "disk_fog_end_deg",
                    s.disk_fog_end_deg);
    check.in_range(i, "star_visibility", s.star_visibility, 0.0f, 1.0f);
    check.colour(i, "sun_light_rgb", s.sun_light_rgb);
    check.colour(i, "moon_light_rgb", s.moon_light_rgb);
    check.colour(i, "ambient_rgb", s.ambient_rgb);
    check.colour(i, "fog_rgb", s.fog_rgb);
    if (!(std::isfinite(s.fog_near_m) && s.fog_near_m >= 0.0f))
      check.fail(check.key(i, "fog_near_m"), format_float(s.fog_near_m),
                 "must be a finite number >= 0");
    if (!std::isfinite(s.fog_far_m))
      check.fail(check.key(i, "fog_far_m"), format_float(s.fog_far_m), "must be finite");
    check.less_than(i, "fog_near_m", s.fog_near_m, "fog_far_m", s.fog_far_m);
  }
  return check.error();
}

}  // namespace nephele

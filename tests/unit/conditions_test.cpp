// Time-of-day and weather conditions (seed 003, section 4): interpolation between the eight
// keys, the weather blend, the defaults' look, local solar time and the table checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "nephele/conditions.h"
#include "nephele/sky.h"

namespace nephele {
namespace {

constexpr int kFields = 28;  // 7 colours x 3 + 7 scalars
static_assert(sizeof(ConditionSet) == kFields * sizeof(float),
              "ConditionSet changed: update to_fields / from_fields");

// Every field of a set, in declaration order, so tests can check all of them at once.
std::vector<float> to_fields(const ConditionSet& s) {
  std::vector<float> f;
  auto add3 = [&](const glm::vec3& v) { f.insert(f.end(), {v.x, v.y, v.z}); };
  add3(s.sky_zenith_rgb);
  add3(s.sky_fog_rgb);
  f.push_back(s.sky_fog_start_deg);
  f.push_back(s.sky_fog_end_deg);
  add3(s.disk_fog_rgb);
  f.push_back(s.disk_fog_start_deg);
  f.push_back(s.disk_fog_end_deg);
  f.push_back(s.star_visibility);
  add3(s.sun_light_rgb);
  add3(s.moon_light_rgb);
  add3(s.ambient_rgb);
  add3(s.fog_rgb);
  f.push_back(s.fog_near_m);
  f.push_back(s.fog_far_m);
  return f;
}

ConditionSet from_fields(const std::vector<float>& f) {
  size_t i = 0;
  auto get3 = [&] {
    glm::vec3 v(f[i], f[i + 1], f[i + 2]);
    i += 3;
    return v;
  };
  ConditionSet s;
  s.sky_zenith_rgb = get3();
  s.sky_fog_rgb = get3();
  s.sky_fog_start_deg = f[i++];
  s.sky_fog_end_deg = f[i++];
  s.disk_fog_rgb = get3();
  s.disk_fog_start_deg = f[i++];
  s.disk_fog_end_deg = f[i++];
  s.star_visibility = f[i++];
  s.sun_light_rgb = get3();
  s.moon_light_rgb = get3();
  s.ambient_rgb = get3();
  s.fog_rgb = get3();
  s.fog_near_m = f[i++];
  s.fog_far_m = f[i++];
  return s;
}

// A table whose every field differs between keys, irregularly (not linear in the key's
// index), so that taking the wrong neighbour, the wrong weight or skipping a field shows.
ConditionTable synthetic_table(const std::array<float, kKeyframeCount>& hours) {
  // For each field the eight keys take eight different values in an irregular order.
  const float offsets[kKeyframeCount] = {0, 5, 2, 9, 4, 11, 7, 13};
  ConditionTable t;
  for (int k = 0; k < kKeyframeCount; ++k) {
    std::vector<float> f(kFields);
    for (int j = 0; j < kFields; ++j) f[j] = 1.0f + 0.5f * j + offsets[(k + j) % kKeyframeCount];
    t.keys[k] = Keyframe{hours[k], from_fields(f)};
  }
  return t;
}

// Every field of `actual` within a relative tolerance of the expected value.
void expect_fields_near(const std::vector<float>& actual, const std::vector<float>& expected,
                        float relative = 1e-5f) {
  ASSERT_EQ(actual.size(), expected.size());
  for (size_t j = 0; j < actual.size(); ++j)
    EXPECT_NEAR(actual[j], expected[j], relative * std::max(1.0f, std::abs(expected[j])))
        << "field " << j;
}

// a + (b - a) * t, field by field, computed here independently of the library.
std::vector<float> lerp_fields(const ConditionSet& a, const ConditionSet& b, float t) {
  std::vector<float> fa = to_fields(a), fb = to_fields(b), r(kFields);
  for (int j = 0; j < kFields; ++j) r[j] = fa[j] + (fb[j] - fa[j]) * t;
  return r;
}

float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// (max - min) / max: 0 for grey.
float saturation(const glm::vec3& c) {
  const float hi = std::max({c.r, c.g, c.b}), lo = std::min({c.r, c.g, c.b});
  return hi > 0.0f ? (hi - lo) / hi : 0.0f;
}

enum Key { kNight, kEarlyMorning, kMorning, kLateMorning, kDay, kEarlyEvening, kEvening, kLateEvening };

TEST(ConditionsKeys, NamesAndDefaultHours) {
  const char* names[] = {"night", "early_morning", "morning", "late_morning",
                         "day",   "early_evening", "evening", "late_evening"};
  for (int i = 0; i < kKeyframeCount; ++i) EXPECT_STREQ(keyframe_name(i), names[i]);
  EXPECT_STREQ(keyframe_name(-1), "");
  EXPECT_STREQ(keyframe_name(8), "");
  const float hours[] = {0, 5, 7, 10, 13, 17, 19, 21};
  for (const ConditionTable& t : {default_good_weather(), default_bad_weather()})
    for (int i = 0; i < kKeyframeCount; ++i) EXPECT_EQ(t.keys[i].hour, hours[i]) << i;
}

TEST(ConditionsInterpolate, KeyHoursGiveTheKeysExactly) {
  for (const ConditionTable& t :
       {synthetic_table(kDefaultKeyframeHours), default_good_weather(), default_bad_weather()})
    for (int i = 0; i < kKeyframeCount; ++i) {
      SCOPED_TRACE(keyframe_name(i));
      EXPECT_EQ(to_fields(interpolate(t, t.keys[i].hour)), to_fields(t.keys[i].set));
    }
}

TEST(ConditionsInterpolate, HalfwayIsTheMean) {
  const ConditionTable t = synthetic_table(kDefaultKeyframeHours);
  for (int i = 0; i + 1 < kKeyframeCount; ++i) {
    SCOPED_TRACE(keyframe_name(i));
    const float mid = 0.5f * (t.keys[i].hour + t.keys[i + 1].hour);
    expect_fields_near(to_fields(interpolate(t, mid)), lerp_fields(t.keys[i].set, t.keys[i + 1].set, 0.5f));
  }
}

// The mean would not notice swapped weights; a quarter of the way does.
TEST(ConditionsInterpolate, WeightsFollowTheHour) {
  const ConditionTable t = synthetic_table(kDefaultKeyframeHours);
  // 07:00 -> 10:00: 07:45 is a quarter of the way, 09:15 three quarters.
  expect_fields_near(to_fields(interpolate(t, 7.75f)),
                     lerp_fields(t.keys[kMorning].set, t.keys[kLateMorning].set, 0.25f));
  expect_fields_near(to_fields(interpolate(t, 9.25f)),
                     lerp_fields(t.keys[kMorning].set, t.keys[kLateMorning].set, 0.75f));
  // Just before a key: almost that key, not the one before.
  expect_fields_near(to_fields(interpolate(t, 12.999f)),
                     lerp_fields(t.keys[kLateMorning].set, t.keys[kDay].set, 2.999f / 3.0f));
}

TEST(ConditionsInterpolate, WrapsAcrossMidnight) {
  for (const ConditionTable& t : {synthetic_table(kDefaultKeyframeHours), default_good_weather()}) {
    const ConditionSet& late = t.keys[kLateEvening].set;
    const ConditionSet& night = t.keys[kNight].set;
    // Late evening at 21:00, night at 24:00 (= 0:00).
    expect_fields_near(to_fields(interpolate(t, 22.5f)), lerp_fields(late, night, 0.5f));
    expect_fields_near(to_fields(interpolate(t, 23.0f)), lerp_fields(late, night, 2.0f / 3.0f));
    // Hours outside [0, 24) are taken modulo 24.
    EXPECT_EQ(to_fields(interpolate(t, 24.0f)), to_fields(night));
    expect_fields_near(to_fields(interpolate(t, 46.5f)), lerp_fields(late, night, 0.5f));
    expect_fields_near(to_fields(interpolate(t, -1.5f)), lerp_fields(late, night, 0.5f));
    expect_fields_near(to_fields(interpolate(t, 26.0f)), to_fields(interpolate(t, 2.0f)));
  }
}

// When the first key is after midnight, the hours before it also lie on the wrapping segment.
TEST(ConditionsInterpolate, WrapsWhenTheFirstKeyIsAfterMidnight) {
  const ConditionTable t = synthetic_table({2, 5, 7, 10, 13, 17, 19, 21});
  const ConditionSet& late = t.keys[kLateEvening].set;
  const ConditionSet& first = t.keys[kNight].set;
  // 21:00 -> 26:00 (02:00 the next day): 01:00 is 4/5 of the way, 23:00 2/5.
  expect_fields_near(to_fields(interpolate(t, 1.0f)), lerp_fields(late, first, 0.8f));
  expect_fields_near(to_fields(interpolate(t, 0.0f)), lerp_fields(late, first, 0.6f));
  expect_fields_near(to_fields(interpolate(t, 23.0f)), lerp_fields(late, first, 0.4f));
  EXPECT_EQ(to_fields(interpolate(t, 2.0f)), to_fields(first));
}

TEST(ConditionsInterpolate, NonFiniteHourGivesTheFirstKey) {
  const ConditionTable t = default_good_weather();
  EXPECT_EQ(to_fields(interpolate(t, NAN)), to_fields(t.keys[0].set));
  EXPECT_EQ(to_fields(interpolate(t, INFINITY)), to_fields(t.keys[0].set));
}

// Sampled every minute over a day (and across midnight), no field jumps: the largest step is
// at most 1% of that field's range over the day (the shortest key interval is 2 h = 120 min,
// so a continuous piecewise-linear curve moves at most 1/120 of its range a minute).
TEST(ConditionsInterpolate, ContinuousOverTheDay) {
  for (const ConditionTable& t :
       {default_good_weather(), default_bad_weather(), synthetic_table(kDefaultKeyframeHours)}) {
    std::vector<std::vector<float>> samples;
    for (int minute = 0; minute <= 24 * 60; ++minute)  // 24:00 closes the loop at midnight
      samples.push_back(to_fields(interpolate(t, minute / 60.0f)));
    EXPECT_EQ(samples.front(), samples.back());
    for (int j = 0; j < kFields; ++j) {
      float lo = samples[0][j], hi = lo, worst = 0.0f;
      int worst_minute = 0;
      for (size_t m = 1; m < samples.size(); ++m) {
        lo = std::min(lo, samples[m][j]);
        hi = std::max(hi, samples[m][j]);
        const float step = std::abs(samples[m][j] - samples[m - 1][j]);
        if (step > worst) worst = step, worst_minute = static_cast<int>(m);
      }
      EXPECT_LE(worst, 0.01f * (hi - lo)) << "field " << j << " at minute " << worst_minute;
    }
  }
}

TEST(ConditionsBlend, WeatherBlendsGoodAndBad) {
  const ConditionTable t = synthetic_table(kDefaultKeyframeHours);
  const ConditionSet& good = t.keys[kDay].set;
  const ConditionSet& bad = t.keys[kEvening].set;
  EXPECT_EQ(to_fields(blend(good, bad, 1.0f)), to_fields(good));
  EXPECT_EQ(to_fields(blend(good, bad, 0.0f)), to_fields(bad));
  expect_fields_near(to_fields(blend(good, bad, 0.5f)), lerp_fields(good, bad, 0.5f));
  // w = 0.75 is mostly good weather: P = 0.75 good + 0.25 bad.
  expect_fields_near(to_fields(blend(good, bad, 0.75f)), lerp_fields(bad, good, 0.75f));
  // Clamped to [0, 1].
  EXPECT_EQ(to_fields(blend(good, bad, 2.0f)), to_fields(good));
  EXPECT_EQ(to_fields(blend(good, bad, -1.0f)), to_fields(bad));
}

TEST(ConditionsBlend, ConditionsAtInterpolatesBothTablesThenBlends) {
  const ConditionTable good = default_good_weather(), bad = default_bad_weather();
  for (float hour : {0.0f, 6.0f, 13.0f, 18.25f, 22.5f})
    for (float w : {0.0f, 0.3f, 1.0f}) {
      SCOPED_TRACE(testing::Message() << "hour " << hour << " weather " << w);
      expect_fields_near(to_fields(conditions_at(good, bad, hour, w)),
                         lerp_fields(interpolate(bad, hour), interpolate(good, hour), w));
    }
  EXPECT_EQ(to_fields(conditions_at(good, bad, 13.0f, 1.0f)), to_fields(good.keys[kDay].set));
  EXPECT_EQ(to_fields(conditions_at(good, bad, 13.0f, 0.0f)), to_fields(bad.keys[kDay].set));
}

TEST(ConditionsDefaults, PassValidation) {
  EXPECT_EQ(validate_table(default_good_weather(), "conditions.good"), "");
  EXPECT_EQ(validate_table(default_bad_weather(), "conditions.bad"), "");
}

TEST(ConditionsDefaults, StarsAtNightNotByDay) {
  const ConditionTable good = default_good_weather(), bad = default_bad_weather();
  EXPECT_EQ(interpolate(good, 0.0f).star_visibility, 1.0f);
  EXPECT_GT(interpolate(good, 23.0f).star_visibility, 0.5f);
  for (float hour : {8.0f, 10.0f, 13.0f, 16.0f, 18.0f})
    EXPECT_LT(interpolate(good, hour).star_visibility, 0.01f) << hour;
  // Bad weather hides them all day.
  for (int i = 0; i < kKeyframeCount; ++i) EXPECT_EQ(bad.keys[i].set.star_visibility, 0.0f);
}

TEST(ConditionsDefaults, ClearDayIsBlueAndBright) {
  const ConditionSet day = default_good_weather().keys[kDay].set;
  EXPECT_GT(day.sky_zenith_rgb.b, 1.5f * day.sky_zenith_rgb.r);
  EXPECT_GT(day.sky_zenith_rgb.b, day.sky_zenith_rgb.g);
  // The documented scale: zenith about 1, sunlight about 20.
  EXPECT_NEAR(day.sky_zenith_rgb.b, 1.0f, 0.3f);
  EXPECT_NEAR(luminance(day.sun_light_rgb), 20.0f, 3.0f);
  // Night is dark blue and much darker than day.
  const ConditionSet night = default_good_weather().keys[kNight].set;
  EXPECT_GT(night.sky_zenith_rgb.b, night.sky_zenith_rgb.r);
  EXPECT_LT(luminance(night.sky_zenith_rgb), 0.05f * luminance(day.sky_zenith_rgb));
  EXPECT_EQ(night.sun_light_rgb, glm::vec3(0.0f));
  EXPECT_GT(luminance(night.moon_light_rgb), luminance(day.moon_light_rgb));
}

TEST(ConditionsDefaults, LowSunIsRedder) {
  const ConditionTable good = default_good_weather();
  auto red_over_blue = [](const glm::vec3& c) { return c.r / c.b; };
  const ConditionSet& day = good.keys[kDay].set;
  for (Key k : {kEarlyMorning, kEvening, kLateEvening}) {
    SCOPED_TRACE(keyframe_name(k));
    const ConditionSet& s = good.keys[k].set;
    EXPECT_GT(red_over_blue(s.sun_light_rgb), 2.0f * red_over_blue(day.sun_light_rgb));
    // Orange-red horizon: red well above blue.
    EXPECT_GT(s.sky_fog_rgb.r, 2.0f * s.sky_fog_rgb.b);
  }
  EXPECT_LT(day.sky_fog_rgb.r, day.sky_fog_rgb.b);
}

TEST(ConditionsDefaults, BadWeatherIsGreyerDarkerAndFoggier) {
  const ConditionTable good = default_good_weather(), bad = default_bad_weather();
  for (int i = 0; i < kKeyframeCount; ++i) {
    SCOPED_TRACE(keyframe_name(i));
    const ConditionSet &g = good.keys[i].set, &b = bad.keys[i].set;
    EXPECT_LT(luminance(b.sky_zenith_rgb), luminance(g.sky_zenith_rgb));
    EXPECT_LE(luminance(b.sun_light_rgb), luminance(g.sun_light_rgb));
    EXPECT_LE(luminance(b.moon_light_rgb), luminance(g.moon_light_rgb));
    EXPECT_LT(saturation(b.sky_zenith_rgb), saturation(g.sky_zenith_rgb));
    EXPECT_LT(b.fog_far_m, 0.5f * g.fog_far_m);
    EXPECT_LT(b.fog_near_m, g.fog_near_m);
  }
}

TEST(ConditionsDefaults, DiscsFogWithTheSkyFogColour) {
  for (const ConditionTable& t : {default_good_weather(), default_bad_weather()})
    for (int i = 0; i < kKeyframeCount; ++i)
      EXPECT_EQ(t.keys[i].set.disk_fog_rgb, t.keys[i].set.sky_fog_rgb) << keyframe_name(i);
}

TEST(ConditionsFog, LinearBetweenTheLimits) {
  ConditionSet s;
  s.sky_fog_start_deg = 0.0f;
  s.sky_fog_end_deg = 20.0f;
  s.disk_fog_start_deg = -2.0f;
  s.disk_fog_end_deg = 6.0f;
  s.fog_near_m = 1000.0f;
  s.fog_far_m = 5000.0f;
  EXPECT_EQ(sky_fog_factor(s, -10.0f), 1.0f);
  EXPECT_EQ(sky_fog_factor(s, 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(sky_fog_factor(s, 5.0f), 0.75f);
  EXPECT_FLOAT_EQ(sky_fog_factor(s, 10.0f), 0.5f);
  EXPECT_EQ(sky_fog_factor(s, 20.0f), 0.0f);
  EXPECT_EQ(sky_fog_factor(s, 90.0f), 0.0f);
  EXPECT_EQ(disk_fog_factor(s, -2.0f), 1.0f);
  EXPECT_FLOAT_EQ(disk_fog_factor(s, 0.0f), 0.75f);
  EXPECT_EQ(disk_fog_factor(s, 6.0f), 0.0f);
  EXPECT_EQ(object_fog_factor(s, 0.0f), 0.0f);
  EXPECT_EQ(object_fog_factor(s, 1000.0f), 0.0f);
  EXPECT_FLOAT_EQ(object_fog_factor(s, 2000.0f), 0.25f);
  EXPECT_EQ(object_fog_factor(s, 5000.0f), 1.0f);
  EXPECT_EQ(object_fog_factor(s, 1e9f), 1.0f);
  // A degenerate range is a step, not a division by zero.
  s.sky_fog_end_deg = 0.0f;
  EXPECT_EQ(sky_fog_factor(s, 0.0f), 1.0f);
  EXPECT_EQ(sky_fog_factor(s, 0.001f), 0.0f);
}

TEST(ConditionsSolarTime, LocalMeanSolarHour) {
  // JD 2451545.0 is 2000-01-01 12:00 UT (J2000.0).
  EXPECT_NEAR(local_solar_hour(2451545.0, 0.0), 12.0f, 1e-4f);
  EXPECT_NEAR(local_solar_hour(2451545.0, 90.0), 18.0f, 1e-4f);
  EXPECT_NEAR(local_solar_hour(2451545.0, -120.0), 4.0f, 1e-4f);
  EXPECT_NEAR(local_solar_hour(2451545.0, 180.0), 0.0f, 1e-4f);
  EXPECT_NEAR(local_solar_hour(2451545.0, 270.0), 6.0f, 1e-4f);  // longitudes up to 360
  // JD x.5 is midnight UT.
  EXPECT_NEAR(local_solar_hour(2451544.5, 0.0), 0.0f, 1e-4f);
  EXPECT_NEAR(local_solar_hour(2451544.5, -120.0), 16.0f, 1e-4f);
  EXPECT_NEAR(local_solar_hour(2451544.5, 15.0), 1.0f, 1e-4f);
  // Through the scene's date parser: Paris at 21:30 UT is 21:39:24 local mean time.
  const std::optional<double> jd = julian_day_from_iso8601("2026-06-24T21:30:00Z");
  ASSERT_TRUE(jd.has_value());
  EXPECT_NEAR(local_solar_hour(*jd, 2.35), 21.5f + 2.35f / 15.0f, 1e-4f);
  // Always in [0, 24), also a hair before midnight.
  for (double jd_ut : {2451544.5 - 1e-12, 2451544.5, 2460000.25, 2460000.75})
    for (double lon : {-180.0, -0.001, 0.0, 0.001, 179.999, 359.999}) {
      const float h = local_solar_hour(jd_ut, lon);
      EXPECT_GE(h, 0.0f);
      EXPECT_LT(h, 24.0f);
    }
}

TEST(ConditionsValidate, HoursMustIncreaseWithinTheDay) {
  ConditionTable t = default_good_weather();
  t.keys[kEvening].hour = 16.0f;  // before early evening (17)
  EXPECT_EQ(validate_table(t, "conditions.good"),
            "conditions.good.evening.hour = 16: must be > conditions.good.early_evening.hour "
            "(17): hours strictly increase");
  t = default_good_weather();
  t.keys[kEvening].hour = 17.0f;  // equal is not increasing
  EXPECT_NE(validate_table(t).find("conditions.evening.hour = 17"), std::string::npos);
  t = default_good_weather();
  t.keys[kLateEvening].hour = 24.0f;
  EXPECT_EQ(validate_table(t), "conditions.late_evening.hour = 24: must be in [0, 24)");
  t = default_good_weather();
  t.keys[kNight].hour = -1.0f;
  EXPECT_NE(validate_table(t).find("conditions.night.hour = -1"), std::string::npos);
  t = default_good_weather();
  t.keys[kDay].hour = NAN;
  EXPECT_NE(validate_table(t).find("conditions.day.hour"), std::string::npos);
}

TEST(ConditionsValidate, ColoursMustBeFiniteAndNonNegative) {
  ConditionTable t = default_bad_weather();
  t.keys[kDay].set.sky_zenith_rgb.g = -0.1f;
  EXPECT_EQ(validate_table(t, "conditions.bad"),
            "conditions.bad.day.sky_zenith_rgb = (0.3, -0.1, 0.34): every component must be in "
            "[0, 1e+06]");
  t = default_bad_weather();
  t.keys[kDay].set.sun_light_rgb.r = 1e9f;  // beyond any light the sky can have
  EXPECT_NE(validate_table(t).find("conditions.day.sun_light_rgb = (1e+09"), std::string::npos);
  t = default_bad_weather();
  t.keys[kMorning].set.ambient_rgb.r = INFINITY;
  EXPECT_NE(validate_table(t, "conditions.bad").find("conditions.bad.morning.ambient_rgb"),
            std::string::npos);
  t = default_bad_weather();
  t.keys[kNight].set.moon_light_rgb.b = NAN;
  EXPECT_NE(validate_table(t).find("conditions.night.moon_light_rgb"), std::string::npos);
}

TEST(ConditionsValidate, StarVisibilityAndFogLimits) {
  ConditionTable t = default_good_weather();
  t.keys[kNight].set.star_visibility = 1.5f;
  EXPECT_EQ(validate_table(t, "conditions.good"),
            "conditions.good.night.star_visibility = 1.5: must be in [0, 1]");
  t = default_good_weather();
  t.keys[kDay].set.fog_near_m = 90000.0f;
  EXPECT_EQ(validate_table(t, "conditions.good"),
            "conditions.good.day.fog_near_m = 90000: must be < conditions.good.day.fog_far_m "
            "(80000)");
  t = default_good_weather();
  t.keys[kDay].set.fog_near_m = -5.0f;
  EXPECT_NE(validate_table(t).find("conditions.day.fog_near_m = -5"), std::string::npos);
  t = default_good_weather();
  t.keys[kEvening].set.sky_fog_start_deg = 30.0f;
  EXPECT_EQ(validate_table(t),
            "conditions.evening.sky_fog_start_deg = 30: must be < "
            "conditions.evening.sky_fog_end_deg (25)");
  t = default_good_weather();
  t.keys[kEvening].set.disk_fog_end_deg = 91.0f;
  EXPECT_EQ(validate_table(t), "conditions.evening.disk_fog_end_deg = 91: must be in [-90, 90]");
}

// One message: the first bad field in key order.
TEST(ConditionsValidate, ReportsTheFirstProblemOnly) {
  ConditionTable t = default_good_weather();
  t.keys[kMorning].set.star_visibility = -1.0f;
  t.keys[kDay].set.sun_light_rgb.r = -1.0f;
  const std::string message = validate_table(t);
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_NE(message.find("conditions.morning.star_visibility = -1"), std::string::npos);
  EXPECT_EQ(message.find("sun_light_rgb"), std::string::npos);
}

}  // namespace
}  // namespace nephele

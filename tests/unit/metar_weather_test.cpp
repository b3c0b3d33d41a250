// From a weather report to the weather state and the scene (src/weather/metar_weather.h):
// layers by group, genus and height, the summation of their cover, the wind, the haze, the
// precipitation and the report's time on the scene's date.
#include "weather/metar_weather.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "nephele/error.h"
#include "nephele/scene_io.h"

namespace nephele::weather {
namespace {

ReportWeather weather_of(const std::string& report) {
  return weather_from_metar(parse_metar(report), weather_state(Scene{}));
}

std::string error_of(const std::string& toml) {
  try {
    parse_scene_toml(toml, "storm.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MetarWeather, GroupsBecomeLayersWhoseCoverSumsAsReported) {
  const ReportWeather w = weather_of("EDDF 271150Z 24015KT 9999 FEW025 SCT040 BKN080 12/06 Q1008");
  EXPECT_EQ(w.oktas_min, 5);  // BKN: the sky covered up to 8,000 ft
  EXPECT_EQ(w.oktas_max, 7);
  // Two volumetric layers: the two cumulus groups, whose clouds overlap, drawn as one.
  ASSERT_EQ(w.layers.size(), 2u);
  EXPECT_EQ(w.layers[0].groups, "FEW025 SCT040");
  EXPECT_EQ(w.layers[0].genus, Genus::Cumulus);  // 6 deg of spread: a convective base at 750 m
  EXPECT_NEAR(w.layers[0].cloud_base_m, 2500 * 0.3048f, 0.5f);
  EXPECT_EQ(w.layers[1].genus, Genus::Altocumulus);
  EXPECT_NEAR(w.layers[1].cloud_base_m, 8000 * 0.3048f, 0.5f);
  // The next layer covers what the low one leaves: 1 - (1 - 6/8) / (1 - 3.5/8) of the sky.
  EXPECT_NEAR(w.layers[0].own_oktas, 3.5f, 1e-5f);
  EXPECT_NEAR(w.layers[1].own_oktas, 8.0f * (1.0f - 0.25f / 0.5625f), 1e-4f);
  EXPECT_EQ(w.state.low.coverage_oktas, w.layers[0].own_oktas);
  // It is drawn by [[cloud_layers]], as the report gives it; high_clouds stays off.
  EXPECT_EQ(w.layers[0].slot, "clouds");
  EXPECT_EQ(w.layers[1].slot, "cloud_layers[0]");
  ASSERT_EQ(w.state.more.size(), 1u);
  EXPECT_EQ(w.state.more[0].coverage_oktas, w.layers[1].own_oktas);
  EXPECT_EQ(w.state.more[0].genus, Genus::Altocumulus);
  EXPECT_NEAR(w.state.more[0].base_m, 8000 * 0.3048f, 0.5f);
  EXPECT_EQ(w.state.high.coverage_oktas, 0.0f);
  // Where the clouds are: the low shell puts the cumulus' bases at 762 m and its tops at the
  // SCT040 group's (1219 m + 1200 m).
  const float cu = genus_type(Genus::Cumulus);
  const glm::vec2 low_clouds =
      clouds_in_shell_m(cu, coverage_for_oktas(w.state.low.coverage_oktas, cu),
                        {w.state.low.base_m, w.state.low.top_m});
  EXPECT_NEAR(low_clouds.x, 762.0f, 1.0f);
  EXPECT_NEAR(low_clouds.y, 4000 * 0.3048f + 1200.0f, 1.0f);
  EXPECT_LE(w.state.low.top_m, w.state.high.base_m);  // high_clouds, off, kept clear of it
  // From 240 deg: towards the north-east, 15 kt at 10 m and about twice it at 1 km.
  ASSERT_EQ(w.state.wind.size(), 2u);
  const glm::vec2 surface = w.state.wind[0].wind_mps;
  EXPECT_NEAR(surface.x, 15.0f * 0.514444f * std::sin(glm::radians(60.0f)), 1e-3f);
  EXPECT_NEAR(surface.y, 15.0f * 0.514444f * std::cos(glm::radians(60.0f)), 1e-3f);
  EXPECT_NEAR(glm::length(w.state.wind[1].wind_mps) / glm::length(surface), 1.93f, 0.01f);
  // 9999: ten kilometres or more; a clearer scene keeps its own.
  EXPECT_EQ(w.state.visibility_m, weather_state(Scene{}).visibility_m);
  EXPECT_EQ(w.state.precipitation, PrecipitationKind::None);
}

// Four groups whose clouds lie apart are four layers: the lowest drawn by clouds, the others
// by [[cloud_layers]] with the groups' bases, tops and own oktas; a scene holds them, valid,
// and writes and reads them back. Seven groups are drawn as five, the nearest merged.
TEST(MetarWeather, SeparateGroupsAreSeparateLayers) {
  const std::string report = "XXXX 011200Z 00000KT 9999 FEW008 SCT030 BKN080 BKN150 15/05 Q1013";
  const ReportWeather w = weather_of(report);
  ASSERT_EQ(w.layers.size(), 4u);
  const char* slots[] = {"clouds", "cloud_layers[0]", "cloud_layers[1]", "cloud_layers[2]"};
  const Genus genera[] = {Genus::Stratocumulus, Genus::Cumulus, Genus::Altocumulus,
                          Genus::Altocumulus};
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(w.layers[k].slot, slots[k]);
    EXPECT_EQ(w.layers[k].genus, genera[k]);
  }
  ASSERT_EQ(w.state.more.size(), 3u);
  EXPECT_NEAR(w.state.more[2].base_m, 15000 * 0.3048f, 0.5f);
  EXPECT_NEAR(w.state.more[2].top_m, 15000 * 0.3048f + 600.0f, 0.5f);
  // BKN080 brings the cover from 3.5 to 6 oktas; BKN150 adds nothing to 6.
  EXPECT_NEAR(w.state.more[1].coverage_oktas, 8.0f * (1.0f - 0.25f / 0.5625f), 1e-4f);
  EXPECT_EQ(w.state.more[2].coverage_oktas, 0.0f);
  Scene scene;
  scene.weather.metar = "METAR " + report;
  apply_metar(scene);
  ASSERT_EQ(scene.cloud_layers.size(), 3u);
  EXPECT_EQ(scene.cloud_layers[1].genus, "altocumulus");
  EXPECT_NEAR(scene.cloud_layers[1].base_m, 8000 * 0.3048f, 0.5f);
  EXPECT_NO_THROW(validate_scene(scene));
  Scene written = parse_scene_toml(scene_to_toml(scene), "written.toml");
  EXPECT_EQ(written.cloud_layers, scene.cloud_layers);

  const ReportWeather seven = weather_of(
      "XXXX 011200Z 00000KT 9999 FEW008 SCT030 SCT060 BKN080 BKN100 BKN150 BKN180 15/05 Q1013");
  EXPECT_EQ(seven.layers.size(), 5u);
  bool said = false;
  for (const std::string& note : seven.notes)
    said = said || note.find("5 volumetric layers at most") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(MetarWeather, GenusFromHeightCoverAndType) {
  // Stratus under 1,000 ft, stratocumulus in a closed low deck, altocumulus from 2 km, cirrus
  // from 6 km on the sheet.
  EXPECT_EQ(weather_of("XXXX 011200Z 00000KT 9999 OVC004 10/09 Q1013").layers[0].genus,
            Genus::Stratus);
  EXPECT_EQ(weather_of("XXXX 011200Z 00000KT 9999 BKN015 10/09 Q1013").layers[0].genus,
            Genus::Stratocumulus);
  EXPECT_EQ(weather_of("XXXX 011200Z 00000KT 9999 SCT100 10/00 Q1013").layers[0].genus,
            Genus::Altocumulus);
  const ReportWeather cirrus = weather_of("XXXX 011200Z 00000KT 9999 SCT250 10/00 Q1013");
  EXPECT_EQ(cirrus.layers[0].slot, "cirrus");
  EXPECT_EQ(cirrus.state.sheet.genus, Genus::Cirrus);
  EXPECT_NEAR(cirrus.state.sheet.base_m, 25000 * 0.3048f, 0.5f);
  EXPECT_EQ(cirrus.state.low.coverage_oktas, 0.0f);
  // A scattered low layer far below the convective base (25 deg of spread: 3 km) is no cumulus.
  EXPECT_EQ(weather_of("XXXX 011200Z 00000KT 9999 SCT008 30/05 Q1013").layers[0].genus,
            Genus::Stratocumulus);
  // A stratus fills a low part of its shell, a tenth of it: the shell is set so that its
  // clouds lie 400 ft and 400 m above.
  const ReportWeather stratus = weather_of("XXXX 011200Z 00000KT 9999 OVC004 10/09 Q1013");
  const glm::vec2 shell(stratus.state.low.base_m, stratus.state.low.top_m);
  EXPECT_GT(shell.y - shell.x, 2000.0f);
  const glm::vec2 st_clouds = clouds_in_shell_m(0.0f, 1.0f, shell);
  EXPECT_NEAR(st_clouds.x, 400 * 0.3048f, 1.0f);
  EXPECT_NEAR(st_clouds.y, 400 * 0.3048f + 400.0f, 1.0f);
  // TCU: a towering cumulus between cumulus and cumulonimbus.
  const ReportWeather tcu = weather_of("XXXX 011200Z 00000KT 9999 SCT030TCU 25/15 Q1013");
  EXPECT_EQ(tcu.layers[0].genus, Genus::Cumulus);
  EXPECT_GT(tcu.state.low.type, 0.8f);
  EXPECT_NEAR(tcu.layers[0].cloud_top_m - tcu.layers[0].cloud_base_m, 4000.0f, 1.0f);
}

TEST(MetarWeather, ThunderstormsRainSnowAndFog) {
  const ReportWeather storm =
      weather_of("WMKD 180700Z 33005KT 0300 +TSRA FEW000 FEW017CB SCT023 OVC140 25/23 Q1009");
  ASSERT_EQ(storm.layers.size(), 1u);  // the cumulonimbus spans the layers
  EXPECT_EQ(storm.layers[0].genus, Genus::Cumulonimbus);
  EXPECT_GE(storm.layers[0].cloud_top_m, 9000.0f);
  EXPECT_EQ(storm.state.storm_growth, 1.0f);  // +TS
  EXPECT_EQ(storm.state.lightning_per_min, 15.0f);  // a severe storm's flashes
  EXPECT_EQ(storm.state.precipitation, PrecipitationKind::Rain);
  EXPECT_GT(storm.state.precipitation_mm_per_h, 7.6f);   // heavy rain
  EXPECT_EQ(storm.state.visibility_m, kMinVisibilityM);  // 300 m: the haze's least
  EXPECT_EQ(storm.oktas_min, 8);
  const ReportWeather snow = weather_of("ESSA 180750Z 17009KT 4000 -SN BKN004 00/00 Q0995");
  EXPECT_EQ(snow.state.precipitation, PrecipitationKind::Snow);
  EXPECT_LT(snow.state.precipitation_mm_per_h, 1.0f);
  EXPECT_EQ(snow.state.lightning_per_min, 0.0f);  // no thunder, no lightning
  EXPECT_EQ(
      weather_of("KMIA 180750Z 09010KT 5SM TSRA BKN020CB 27/24 A2990").state.lightning_per_min,
      6.0f);
  EXPECT_EQ(snow.state.visibility_m, 4000.0f);
  // Drizzle, sleet (rain and snow together, or ice pellets), showers of heavy rain.
  EXPECT_EQ(weather_of("EGLL 180750Z 22011KT 3000 -DZ OVC004 09/09 Q1012").state.precipitation,
            PrecipitationKind::Drizzle);
  EXPECT_EQ(weather_of("CYUL 180750Z 05012KT 2SM -RASN OVC010 01/00 A2990").state.precipitation,
            PrecipitationKind::Sleet);
  EXPECT_EQ(weather_of("CYUL 180750Z 05012KT 2SM PL OVC010 M01/M02 A2990").state.precipitation,
            PrecipitationKind::Sleet);
  const ReportWeather showers =
      weather_of("LFPG 180750Z 27015KT 4000 +SHRA SCT020CB BKN030 14/11 Q1002");
  EXPECT_EQ(showers.state.precipitation, PrecipitationKind::Rain);
  EXPECT_EQ(showers.state.precipitation_mm_per_h, 16.0f);
  // Showers in the vicinity are not here.
  EXPECT_EQ(weather_of("ENBR 180750Z 22011KT 9999 VCSH FEW018 06/04 Q0988").state.precipitation,
            PrecipitationKind::None);
  // An obscured sky is a closed deck at its vertical visibility.
  const ReportWeather fog = weather_of("KLAX 281253Z 24005KT 1/8SM FG VV002 17/16 A2998");
  EXPECT_EQ(fog.layers[0].groups, "VV");
  EXPECT_NEAR(fog.layers[0].cloud_base_m, 200 * 0.3048f, 0.5f);
  EXPECT_EQ(fog.oktas_min, 8);
  EXPECT_EQ(fog.layers[0].own_oktas, 8.0f);
}

TEST(MetarWeather, TheReportsTimeIsSetOnTheScenesDate) {
  const MetarReport r = parse_metar("EDDF 271150Z 24015KT 9999 12/06 Q1008");
  EXPECT_EQ(report_time(r, "2026-11-01T00:00:00Z"), "2026-11-27T11:50:00Z");
  EXPECT_EQ(report_time(r, "2026-02-03T23:00:00+02:00"), "2026-02-27T11:50:00Z");
  try {
    report_time(parse_metar("EDDF 311150Z 24015KT 9999 12/06 Q1008"), "2026-11-05T00:00:00Z");
    ADD_FAILURE() << "day 31 of November accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "weather.metar: day 31 of the report: 2026-11 (the scene's month) has 30 days");
  }
  EXPECT_THROW(report_time(r, ""), InputError);
}

TEST(MetarWeather, ASceneFileTakesTheReportOverItsKeys) {
  const Scene scene = parse_scene_toml(
      "time = \"2026-06-02T00:00:00Z\"\n"
      "[clouds]\ncoverage = 0.9\n"
      "[weather]\nmetar = \"LFPG 021030Z 18008KT CAVOK 21/11 Q1021\"\n",
      "cavok.toml");
  validate_scene(scene);
  EXPECT_EQ(scene.clouds.coverage, 0.0f);  // CAVOK: no cloud, whatever [clouds] said
  EXPECT_EQ(scene.time, "2026-06-02T10:30:00Z");
  EXPECT_NEAR(scene.clouds.wind_mps.y, 8.0f * 0.514444f * 1.93f, 0.05f);  // from the south
  // Loading the scene it writes gives it again.
  EXPECT_EQ(scene_to_toml(parse_scene_toml(scene_to_toml(scene), "again.toml")),
            scene_to_toml(scene));
  EXPECT_EQ(error_of("[weather]\nmetar = \"EDDF 271150Z 24O15KT 9999 12/06 Q1008\"\n"),
            "storm.toml:2:9: weather.metar: metar: group 3 \"24O15KT\": expected AUTO or COR, "
            "or a later group: the wind (dddffKT, dddffGggKT, VRBffKT, in KT, MPS or KMH)");
}

}  // namespace
}  // namespace nephele::weather

// METAR and SPECI parsing (src/weather/metar.h): hand-decoded reports, the corpus of real
// reports with their expected fields (tests/data/metar_reports.json), and malformed reports.
#include "weather/metar.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "nephele/error.h"

using nephele::InputError;
using nephele::weather::MetarCloud;
using nephele::weather::MetarReport;
using nephele::weather::MetarVisibility;
using nephele::weather::MetarWeather;
using nephele::weather::MetarWind;
using nephele::weather::parse_metar;

TEST(Metar, TheIssuesReportDecodesGroupByGroup) {
  const MetarReport r =
      parse_metar("METAR EDDF 271150Z 24015KT 9999 FEW025 SCT040 BKN080 12/06 Q1008");
  EXPECT_FALSE(r.speci);
  EXPECT_EQ(r.station, "EDDF");
  EXPECT_EQ(r.day, 27);
  EXPECT_EQ(r.hour, 11);
  EXPECT_EQ(r.minute, 50);
  ASSERT_TRUE(r.wind);
  EXPECT_EQ(r.wind->direction_deg, 240);
  EXPECT_EQ(r.wind->speed, 15.0f);
  EXPECT_NEAR(r.wind->speed_mps(), 7.72f, 0.01f);
  ASSERT_TRUE(r.visibility);
  EXPECT_TRUE(r.visibility->at_least);
  EXPECT_EQ(r.visibility->distance_m, 10000.0f);
  ASSERT_EQ(r.clouds.size(), 3u);
  EXPECT_EQ(r.clouds[0].cover, "FEW");
  EXPECT_EQ(*r.clouds[0].base_ft, 2500);
  EXPECT_EQ(r.clouds[2].cover, "BKN");
  EXPECT_EQ(*r.clouds[2].base_ft, 8000);
  EXPECT_EQ(*r.temperature_c, 12.0f);
  EXPECT_EQ(*r.dew_point_c, 6.0f);
  EXPECT_EQ(*r.qnh_hpa, 1008.0f);
}

TEST(Metar, UsReportWithMilesGustsWeatherAndRemarks) {
  const MetarReport r = parse_metar(
      "SPECI KJFK 041751Z 31018G29KT 1 1/2SM -TSRA BR FEW008 BKN025CB OVC050 M02/M05 A2992 RMK AO2 "
      "PK WND 30035/1722 SLP132 T10221050=");
  EXPECT_TRUE(r.speci);
  EXPECT_EQ(*r.wind->gust, 29.0f);
  EXPECT_NEAR(r.visibility->distance_m, 1.5f * 1609.344f, 0.1f);
  EXPECT_TRUE(r.visibility->statute_miles);
  ASSERT_EQ(r.weather.size(), 2u);
  EXPECT_EQ(r.weather[0].intensity, "-");
  EXPECT_EQ(r.weather[0].descriptor, "TS");
  EXPECT_TRUE(r.weather[0].has("RA"));
  EXPECT_TRUE(r.weather[1].has("BR"));
  EXPECT_EQ(r.clouds[1].type, "CB");
  EXPECT_EQ(*r.temperature_c, -2.0f);
  EXPECT_EQ(*r.dew_point_c, -5.0f);
  EXPECT_NEAR(r.pressure_hpa(), 1013.2f, 0.1f);  // 29.92 inHg
  EXPECT_EQ(r.remarks, "AO2 PK WND 30035/1722 SLP132 T10221050");
}

TEST(Metar, CavokVerticalVisibilityTrendsAndSupplementaryGroups) {
  MetarReport r = parse_metar("LFPG 121030Z AUTO VRB02KT CAVOK 21/11 Q1021 NOSIG");
  EXPECT_TRUE(r.automatic);
  EXPECT_TRUE(r.wind->variable);
  EXPECT_TRUE(r.visibility->cavok);
  EXPECT_EQ(r.trends, std::vector<std::string>{"NOSIG"});
  r = parse_metar(
      "METAR COR UUEE 030600Z 18004MPS 150V220 0350 R24L/0550U R24R/P2000 FZFG VV002 M08/M09 "
      "Q1030 R24L/290050 BECMG FM0700 1500 BR TEMPO 0200 FG RMK QFE752");
  EXPECT_TRUE(r.corrected);
  EXPECT_EQ(r.wind->unit, "MPS");
  EXPECT_EQ(r.wind->speed_mps(), 4.0f);
  EXPECT_EQ(*r.wind->varies_from_deg, 150);
  EXPECT_EQ(r.visibility->distance_m, 350.0f);
  EXPECT_EQ(r.runway_visual_range.size(), 2u);
  EXPECT_EQ(r.weather[0].descriptor, "FZ");
  EXPECT_TRUE(r.sky_obscured);
  EXPECT_EQ(*r.vertical_visibility_ft, 200);
  EXPECT_EQ(r.supplementary, std::vector<std::string>{"R24L/290050"});
  ASSERT_EQ(r.trends.size(), 2u);
  EXPECT_EQ(r.trends[0], "BECMG FM0700 1500 BR");
  EXPECT_EQ(r.trends[1], "TEMPO 0200 FG");
  EXPECT_EQ(r.remarks, "QFE752");
  r = parse_metar("EGLL 010920Z 27010KT 9999 -RA SCT012 ///CB 14/12 Q0998 RERA WS R27L TEMPO SHRA");
  EXPECT_EQ(r.recent_weather.size(), 1u);
  EXPECT_TRUE(r.recent_weather[0].has("RA"));
  EXPECT_EQ(r.wind_shear, std::vector<std::string>{"WS R27L"});
  EXPECT_EQ(r.clouds[1].cover, "///");
  EXPECT_FALSE(r.clouds[1].base_ft);
  EXPECT_EQ(r.clouds[1].type, "CB");
  r = parse_metar("KSEA 201653Z 00000KT 10SM CLR 08/M01 A3031");
  EXPECT_EQ(r.no_cloud, "CLR");
  EXPECT_EQ(r.wind->speed, 0.0f);
  r = parse_metar("ZBAA 150300Z /////KT //// // ////// ///// Q////");
  EXPECT_TRUE(r.wind->missing);
  EXPECT_TRUE(r.visibility->missing);
  EXPECT_FALSE(r.temperature_c);
  EXPECT_FALSE(r.qnh_hpa);
  EXPECT_TRUE(parse_metar("METAR LOWW 010950Z NIL=").nil);
}

// A malformed report: one line naming the group and what may stand there.
TEST(Metar, MalformedReportsNameTheGroup) {
  const auto message = [](const std::string& text) {
    try {
      parse_metar(text);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(message("EDDF 271150Z 24O15KT 9999 FEW025 12/06 Q1008"),
            "metar: group 3 \"24O15KT\": expected AUTO or COR, or a later group: the wind "
            "(dddffKT, dddffGggKT, VRBffKT, in KT, MPS or KMH)");
  EXPECT_NE(message("EDDF 2711Z 24015KT").find("group 2 \"2711Z\": expected the day and time"),
            std::string::npos);
  EXPECT_NE(message("EDDF 321150Z 24015KT").find("a day of 01-31"), std::string::npos);
  EXPECT_NE(message("E1 271150Z").find("group 1 \"E1\": expected the station"), std::string::npos);
  EXPECT_NE(message("EDDF 271150Z 24015KT 9999 FEW25 12/06 Q1008").find("group 5 \"FEW25\""),
            std::string::npos);
  EXPECT_NE(message("EDDF 271150Z 24015KT 9999 FEW025 12/06 Q1008 FEW030")
                .find("group 8 \"FEW030\": expected the pressure"),
            std::string::npos);
  EXPECT_NE(message("EDDF 271150Z 24015KT 9999 12/06 Q1008= EDDM 271150Z").find("more than one"),
            std::string::npos);
  EXPECT_NE(message("").find("empty"), std::string::npos);
  EXPECT_NE(message("EDDF").find("ends after 1 groups"), std::string::npos);
  EXPECT_NE(message("EDDF 271150Z 45015KT").find("at most 360"), std::string::npos);
  EXPECT_NE(message("EDDF 271150Z NIL 24015KT").find("nothing after NIL"), std::string::npos);
  EXPECT_NE(message("EDDF 271150Z 24015KT 9999 12/06 Q1008 WS").find("a runway after WS"),
            std::string::npos);
}

namespace {
// The fields of a report as the corpus states them (tests/data/metar_reports.json).
nlohmann::json expect_fields(const MetarReport& r) {
  nlohmann::json e;
  e["kind"] = r.speci ? "SPECI" : "METAR";
  e["station"] = r.station;
  char t[16];
  std::snprintf(t, sizeof(t), "%02d%02d%02dZ", r.day, r.hour, r.minute);
  e["time"] = t;
  if (r.automatic) e["auto"] = true;
  if (r.corrected) e["cor"] = true;
  if (r.nil) {
    e["nil"] = true;
    return e;
  }
  if (r.wind) {
    const MetarWind& w = *r.wind;
    std::string s;
    if (w.missing)
      s = "missing";
    else {
      char b[64];
      std::snprintf(b, sizeof(b), "%s %g%s",
                    w.variable ? "VRB" : std::to_string(w.direction_deg).c_str(), w.speed,
                    w.above ? "+" : "");
      s = b;
      if (w.gust) {
        std::snprintf(b, sizeof(b), " G%g", *w.gust);
        s += b;
      }
      s += " " + w.unit;
      if (w.varies_from_deg)
        s += " " + std::to_string(*w.varies_from_deg) + "V" + std::to_string(*w.varies_to_deg);
    }
    e["wind"] = s;
  }
  if (r.visibility) {
    const MetarVisibility& v = *r.visibility;
    if (v.cavok)
      e["visibility"] = "CAVOK";
    else if (v.missing)
      e["visibility"] = "missing";
    else {
      char b[64];
      std::snprintf(b, sizeof(b), "%s%.0f m%s", v.less_than ? "<" : "", v.distance_m,
                    v.at_least ? "+" : "");
      std::string s = b;
      if (v.minimum_m) {
        std::snprintf(b, sizeof(b), " min %.0f m%s%s", *v.minimum_m,
                      v.minimum_direction.empty() ? "" : " ", v.minimum_direction.c_str());
        s += b;
      }
      e["visibility"] = s;
    }
  }
  if (!r.runway_visual_range.empty()) e["rvr"] = r.runway_visual_range.size();
  nlohmann::json wx = nlohmann::json::array();
  for (const MetarWeather& w : r.weather) {
    std::string s = w.intensity + w.descriptor;
    for (auto& p : w.phenomena) s += p;
    if (w.text == "//") s = "//";
    wx.push_back(s);
  }
  if (!wx.empty()) e["weather"] = wx;
  nlohmann::json cl = nlohmann::json::array();
  for (const MetarCloud& c : r.clouds)
    cl.push_back(c.cover + " " +
                 (c.base_ft ? std::to_string(*c.base_ft) + " ft" : std::string("///")) +
                 (c.type.empty() ? "" : " " + c.type));
  if (!cl.empty()) e["clouds"] = cl;
  if (r.sky_obscured)
    e["vertical_visibility_ft"] = r.vertical_visibility_ft
                                      ? nlohmann::json(*r.vertical_visibility_ft)
                                      : nlohmann::json("///");
  if (!r.no_cloud.empty()) e["no_cloud"] = r.no_cloud;
  if (r.temperature_c) e["temperature_c"] = *r.temperature_c;
  if (r.dew_point_c) e["dew_point_c"] = *r.dew_point_c;
  if (r.qnh_hpa) e["qnh_hpa"] = *r.qnh_hpa;
  if (r.altimeter_inhg) e["altimeter_inhg"] = std::round(*r.altimeter_inhg * 100.0) / 100.0;
  if (!r.recent_weather.empty()) {
    nlohmann::json a = nlohmann::json::array();
    for (auto& w : r.recent_weather) a.push_back(w.text);
    e["recent"] = a;
  }
  if (!r.wind_shear.empty()) e["wind_shear"] = r.wind_shear;
  if (!r.supplementary.empty()) e["supplementary"] = r.supplementary;
  if (!r.trends.empty()) e["trends"] = r.trends;
  if (!r.remarks.empty()) e["remarks"] = r.remarks;
  return e;
}
}  // namespace

// The corpus: every real report's fields exactly as expected, and the malformed ones refused
// naming the group.
TEST(Metar, RealReportsFromEveryContinentParseExactly) {
  std::ifstream file(NEPHELE_SOURCE_DIR "/tests/data/metar_reports.json");
  ASSERT_TRUE(file) << "tests/data/metar_reports.json";
  const nlohmann::json corpus = nlohmann::json::parse(file);
  std::map<std::string, int> continents;
  int parsed = 0, refused = 0;
  for (const nlohmann::json& entry : corpus) {
    const std::string raw = entry["raw"];
    ASSERT_FALSE(entry["source"].get<std::string>().empty()) << raw;
    if (entry.contains("error")) {
      try {
        parse_metar(raw);
        ADD_FAILURE() << "accepted a malformed report: " << raw;
      } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).find("metar: " + entry["error"].get<std::string>() +
                                             ": expected"),
                  0u)
            << raw << "\n"
            << e.what();
      }
      ++refused;
      continue;
    }
    MetarReport r;
    try {
      r = parse_metar(raw);
    } catch (const InputError& e) {
      ADD_FAILURE() << raw << "\n" << e.what();
      continue;
    }
    EXPECT_EQ(expect_fields(r), entry["expect"]) << raw << "\ngot " << expect_fields(r).dump();
    ++continents[entry["continent"]];
    ++parsed;
  }
  EXPECT_GE(parsed, 60);
  EXPECT_EQ(refused, 5);
  EXPECT_GE(continents.size(), 5u);
  for (const char* c : {"Europe", "North America", "South America", "Asia", "Africa", "Oceania"})
    EXPECT_GE(continents[c], 5) << c;
}

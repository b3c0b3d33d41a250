// nephele — METAR and SPECI, the WMO's aerodrome weather reports (FM 15 and FM 16, Manual on
// Codes WMO-No. 306, with the common ICAO Annex 3 and US FMH-1 variants), read into their
// groups. The observation's groups are decoded; runway visual range, runway state, sea state
// and remarks are recognised and kept as text; recent weather, wind shear and the trend
// (NOSIG, BECMG, TEMPO) are kept apart from the observation. A group that fits none of the
// groups that may stand where it stands is refused, naming it.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace nephele::weather {

struct MetarWind {
  bool missing = false;   // "/////KT"
  bool variable = false;  // "VRB"
  int direction_deg = 0;  // where it blows from, true north (0 with a calm or VRB)
  float speed = 0.0f;     // in `unit`
  std::optional<float> gust;
  std::string unit = "KT";  // KT, MPS or KMH
  bool above = false;       // "P99": more than the speed given
  // A direction varying over 60 deg or more ("180V240"): from, to (deg).
  std::optional<int> varies_from_deg, varies_to_deg;
  float speed_mps() const;
  std::optional<float> gust_mps() const;
};

struct MetarVisibility {
  bool missing = false;            // "////"
  bool cavok = false;              // ceiling and visibility OK: 10 km or more, no cloud below
                                   // 5,000 ft, no CB or TCU, no significant weather
  float distance_m = 0.0f;         // prevailing (9999: 10 km or more)
  bool less_than = false;          // "M1/4SM"
  bool at_least = false;           // "9999" (10 km or more), "P6SM" (more than 6 miles)
  bool statute_miles = false;      // given in SM
  bool no_directional = false;     // "NDV" (automatic stations)
  std::optional<float> minimum_m;  // "1500SW": the lowest, in some direction
  std::string minimum_direction;
};

// Present or recent weather: "+SHRA", "VCTS", "FZFG", "-DZ", "//" (not observed).
struct MetarWeather {
  std::string intensity;   // "-", "+", "" (moderate) or "VC" (in the vicinity)
  std::string descriptor;  // MI PR BC DR BL SH TS FZ, or ""
  std::vector<std::string>
      phenomena;     // DZ RA SN SG IC PL GR GS UP BR FG FU VA DU SA HZ PO SQ FC SS DS
  std::string text;  // the group as written
  bool has(std::string_view phenomenon) const;
};

struct MetarCloud {
  std::string cover;           // FEW SCT BKN OVC, or "///" (not observed)
  std::optional<int> base_ft;  // above the aerodrome; none: "///"
  std::string type;            // "CB", "TCU", "///" (not observed) or ""
};

struct MetarReport {
  bool speci = false;
  std::string station;                // ICAO
  int day = 0, hour = 0, minute = 0;  // of the month, UTC
  bool automatic = false;             // AUTO
  bool corrected = false;             // COR
  bool nil = false;                   // NIL: no report
  std::optional<MetarWind> wind;
  std::optional<MetarVisibility> visibility;
  std::vector<std::string> runway_visual_range;  // R27L/0600N, as written
  std::vector<MetarWeather> weather;
  std::vector<MetarCloud> clouds;
  // VV: the sky obscured, vertical visibility (ft); VV///: obscured, not measured.
  bool sky_obscured = false;
  std::optional<int> vertical_visibility_ft;
  std::string no_cloud;  // NSC, NCD, SKC or CLR; "" otherwise (CAVOK says it in visibility)
  std::optional<float> temperature_c, dew_point_c;
  std::optional<float> qnh_hpa;              // Q1013
  std::optional<float> altimeter_inhg;       // A2992
  std::vector<MetarWeather> recent_weather;  // RERA
  std::vector<std::string> wind_shear;       // "WS R27", "WS ALL RWY"
  std::vector<std::string> supplementary;  // runway state (R24/190095), sea (W15/S3), colour state
  std::vector<std::string> trends;         // "NOSIG", "BECMG FM1200 25020KT", "TEMPO 4000 TSRA"
  std::string remarks;                     // after RMK, as written

  float pressure_hpa() const;  // QNH, or the altimeter setting in hPa; 1013.25 when neither
};

// Parses one report: an optional "METAR" or "SPECI", the station, the day and time, and the
// groups after them; a trailing "=" ends it. Throws InputError naming the group and what may
// stand there: 'metar: group 5 "24O15KT": expected the wind (dddffKT, dddffGggMPS, VRBffKT,
// 00000KT, /////KT) or the visibility'.
MetarReport parse_metar(std::string_view text);

// The report's kind, station and groups as one line a person reads ("EDDF 27 11:50Z, wind
// 240 deg 15 kt, visibility 10 km or more, FEW 2500 ft, ..."), for --verbose.
std::string describe(const MetarReport& report);

}  // namespace nephele::weather

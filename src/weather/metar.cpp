// nephele — METAR and SPECI reports read into their groups (metar.h).
#include "weather/metar.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <regex>
#include <sstream>

#include "nephele/error.h"

namespace nephele::weather {
namespace {

constexpr float kKnotMps = 0.514444f;
constexpr float kStatuteMileM = 1609.344f;
constexpr float kInchHgHpa = 33.8639f;

bool matches(const std::string& token, const std::regex& re, std::smatch& m) {
  return std::regex_match(token, m, re);
}

bool matches(const std::string& token, const std::regex& re) {
  return std::regex_match(token, re);
}

// "M05" -> -5, "12" -> 12.
float signed_temperature(const std::string& text) {
  const float value = std::stof(text[0] == 'M' ? text.substr(1) : text);
  return text[0] == 'M' && value > 0.0f ? -value : value;  // M00: just below 0, shown as 0
}

const std::regex kStation("[A-Z][A-Z0-9]{3}");
const std::regex kTime("(\\d{2})(\\d{2})(\\d{2})Z");
const std::regex kWind("(\\d{3}|VRB|///)(P?\\d{2,3}|//)(?:G(P?\\d{2,3}))?(KT|MPS|KMH)");
const std::regex kWindVaries("(\\d{3})V(\\d{3})");
const std::regex kVisibilityM("(\\d{4})(NDV)?");
const std::regex kVisibilityMinimum("(\\d{4})(N|NE|E|SE|S|SW|W|NW)");
const std::regex kVisibilityKm("(\\d{1,2})KM");
const std::regex kVisibilitySm("([MP])?(\\d{1,2})SM");
const std::regex kVisibilitySmFraction("([MP])?(\\d)/(\\d{1,2})SM");
const std::regex kWholeMiles("\\d");
const std::regex kRvr("R\\d{2}[LCR]?/(?:[PM]?\\d{4}(?:V[PM]?\\d{4})?(?:FT)?(?:/?[UDN])?|/{4,})");
const std::regex kWeather(
    "(-|\\+|VC)?(MI|PR|BC|DR|BL|SH|TS|FZ)?((?:DZ|RA|SN|SG|IC|PL|GR|GS|UP|BR|FG|FU|VA|DU|SA|HZ|"
    "PY|PO|SQ|FC|SS|DS)*)");
// "///CB": an automatic station's CB or TCU whose cover and base it cannot tell. Some
// national variants name every layer's genus (FEW025SC, BKN090AC).
const std::regex kCloud(
    "(FEW|SCT|BKN|OVC|///)(\\d{3}|///)?(CB|TCU|///|CU|SC|ST|NS|AS|AC|CI|CS|CC)?");
const std::regex kVerticalVisibility("VV(\\d{3}|///)");
const std::regex kTemperature("(M?\\d{2}|//|XX)/(M?\\d{2}|//|XX)?");
const std::regex kPressure("([QA])(\\d{4}|////)");
// Runway state (EUR: R24/190095, R88/CLRD70, R24/SNOCLO, and without the R of the older
// form: 88CLRD95, 24190095), sea state (W15/S3, W12/H14), the sea-level pressure some
// stations add (QFF1011), Australia's rainfall (RF00.2/001.4) and the military colour states.
const std::regex kRunwayState(
    "R\\d{2}[LCR]?/[A-Z0-9/]+|R/SNOCLO|SNOCLO|\\d{2}(?:[0-9/]{6}|CLRD[0-9/]{2})");
const std::regex kOtherSupplementary("QFF\\d{4}|RF\\d{2}\\.\\d/\\d{3}\\.\\d");
const std::regex kSea("W(?:M?\\d{2}|//)/(?:S[0-9/]|H[0-9/]{1,3})");
const std::regex kColour("(?:BLACK)?(?:BLU|WHT|GRN|YLO1|YLO2|YLO|AMB|RED)\\+?");
const std::regex kTrendFrom("FM\\d{4}");
const std::regex kWindShearRunway("(R|RWY)\\d{2}[LCR]?");
const std::regex kCorrection("CC[A-Z]");

// A weather group's code ("+SHRA"; recent weather's after its RE, which takes no intensity)
// as written in `text`; none when it is not one. A descriptor alone is present weather only
// as TS (a thunderstorm) or, in the vicinity, SH.
std::optional<MetarWeather> weather_group(const std::string& code, const std::string& text,
                                          bool recent) {
  std::smatch m;
  if (!std::regex_match(code, m, kWeather) || (!m[2].matched && m[3].length() == 0))
    return std::nullopt;
  if (recent ? m[1].matched : m[3].length() == 0 && m[2] != "TS" && !(m[1] == "VC" && m[2] == "SH"))
    return std::nullopt;
  MetarWeather w{m[1], m[2], {}, text};
  const std::string p = m[3];
  for (size_t k = 0; k < p.size(); k += 2) w.phenomena.push_back(p.substr(k, 2));
  return w;
}

// A speed in `unit` (KT, MPS or KMH) in m/s.
float to_mps(float speed, const std::string& unit) {
  return to_mps(speed, unit);
}

// NOSIG, BECMG and TEMPO; Australia's trend forecast also begins with INTER, or with FMhhmm
// where no trend has begun (within BECMG or TEMPO, FMhhmm is the change's time).
bool is_trend_start(const std::string& t, bool in_trend) {
  return t == "NOSIG" || t == "BECMG" || t == "TEMPO" || t == "INTER" ||
         (!in_trend && std::regex_match(t, kTrendFrom));
}

struct Parser {
  std::vector<std::string> tokens;
  size_t i = 0;
  MetarReport r;

  const std::string& token() const { return tokens[i]; }
  bool more() const { return i < tokens.size(); }

  [[noreturn]] void fail(const std::string& expected) const {
    throw InputError("metar: group " + std::to_string(i + 1) + " \"" +
                     shorten_for_message(more() ? token() : std::string()) + "\": expected " +
                     expected);
  }
  [[noreturn]] void fail_end(const std::string& expected) const {
    throw InputError("metar: the report ends after " + std::to_string(tokens.size()) +
                     " groups: expected " + expected);
  }

  bool wind() {
    std::smatch m;
    if (!matches(token(), kWind, m)) return false;
    MetarWind w;
    w.unit = m[4];
    if (m[1] == "///" || m[2] == "//") {
      w.missing = true;
    } else {
      w.variable = m[1] == "VRB";
      if (!w.variable) w.direction_deg = std::stoi(m[1]);
      std::string speed = m[2];
      if (speed[0] == 'P') {
        w.above = true;
        speed = speed.substr(1);
      }
      w.speed = std::stof(speed);
      if (m[3].matched) {
        std::string gust = m[3];
        if (gust[0] == 'P') gust = gust.substr(1);
        w.gust = std::stof(gust);
      }
      if (w.direction_deg > 360) fail("a wind direction of at most 360 deg in \"" + token() + "\"");
    }
    ++i;
    if (more() && matches(token(), kWindVaries, m)) {
      w.varies_from_deg = std::stoi(m[1]);
      w.varies_to_deg = std::stoi(m[2]);
      if (*w.varies_from_deg > 360 || *w.varies_to_deg > 360)
        fail("directions of at most 360 deg (dddVddd)");
      ++i;
    }
    r.wind = w;
    return true;
  }

  bool visibility() {
    std::smatch m;
    MetarVisibility v;
    const std::string& t = token();
    if (t == "CAVOK") {
      v.cavok = true;
      v.distance_m = 10000.0f;
      v.at_least = true;
      ++i;
    } else if (t == "////") {
      v.missing = true;
      ++i;
    } else if (matches(t, kVisibilityM, m)) {
      v.distance_m = std::stof(m[1]);
      if (v.distance_m >= 9999.0f) {
        v.distance_m = 10000.0f;
        v.at_least = true;
      }
      v.no_directional = m[2].matched;
      ++i;
      if (more() && matches(token(), kVisibilityMinimum, m)) {
        v.minimum_m = std::stof(m[1]);
        v.minimum_direction = m[2];
        ++i;
      } else if (more() && matches(token(), kVisibilityM, m) && !m[2].matched &&
                 std::stof(m[1]) < v.distance_m) {  // a minimum without its direction
        v.minimum_m = std::stof(m[1]);
        ++i;
      }
    } else if (matches(t, kVisibilityKm, m)) {
      v.distance_m = std::stof(m[1]) * 1000.0f;
      ++i;
    } else if (matches(t, kVisibilitySm, m)) {
      v.statute_miles = true;
      v.distance_m = std::stof(m[2]) * kStatuteMileM;
      v.less_than = m[1] == "M";
      v.at_least = m[1] == "P";
      ++i;
    } else if (matches(t, kVisibilitySmFraction, m)) {
      v.statute_miles = true;
      v.distance_m = std::stof(m[2]) / std::stof(m[3]) * kStatuteMileM;
      v.less_than = m[1] == "M";
      v.at_least = m[1] == "P";
      ++i;
    } else if (matches(t, kWholeMiles) && i + 1 < tokens.size() &&
               matches(tokens[i + 1], kVisibilitySmFraction, m) && !m[1].matched) {
      v.statute_miles = true;
      v.distance_m = (std::stof(t) + std::stof(m[2]) / std::stof(m[3])) * kStatuteMileM;
      i += 2;
    } else {
      return false;
    }
    r.visibility = v;
    return true;
  }

  bool runway_visual_range() {
    if (!matches(token(), kRvr)) return false;
    r.runway_visual_range.push_back(token());
    ++i;
    return true;
  }

  bool present_weather() {
    const std::string& t = token();
    if (t == "//") {
      r.weather.push_back({"", "", {}, t});
      ++i;
      return true;
    }
    const std::optional<MetarWeather> w = weather_group(t, t, false);
    if (!w) return false;
    r.weather.push_back(*w);
    ++i;
    return true;
  }

  bool clouds() {
    std::smatch m;
    const std::string& t = token();
    if (t == "NSC" || t == "NCD" || t == "SKC" || t == "CLR") {
      r.no_cloud = t;
      ++i;
      return true;
    }
    if (matches(t, kVerticalVisibility, m)) {
      r.sky_obscured = true;
      if (m[1] != "///") r.vertical_visibility_ft = std::stoi(m[1]) * 100;
      ++i;
      return true;
    }
    if (!matches(t, kCloud, m) || (!m[2].matched && (m[1] != "///" || !m[3].matched))) return false;
    MetarCloud c{m[1], std::nullopt, m[3].matched ? std::string(m[3]) : std::string()};
    if (m[2].matched && m[2] != "///") c.base_ft = std::stoi(m[2]) * 100;
    r.clouds.push_back(c);
    ++i;
    return true;
  }

  bool temperature() {
    std::smatch m;
    if (!matches(token(), kTemperature, m)) return false;
    const std::string t = m[1], d = m[2];
    if (t != "//" && t != "XX") r.temperature_c = signed_temperature(t);
    if (m[2].matched && d != "//" && d != "XX") r.dew_point_c = signed_temperature(d);
    ++i;
    return true;
  }

  bool pressure() {
    std::smatch m;
    if (!matches(token(), kPressure, m)) return false;
    if (m[2] != "////") {
      const float value = std::stof(m[2]);
      if (m[1] == "Q")
        r.qnh_hpa = value;
      else
        r.altimeter_inhg = value / 100.0f;
    }
    ++i;
    return true;
  }

  bool supplementary() {
    const std::string& t = token();
    if (t.starts_with("RE") && t.size() > 2)
      if (const std::optional<MetarWeather> w = weather_group(t.substr(2), t, true)) {
        r.recent_weather.push_back(*w);
        ++i;
        return true;
      }
    if (t == "WS") {  // WS R27, WS RWY27, WS ALL RWY
      std::string group = t;
      ++i;
      if (more() && token() == "ALL") {
        group += " ALL";
        ++i;
        if (!more() || token() != "RWY") fail("RWY after WS ALL (wind shear on all runways)");
        group += " RWY";
        ++i;
      } else if (more() && std::regex_match(token(), kWindShearRunway)) {
        group += " " + token();
        ++i;
      } else {
        fail("a runway after WS (WS R27, WS RWY27 or WS ALL RWY)");
      }
      r.wind_shear.push_back(group);
      return true;
    }
    if (matches(t, kRunwayState) || matches(t, kSea) || matches(t, kColour) ||
        matches(t, kOtherSupplementary)) {
      r.supplementary.push_back(t);
      ++i;
      return true;
    }
    return false;
  }

  // A trend: its keyword and the groups up to the next trend or the remarks, as written.
  void trend() {
    std::string text = token();
    ++i;
    while (more() && !is_trend_start(token(), true) && token() != "RMK") {
      text += " " + token();
      ++i;
    }
    r.trends.push_back(text);
  }

  void parse() {
    if (tokens.empty())
      throw InputError("metar: the report is empty: expected a station and a time");
    if (token() == "METAR" || token() == "SPECI") {
      r.speci = token() == "SPECI";
      ++i;
    }
    if (more() && token() == "COR") {
      r.corrected = true;
      ++i;
    }
    if (!more()) fail_end("the station (its ICAO identifier, e.g. EDDF)");
    if (!matches(token(), kStation)) fail("the station (its ICAO identifier, e.g. EDDF)");
    r.station = token();
    ++i;
    std::smatch m;
    if (!more()) fail_end("the day and time (DDHHMMZ, e.g. 271150Z)");
    if (!matches(token(), kTime, m)) fail("the day and time (DDHHMMZ, e.g. 271150Z)");
    r.day = std::stoi(m[1]);
    r.hour = std::stoi(m[2]);
    r.minute = std::stoi(m[3]);
    if (r.day < 1 || r.day > 31 || r.hour > 23 || r.minute > 59)
      fail("a day of 01-31, an hour of 00-23 and minutes of 00-59 (DDHHMMZ)");
    ++i;
    // The observation's groups in their order; the repeatable ones may come again.
    struct Stage {
      const char* name;
      bool (*consume)(Parser&);
      bool repeats;
    };
    const Stage stages[] = {
        {"AUTO or COR", [](Parser& p) { return p.modifier(); }, true},
        {"the wind (dddffKT, dddffGggKT, VRBffKT, in KT, MPS or KMH)",
         [](Parser& p) { return p.wind(); }, false},
        {"the visibility (metres as 4 digits, CAVOK, or statute miles: 10SM, 1 1/2SM, M1/4SM)",
         [](Parser& p) { return p.visibility(); }, false},
        {"the runway visual range (R27L/0600N)", [](Parser& p) { return p.runway_visual_range(); },
         true},
        {"present weather (e.g. -SHRA, +TSRA, FZFG, BR, VCSH)",
         [](Parser& p) { return p.present_weather(); }, true},
        {"cloud (FEW, SCT, BKN or OVC with the base in hundreds of feet, CB or TCU; VVhhh; NSC, "
         "NCD, SKC, CLR)",
         [](Parser& p) { return p.clouds(); }, true},
        {"the temperature and dew point (12/06, M02/M05)",
         [](Parser& p) { return p.temperature(); }, false},
        {"the pressure (Q1013 or A2992)", [](Parser& p) { return p.pressure(); }, true},
        {"recent weather (RERA), wind shear (WS R27), runway or sea state",
         [](Parser& p) { return p.supplementary(); }, true},
    };
    constexpr size_t kStages = sizeof(stages) / sizeof(stages[0]);
    size_t stage = 0;
    while (more()) {
      if (token() == "NIL" && stage <= 1) {  // no report (after AUTO or COR, if any)
        r.nil = true;
        ++i;
        if (more()) fail("nothing after NIL (no report)");
        return;
      }
      if (token() == "RMK") {
        ++i;
        std::string text;
        for (; more(); ++i) text += (text.empty() ? "" : " ") + token();
        r.remarks = text;
        return;
      }
      if (is_trend_start(token(), !r.trends.empty())) {
        trend();
        stage = kStages;  // nothing of the observation after a trend
        continue;
      }
      bool taken = false;
      for (size_t s = stage; s < kStages && !taken; ++s)
        if (stages[s].consume(*this)) {
          taken = true;
          stage = stages[s].repeats ? s : s + 1;
        }
      if (taken) continue;
      if (stage >= kStages) fail("a trend (NOSIG, BECMG, TEMPO) or the remarks (RMK)");
      std::string expected = stages[stage].name;
      if (stage + 1 < kStages)
        expected += ", or a later group: " + std::string(stages[stage + 1].name);
      fail(expected);
    }
  }

  bool modifier() {
    const std::string& t = token();
    if (t == "AUTO") {
      r.automatic = true;
    } else if (t == "COR" || std::regex_match(t, kCorrection)) {
      r.corrected = true;
    } else {
      return false;
    }
    ++i;
    return true;
  }
};

std::string format(const char* f, double v) {
  char text[64];
  std::snprintf(text, sizeof(text), f, v);
  return text;
}

}  // namespace

float MetarWind::speed_mps() const {
  return unit == "MPS" ? speed : unit == "KMH" ? speed / 3.6f : speed * kKnotMps;
}

std::optional<float> MetarWind::gust_mps() const {
  if (!gust) return std::nullopt;
  return to_mps(*gust, unit);
}

bool MetarWeather::has(std::string_view phenomenon) const {
  return std::find(phenomena.begin(), phenomena.end(), phenomenon) != phenomena.end();
}

float MetarReport::pressure_hpa() const {
  if (qnh_hpa) return *qnh_hpa;
  if (altimeter_inhg) return *altimeter_inhg * kInchHgHpa;
  return 1013.25f;
}

MetarReport parse_metar(std::string_view text) {
  Parser p;
  std::istringstream in{std::string(text)};
  for (std::string t; in >> t;) p.tokens.push_back(t);
  // A trailing "=" ends the report (alone or on the last group).
  if (!p.tokens.empty() && p.tokens.back() == "=") p.tokens.pop_back();
  if (!p.tokens.empty() && p.tokens.back().size() > 1 && p.tokens.back().back() == '=')
    p.tokens.back().pop_back();
  for (size_t k = 0; k < p.tokens.size(); ++k)
    if (p.tokens[k].find('=') != std::string::npos) {
      p.i = k;
      p.fail("the report to end at \"=\": it holds more than one report");
    }
  p.parse();
  return p.r;
}

std::string describe(const MetarReport& r) {
  std::string s = std::string(r.speci ? "SPECI " : "METAR ") + r.station + " day " +
                  std::to_string(r.day) + " " + format("%02.0f", r.hour) + ":" +
                  format("%02.0f", r.minute) + "Z";
  if (r.automatic) s += " AUTO";
  if (r.corrected) s += " COR";
  if (r.nil) return s + " NIL";
  if (r.wind) {
    const MetarWind& w = *r.wind;
    if (w.missing)
      s += ", wind missing";
    else
      s += ", wind " +
           (w.variable ? std::string("variable") : std::to_string(w.direction_deg) + " deg") + " " +
           format("%.3g", w.speed) + (w.above ? "+" : "") + " " + w.unit +
           (w.gust ? " gusting " + format("%.3g", *w.gust) : "") +
           (w.varies_from_deg ? " (varying " + std::to_string(*w.varies_from_deg) + "-" +
                                    std::to_string(*w.varies_to_deg) + ")"
                              : "");
  }
  if (r.visibility) {
    const MetarVisibility& v = *r.visibility;
    s += v.cavok ? ", CAVOK"
         : v.missing
             ? ", visibility missing"
             : ", visibility " + std::string(v.less_than ? "under " : "") +
                   format("%.0f", v.distance_m) + " m" + (v.at_least ? " or more" : "") +
                   (v.minimum_m
                        ? " (" + format("%.0f", *v.minimum_m) + " m" +
                              (v.minimum_direction.empty() ? "" : " " + v.minimum_direction) + ")"
                        : "");
  }
  for (const MetarWeather& w : r.weather) s += ", " + w.text;
  for (const MetarCloud& c : r.clouds)
    s += ", " + c.cover + " " + (c.base_ft ? std::to_string(*c.base_ft) + " ft" : "base ///") +
         (c.type.empty() ? "" : " " + c.type);
  if (r.sky_obscured)
    s += ", sky obscured (VV " +
         (r.vertical_visibility_ft ? std::to_string(*r.vertical_visibility_ft) + " ft" : "///") +
         ")";
  if (!r.no_cloud.empty()) s += ", " + r.no_cloud;
  if (r.temperature_c) s += ", " + format("%.0f", *r.temperature_c) + " C";
  if (r.dew_point_c) s += " dew point " + format("%.0f", *r.dew_point_c) + " C";
  if (r.qnh_hpa || r.altimeter_inhg) s += ", " + format("%.1f", r.pressure_hpa()) + " hPa";
  for (const std::string& t : r.trends) s += "; trend " + t;
  return s;
}

}  // namespace nephele::weather

// nephele-view — the scene being viewed and its edits.
#include "scene_editor.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "nephele/error.h"
#include "nephele/scene_io.h"

namespace nephele::view {

std::string SceneEditor::set(const std::string& key, const std::string& value) {
  Scene next = scene_;
  try {
    set_scene_value(next, key, value);
    // A weather report pasted into weather.metar (or a forecast, a wind or a visibility in a
    // report's units) is applied as a scene file applies it: its layers, wind, haze and time.
    if (key.starts_with("weather.")) apply_weather_sources(next);
  } catch (const InputError& error) {
    error_ = error.what();
    error_key_ = key;
    return error_;
  }
  return accept(next, key);
}

std::string SceneEditor::replace(const Scene& scene, const std::string& what) {
  const std::string message = accept(scene, "");
  if (!message.empty()) error_ = what + ": " + message;
  return error_;
}

std::string SceneEditor::accept(const Scene& next, const std::string& key) {
  try {
    validate_scene(next);
  } catch (const InputError& error) {
    error_ = error.what();
    error_key_ = key;
    return error_;
  }
  scene_ = next;
  error_.clear();
  error_key_.clear();
  ++revision_;
  return "";
}

const std::vector<ParameterGroup>& parameter_groups() {
  static const std::vector<ParameterGroup> groups = [] {
    // Title and the key prefixes (a table and its subtables) or top-level keys it takes.
    const std::vector<std::pair<std::string, std::vector<std::string>>> layout = {
        {"Location and time", {"time", "time_s", "location."}},
        {"Camera", {"camera."}},
        {"Sun and moon", {"sun."}},
        {"Atmosphere and sky model", {"atmosphere."}},
        {"Clouds", {"clouds.", "noise_seed"}},
        {"High clouds", {"high_clouds."}},
        {"Cirrus", {"cirrus."}},
        {"Weather", {"weather.", "precipitation.", "lightning.", "ground_fog."}},
        {"Particle clouds", {"particle_clouds."}},
        {"Classical cloud models", {"classic."}},
        {"Terrain", {"terrain."}},
        {"Conditions", {"conditions."}},
        {"Quality", {"quality."}},
        {"Output", {"output."}},
        {"Lab", {"lab."}},
    };
    std::vector<ParameterGroup> out;
    for (const auto& [title, prefixes] : layout) out.push_back({title, {}});
    for (const SceneParameter& p : scene_parameters()) {
      bool placed = false;
      for (size_t g = 0; g < layout.size() && !placed; ++g)
        for (const std::string& prefix : layout[g].second)
          if (prefix.ends_with('.') ? p.key.starts_with(prefix) : p.key == prefix) {
            out[g].keys.push_back(p.key);
            placed = true;
            break;
          }
      if (!placed) out.back().keys.push_back(p.key);  // a new key still gets a widget
    }
    // A group's own table first, then the top-level keys it shows (clouds, then noise_seed).
    for (size_t g = 0; g < out.size(); ++g) {
      const std::string& first = layout[g].second.front();
      std::stable_partition(out[g].keys.begin(), out[g].keys.end(),
                            [&](const std::string& key) { return key.starts_with(first); });
    }
    return out;
  }();
  return groups;
}

std::vector<double> parse_numbers(const std::string& literal) {
  std::vector<double> out;
  size_t i = 0;
  while (i < literal.size()) {
    const char c = literal[i];
    if (c == '[' || c == ']' || c == ',' || c == ' ' || c == '\t') {
      ++i;
      continue;
    }
    size_t end = literal.find_first_of(",] \t", i);
    if (end == std::string::npos) end = literal.size();
    std::string word = literal.substr(i, end - i);
    double value = std::numeric_limits<double>::quiet_NaN();
    if (word == "inf" || word == "+inf") {
      value = std::numeric_limits<double>::infinity();
    } else if (word == "-inf") {
      value = -std::numeric_limits<double>::infinity();
    } else if (word != "nan" && word != "+nan" && word != "-nan") {
      std::erase(word, '_');  // TOML's digit separators
      value = std::strtod(word.c_str(), nullptr);
    }
    out.push_back(value);
    i = end;
  }
  return out;
}

std::string float_literal(float value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string vector_literal(const float* values, int count) {
  std::string text = "[";
  for (int i = 0; i < count; ++i) text += (i ? ", " : "") + float_literal(values[i]);
  return text + "]";
}

std::string quote_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned char>(c));
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string unquote_string(const std::string& literal) {
  if (literal.size() < 2 || literal.front() != '"' || literal.back() != '"') return "";
  std::string out;
  for (size_t i = 1; i + 1 < literal.size(); ++i) {
    char c = literal[i];
    if (c != '\\' || i + 2 >= literal.size()) {
      out += c;
      continue;
    }
    c = literal[++i];
    switch (c) {
      case 'n':
        out += '\n';
        break;
      case 't':
        out += '\t';
        break;
      case 'r':
        out += '\r';
        break;
      case 'u':  // the writer escapes only control characters this way
        if (i + 4 < literal.size()) {
          out += char(std::strtol(literal.substr(i + 1, 4).c_str(), nullptr, 16));
          i += 4;
        }
        break;
      default:
        out += c;  // \" and \\ .
    }
  }
  return out;
}

}  // namespace nephele::view

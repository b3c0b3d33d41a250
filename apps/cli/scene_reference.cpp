// nephele CLI — the scene reference, generated from scene_parameters() and the scene flags.
#include "scene_reference.h"

#include <map>
#include <string_view>

#include "nephele/scene_io.h"
#include "scene/scene_fields.h"
#include "scene_flags.h"

namespace nephele::cli {
namespace {

// A table cell: no line breaks, pipes escaped.
std::string cell(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '|')
      out += "\\|";
    else if (c == '\n')
      out += ' ';
    else
      out += c;
  }
  return out;
}

std::string code(std::string_view text) {
  return text.empty() ? "" : "`" + cell(text) + "`";
}

std::string allowed_of(const SceneParameter& p) {
  if (!p.allowed.empty()) {
    std::string text;
    for (size_t i = 0; i < p.allowed.size(); ++i)
      text += (i == 0 ? "" : ", ") + std::string("`") + p.allowed[i] + "`";
    return text;
  }
  return cell(p.allowed_values);
}

// "conditions.good.night.hour" -> table "conditions.good.night", key "hour".
std::pair<std::string, std::string> split_key(const std::string& key) {
  const size_t dot = key.rfind('.');
  if (dot == std::string::npos) return {"", key};
  return {key.substr(0, dot), key.substr(dot + 1)};
}
// The rows of an array of tables' keys, with `defaults`' values.
template <typename T>
std::string array_rows(const T& defaults, const std::vector<scene_detail::ArrayField<T>>& fields) {
  std::string md;
  for (const scene_detail::ArrayField<T>& field : fields)
    md += "| " + code(field.name) + " | " + cell(scene_detail::unit_of(field.name)) + " | " +
          cell(scene_detail::allowed_text(field)) + " | " +
          code(scene_detail::array_field_value_text(defaults, field)) + " |  | " +
          cell(field.note) + " |\n";
  return md;
}

const char* kHeader =
    "| key | unit | allowed | default | flag | meaning |\n"
    "|---|---|---|---|---|---|\n";

}  // namespace

std::string scene_reference_markdown() {
  std::map<std::string, std::string> flag_of;  // key -> "--flag"
  for (const auto& [flag, key] : scene_flag_keys())
    if (!flag_of.count(key)) flag_of[key] = flag;

  std::string md =
      "# Scene reference\n\n"
      "Every key of a scene file (TOML), with its unit, the values it allows, its default (a\n"
      "scene without `preset` starts from these), the `nephele render` flag that sets it and\n"
      "what it means. A preset (`preset = \"sunset\"`, `nephele presets`) changes some defaults.\n"
      "The rules between keys (a layer's bottom below its top, the cirrus above the clouds) are\n"
      "checked too; their messages name both keys.\n\n"
      "Generated from the table of scene fields (`src/scene/scene_fields.cpp`), where each key's\n"
      "range, unit and meaning are declared once; validation, the CLI's help and the viewer's\n"
      "panel read the same table. Do not edit this page: run\n"
      "`./build/nephele keys > docs/scene-reference.md` (a test fails while it is out of date).\n";

  // Keyframe tables ([conditions.good.night] ...) share their keys: shown once.
  const std::string keyframe_prefix = "conditions.good.";
  const std::string keyframe_example = keyframe_prefix + "night";
  std::string table = "\x01";  // no table yet
  for (const SceneParameter& p : scene_parameters()) {
    auto [section, name] = split_key(p.key);
    const bool keyframe =
        section.starts_with("conditions.good.") || section.starts_with("conditions.bad.");
    if (keyframe && section != keyframe_example) continue;
    if (section != table) {
      table = section;
      if (section.empty())
        md += "\n## Top level\n\n";
      else if (keyframe)
        md +=
            "\n## [conditions.good.night] and the other keyframes\n\n"
            "The same keys in each keyframe table, `[conditions.good.K]` and `[conditions.bad.K]`"
            " for K in night, dawn, sunrise, morning, day, evening, sunset, dusk and late_evening"
            " (the presets' tables give their values; the default shown is good night's).\n\n";
      else
        md += "\n## [" + section + "]\n\n";
      md += kHeader;
    }
    const auto flag = flag_of.find(p.key);
    md += "| " + code(name) + " | " + cell(p.unit) + " | " + allowed_of(p) + " | " +
          code(p.default_value) + " | " + (flag == flag_of.end() ? "" : code(flag->second)) +
          " | " + cell(p.meaning) + " |\n";
  }

  md +=
      "\n## [[cloud_layers]]\n\n"
      "An array of tables, one per volumetric layer besides `clouds` and `high_clouds` (at most " +
      std::to_string(kMaxCloudLayers - 2) +
      "), given as a weather report gives one: the renderer finds the shell and the coverage "
      "that put its clouds' bases and tops where they are given and cover its oktas. Shells "
      "that are there may not overlap.\n\n" +
      kHeader;
  md += array_rows(CloudLayerParams{}, scene_detail::cloud_layer_fields());
  md +=
      "\n## [[voxel_clouds]]\n\n"
      "An array of tables, one per voxel cloud (at most " +
      std::to_string(kMaxVoxelClouds) +
      "); `lat_deg`, `lon_deg` and `altitude_m` (all three) may replace `position_m`. "
      "`nephele render --voxel-cloud SPEC` adds one.\n\n" +
      kHeader;
  md += array_rows(VoxelCloudParams{}, scene_detail::voxel_cloud_fields());
  return md;
}

}  // namespace nephele::cli

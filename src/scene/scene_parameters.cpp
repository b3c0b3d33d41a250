// nephele — the scene's parameters one at a time (scene_parameters, get/set_scene_value),
// generated from the table of scene keys that the TOML reader and writer share.
#include <type_traits>

#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "scene/scene_fields.h"

namespace nephele {
namespace {

using scene_detail::Field;
using scene_detail::Section;

std::string key_of(const Section& section, const Field& field) {
  if (section.name.empty()) return std::string(field.name);
  return std::string(section.name) + "." + std::string(field.name);
}

// The kind and, for enumerations, the allowed values of the field `access` refers to.
template <typename T>
void describe_type(SceneParameter& parameter) {
  using K = SceneValueKind;
  if constexpr (std::is_same_v<T, float>) {
    parameter.kind = K::kFloat;
  } else if constexpr (std::is_same_v<T, int>) {
    parameter.kind = K::kInt;
  } else if constexpr (std::is_same_v<T, uint32_t>) {
    parameter.kind = K::kUint;
  } else if constexpr (std::is_same_v<T, glm::vec2>) {
    parameter.kind = K::kVec2;
  } else if constexpr (std::is_same_v<T, glm::vec3>) {
    parameter.kind = K::kVec3;
  } else if constexpr (std::is_same_v<T, std::string>) {
    parameter.kind = K::kString;
  } else if constexpr (std::is_same_v<T, bool>) {
    parameter.kind = K::kBool;
  } else if constexpr (std::is_same_v<T, MarchMode>) {
    parameter.kind = K::kEnum;
    for (MarchMode m : {MarchMode::Default, MarchMode::Baseline})
      parameter.allowed.emplace_back(to_string(m));
  } else if constexpr (std::is_same_v<T, VoxelMarch>) {
    parameter.kind = K::kEnum;
    for (VoxelMarch m : {VoxelMarch::Plain, VoxelMarch::ThreePhase})
      parameter.allowed.emplace_back(to_string(m));
  } else if constexpr (std::is_same_v<T, VoxelShadow>) {
    parameter.kind = K::kEnum;
    for (VoxelShadow m : {VoxelShadow::LightMarch, VoxelShadow::SdfCone})
      parameter.allowed.emplace_back(to_string(m));
  } else if constexpr (std::is_same_v<T, CloudModel>) {
    parameter.kind = K::kEnum;
    for (CloudModel m : kCloudModels) parameter.allowed.emplace_back(to_string(m));
  } else if constexpr (std::is_same_v<T, ToneMap>) {
    parameter.kind = K::kEnum;
    for (ToneMap op : kToneMaps) parameter.allowed.emplace_back(to_string(op));
  } else if constexpr (std::is_same_v<T, SkyModel>) {
    parameter.kind = K::kEnum;
    for (SkyModel m : {SkyModel::Hillaire, SkyModel::Preetham, SkyModel::Reference})
      parameter.allowed.emplace_back(to_string(m));
  } else {
    static_assert(std::is_same_v<T, ConditionsMode>, "a field type SceneValueKind lacks");
    parameter.kind = K::kEnum;
    for (ConditionsMode m : {ConditionsMode::Off, ConditionsMode::Artist, ConditionsMode::Overlay})
      parameter.allowed.emplace_back(to_string(m));
  }
}

const Section* find_section(std::string_view name) {
  for (const Section& section : scene_detail::scene_sections())
    if (section.name == name) return &section;
  return nullptr;
}

// "unknown key 'clouds.cover' (allowed in [clouds]: bottom_altitude_m, ...)".
[[noreturn]] void fail_unknown_key(std::string_view key) {
  const size_t dot = key.rfind('.');
  const Section* section = find_section(dot == std::string_view::npos ? "" : key.substr(0, dot));
  std::string message = "unknown scene key '";
  message.append(shorten_for_message(key)).append("' (allowed ");
  if (section && !section->fields.empty()) {
    if (section->name.empty())
      message.append("at the top level: ");
    else
      message.append("in [").append(section->name).append("]: ");
    for (size_t i = 0; i < section->fields.size(); ++i)
      message.append(i == 0 ? "" : ", ").append(section->fields[i].name);
  } else {
    message.append("tables:");
    for (const Section& s : scene_detail::scene_sections())
      if (!s.name.empty() && s.name.find('.') == std::string_view::npos)
        message.append(" ").append(s.name);
  }
  throw InputError(message + ")");
}

const Field& field_or_fail(std::string_view key) {
  const Field* field = scene_detail::find_field(key);
  if (!field) fail_unknown_key(key);
  return *field;
}

}  // namespace

const Field* scene_detail::find_field(std::string_view key) {
  const size_t dot = key.rfind('.');
  const std::string_view section_name = dot == std::string_view::npos ? "" : key.substr(0, dot);
  const std::string_view name = dot == std::string_view::npos ? key : key.substr(dot + 1);
  const Section* section = find_section(section_name);
  if (!section) return nullptr;
  for (const Field& field : section->fields)
    if (field.name == name) return &field;
  return nullptr;
}

const std::vector<SceneParameter>& scene_parameters() {
  static const std::vector<SceneParameter> parameters = [] {
    std::vector<SceneParameter> list;
    const Scene defaults{};
    for (const Section& section : scene_detail::scene_sections()) {
      for (const Field& field : section.fields) {
        SceneParameter parameter;
        parameter.key = key_of(section, field);
        parameter.note = scene_detail::field_comment(field);
        parameter.meaning = std::string(field.note);
        parameter.allowed_values = scene_detail::allowed_text(field);
        parameter.unit = std::string(scene_detail::unit_of(field.name));
        if (field.range.given) {
          parameter.min = field.range.min;
          parameter.max = field.range.max;
          parameter.min_open = field.range.min_open;
          parameter.max_open = field.range.max_open;
          if (field.range.has_off) parameter.off = field.range.off;
        }
        parameter.default_value = scene_detail::field_value_text(defaults, field);
        parameter.flag = std::string(field.flag);
        std::visit(
            [&](auto access) {
              using T = std::remove_reference_t<decltype(access(std::declval<Scene&>()))>;
              describe_type<T>(parameter);
            },
            field.access);
        list.push_back(std::move(parameter));
      }
    }
    return list;
  }();
  return parameters;
}

std::string get_scene_value(const Scene& scene, std::string_view key) {
  return scene_detail::field_value_text(scene, field_or_fail(key));
}

void set_scene_value(Scene& scene, std::string_view key, std::string_view value) {
  scene_detail::read_field_value(scene, field_or_fail(key), std::string(key), value);
}

}  // namespace nephele

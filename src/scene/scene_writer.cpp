// nephele — writing a scene as TOML (the --verbose dump; it reads back to the same scene).
#include <cstdio>

#include "nephele/scene_io.h"
#include "scene/scene_fields.h"

namespace nephele {
namespace {

using scene_detail::toml_float;

std::string toml_value(float value) {
  return toml_float(value);
}
std::string toml_value(int value) {
  return std::to_string(value);
}
std::string toml_value(uint32_t value) {
  return std::to_string(value);
}
std::string toml_value(const std::string& value) {
  return scene_detail::toml_quote(value);
}
std::string toml_value(bool value) {
  return value ? "true" : "false";
}
std::string toml_value(MarchMode mode) {
  return scene_detail::toml_quote(to_string(mode));
}
std::string toml_value(ConditionsMode mode) {
  return scene_detail::toml_quote(to_string(mode));
}
std::string toml_value(CloudModel model) {
  return scene_detail::toml_quote(to_string(model));
}
std::string toml_value(ToneMap op) {
  return scene_detail::toml_quote(to_string(op));
}
std::string toml_value(SkyModel model) {
  return scene_detail::toml_quote(to_string(model));
}
std::string toml_value(VoxelMarch mode) {
  return scene_detail::toml_quote(to_string(mode));
}
std::string toml_value(VoxelShadow mode) {
  return scene_detail::toml_quote(to_string(mode));
}

template <typename Vector>
std::string toml_value(const Vector& v) {
  std::string text = "[";
  for (int i = 0; i < Vector::length(); ++i) text += (i == 0 ? "" : ", ") + toml_float(v[i]);
  return text + "]";
}

// A comment giving the sun direction as angles, which is how people think of it.
std::string sun_angles_note(const glm::vec3& direction) {
  SunAngles angles = sun_angles_from_direction(direction);
  char text[96];
  std::snprintf(text, sizeof text, "elevation %.2f deg, azimuth %.2f deg", angles.elevation_deg,
                angles.azimuth_deg);
  return text;
}

}  // namespace

std::string scene_detail::field_value_text(const Scene& scene, const scene_detail::Field& field) {
  Scene copy = scene;  // the field table hands out mutable references
  std::string text;
  std::visit([&](auto access) { text = toml_value(access(copy)); }, field.access);
  return text;
}

template <typename T>
std::string scene_detail::array_field_value_text(const T& item,
                                                 const scene_detail::ArrayField<T>& field) {
  T copy = item;  // the field table hands out mutable references
  std::string text;
  std::visit([&](auto access) { text = toml_value(access(copy)); }, field.access);
  return text;
}
template std::string scene_detail::array_field_value_text(const VoxelCloudParams&,
                                                          const scene_detail::VoxelField&);
template std::string scene_detail::array_field_value_text(const CloudLayerParams&,
                                                          const scene_detail::CloudLayerField&);

// fov_deg is written when it is the form the camera gives its field of view in (the reader
// refuses fov_deg with a non-zero horizontal_fov_deg or focal_length_mm); the others always, 0
// when not given.
static bool fov_form_written(const CameraParams& camera, std::string_view name) {
  return name != "fov_deg" || (camera.focal_length_mm == 0.0f && camera.horizontal_fov_deg == 0.0f);
}

std::string scene_to_toml(const Scene& scene) {
  Scene copy = scene;  // the field table hands out mutable references
  std::string out = "# nephele scene, fully resolved\n";
  for (const scene_detail::Section& section : scene_detail::scene_sections()) {
    if (!section.name.empty()) out += "\n[" + std::string(section.name) + "]\n";
    for (const scene_detail::Field& field : section.fields) {
      // The field of view in its one given form (the reader refuses two); the others as a
      // comment.
      if (section.name == "camera" && !fov_form_written(scene.camera, field.name)) {
        if (field.name == "fov_deg")
          out += "# fov_deg = " + toml_float(vertical_fov_deg(scene)) +
                 "  # the vertical field of view this gives at output's aspect\n";
        continue;
      }
      std::string line = std::string(field.name) + " = ";
      std::visit([&](auto access) { line += toml_value(access(copy)); }, field.access);
      std::string note = scene_detail::field_comment(field);
      if (section.name == "sun" && field.name == "direction")
        note += "; " + sun_angles_note(scene.sun.direction);
      if (!note.empty()) line += "  # " + note;
      out += line + "\n";
    }
  }
  // Arrays of tables go last: a [[table]] ends only at the next header.
  for (const CloudLayerParams& layer : scene.cloud_layers) {
    out += "\n[[" + std::string(scene_detail::kCloudLayersKey) + "]]\n";
    for (const scene_detail::CloudLayerField& field : scene_detail::cloud_layer_fields())
      out += std::string(field.name) + " = " + scene_detail::array_field_value_text(layer, field) +
             "  # " + scene_detail::field_comment(field) + "\n";
  }
  for (const VoxelCloudParams& cloud : scene.voxel_clouds) {
    out += "\n[[" + std::string(scene_detail::kVoxelCloudsKey) + "]]\n";
    for (const scene_detail::VoxelField& field : scene_detail::voxel_cloud_fields()) {
      // The source not used is left out (an empty one reads back as empty anyway).
      if ((field.name == "file" && cloud.file.empty()) ||
          (field.name == "preset" && cloud.preset.empty()))
        continue;
      out += std::string(field.name) + " = " + scene_detail::array_field_value_text(cloud, field) +
             "  # " + scene_detail::field_comment(field) + "\n";
    }
  }
  return out;
}

}  // namespace nephele

// nephele — internal: the table of scene keys shared by the TOML reader and writer, and
// number formatting shared with validation.
#pragma once

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "nephele/scene.h"

namespace nephele::scene_detail {

// Reference to one field of a Scene; the alternative says the field's type.
using FieldAccess =
    std::variant<float& (*)(Scene&), int& (*)(Scene&), uint32_t& (*)(Scene&),
                 glm::vec2& (*)(Scene&), glm::vec3& (*)(Scene&), std::string& (*)(Scene&),
                 MarchMode& (*)(Scene&), bool& (*)(Scene&), SkyModel& (*)(Scene&),
                 ConditionsMode& (*)(Scene&), VoxelMarch& (*)(Scene&), VoxelShadow& (*)(Scene&),
                 CloudModel& (*)(Scene&), ToneMap& (*)(Scene&)>;

// The values a number (or each component of a vector) may take, declared with its field:
// [min, max] with either end open, and `off`, a value outside it that turns the feature off
// ("0 or [1, 1e+07]"). Validation, the CLI's help, the viewer's panel and the scene reference
// all read it from here.
struct Range {
  double min = 0.0, max = 0.0;
  bool min_open = false, max_open = false;
  bool given = false;  // false: any value of the type
  bool has_off = false;
  double off = 0.0;
};
constexpr Range closed(double min, double max) {
  return {min, max, false, false, true};
}
constexpr Range left_open(double min, double max) {
  return {min, max, true, false, true};
}
constexpr Range right_open(double min, double max) {
  return {min, max, false, true, true};
}
constexpr Range open_range(double min, double max) {
  return {min, max, true, true, true};
}
constexpr Range or_off(double off, Range range) {
  range.has_off = true;
  range.off = off;
  return range;
}
constexpr double kPi = 3.14159265358979323846;

struct Field {
  std::string_view name;  // key inside its table, e.g. "coverage"
  FieldAccess access;
  std::string_view note;  // what it means; the range and choices are added to it (field_comment)
  Range range{};          // numbers: the values allowed
  std::vector<std::string_view> choices{};  // strings and integers: the only values allowed
  // The command line's flag that sets it ("ground-fog-visibility-m" for --ground-fog-...);
  // empty: none, or one of the CLI's own (apps/cli/scene_flags.cpp).
  std::string_view flag{};
};

// What a field holds, for the range's wording and checks.
enum class ValueShape { kNumber, kInteger, kVec2, kVec3, kString, kOther };
ValueShape value_shape(const FieldAccess& access);
// The allowed values as text (below) for a range and choices of a value of this shape.
std::string allowed_text(const Range& range, const std::vector<std::string_view>& choices,
                         ValueShape shape);

// "[0, 1]", "(0, 100]", "0 or [1, 1e+07]", "[-200, 200] each" (a vector), "1, 2 or 4",
// "\"off\", \"direct\" or \"tiles\"" (quoted for strings); "" when anything goes.
std::string allowed_text(const Field& field);
// "expected an integer in [1, 16384]", "expected an integer: 1, 2 or 4", "expected an integer"
// for `allowed` (allowed_text's) "[1, 16384]", "1, 2 or 4", "".
std::string expected_integer(const std::string& allowed);
// The unit the key's name ends with (its suffix, by the project's naming): "m", "km", "deg",
// "m/s", "s", "1/m", "lux", "mm", "cd/m^2", "sr", "EV", "EV/s", "1/m^3"; "" for none.
std::string_view unit_of(std::string_view name);
// scene_to_toml's comment and SceneParameter::note: the allowed values, then the note.
std::string field_comment(const Field& field);
// Whether the field's type is an integer (int or uint32_t).
bool is_integer_field(const Field& field);

struct Section {
  std::string_view name;  // TOML table name; "" for the top level
  std::vector<Field> fields;
  std::vector<std::string_view> extra_keys;  // keys the reader handles itself
};

// The keys of one table of an array of tables ([[voxel_clouds]], [[cloud_layers]]: arrays the
// field table above cannot hold; the reader, the writer and validation go through these lists).
template <typename T>
using ArrayFieldAccess =
    std::variant<float& (*)(T&), int& (*)(T&), uint32_t& (*)(T&), glm::vec2& (*)(T&),
                 glm::vec3& (*)(T&), std::string& (*)(T&), bool& (*)(T&)>;

template <typename T>
struct ArrayField {
  std::string_view name;  // key inside the table, e.g. "density"
  ArrayFieldAccess<T> access;
  std::string_view note;  // what it means (field_comment adds the range)
  Range range{};
  std::vector<std::string_view> choices{};  // strings: the only values allowed
};
using VoxelField = ArrayField<VoxelCloudParams>;
using CloudLayerField = ArrayField<CloudLayerParams>;

// The shape of the value a field of `Owner` (Scene, VoxelCloudParams, ...) refers to.
template <typename Owner, typename Access>
ValueShape shape_of(const Access& access) {
  return std::visit(
      [](auto get) {
        using V = std::remove_reference_t<decltype(get(std::declval<Owner&>()))>;
        if constexpr (std::is_same_v<V, float>) return ValueShape::kNumber;
        if constexpr (std::is_same_v<V, int> || std::is_same_v<V, uint32_t>)
          return ValueShape::kInteger;
        if constexpr (std::is_same_v<V, glm::vec2>) return ValueShape::kVec2;
        if constexpr (std::is_same_v<V, glm::vec3>) return ValueShape::kVec3;
        if constexpr (std::is_same_v<V, std::string>) return ValueShape::kString;
        return ValueShape::kOther;
      },
      access);
}
template <typename T>
ValueShape value_shape(const ArrayFieldAccess<T>& access) {
  return shape_of<T>(access);
}
std::string field_comment(const Range& range, const std::vector<std::string_view>& choices,
                          ValueShape shape, std::string_view note);
template <typename T>
std::string field_comment(const ArrayField<T>& field) {
  return field_comment(field.range, field.choices, value_shape(field.access), field.note);
}
template <typename T>
std::string allowed_text(const ArrayField<T>& field) {
  return allowed_text(field.range, field.choices, value_shape(field.access));
}

// The array's top-level key.
constexpr std::string_view kVoxelCloudsKey = "voxel_clouds";
// Every key of a [[voxel_clouds]] table that is a field, in the order scene_to_toml writes them.
const std::vector<VoxelField>& voxel_cloud_fields();
// The keys the reader turns into position_m itself (all three or none, and not with position_m).
inline constexpr std::string_view kVoxelCloudGeoKeys[] = {"lat_deg", "lon_deg", "altitude_m"};
// "voxel_clouds[2]": how messages name cloud i (0-based).
std::string voxel_cloud_key(size_t index);

// [[cloud_layers]] (Scene::cloud_layers): its key, its tables' fields in the order scene_to_toml
// writes them, and "cloud_layers[1]", how messages name layer i (0-based).
constexpr std::string_view kCloudLayersKey = "cloud_layers";
const std::vector<CloudLayerField>& cloud_layer_fields();
std::string cloud_layer_key(size_t index);
// The genera a [[cloud_layers]] table's genus may name.
inline constexpr std::string_view kCloudLayerGenera[] = {"stratus", "stratocumulus", "altocumulus",
                                                         "cumulus", "cumulonimbus"};

// Whether `text` ends with `suffix` (given in lower case), ignoring the case of `text`'s letters:
// file names' extensions ("CLOUD.VDB" ends with ".vdb").
bool ends_with_ignoring_case(std::string_view text, std::string_view suffix);

// One of the voxel clouds' presets (voxel::kCloudPresetNames).
bool is_voxel_cloud_preset(std::string_view name);

// toml++ builds and destroys nested tables recursively, so a dotted key of 50,000 parts
// overflows the stack. nephele's deepest key has 4 parts (conditions.good.night.hour); a
// line whose keys have more than this many parts is refused before parsing (scene files and
// camera paths).
constexpr int kMaxKeyParts = 32;
// The first line on which keys have more than kMaxKeyParts dotted parts, 0 when none.
int line_of_too_deep_key(std::string_view text);

// Every field of Scene, in the order scene_to_toml writes them; the top level comes first.
const std::vector<Section>& scene_sections();

// The field of a dotted key ("clouds.coverage", "time"), nullptr when there is none.
const Field* find_field(std::string_view key);

// The field's value as TOML literal text (scene_writer.cpp).
std::string field_value_text(const Scene& scene, const Field& field);

// A field's value in one table of an array of tables as TOML literal text (VoxelCloudParams,
// CloudLayerParams).
template <typename T>
std::string array_field_value_text(const T& item, const ArrayField<T>& field);

// Reads TOML literal text into the field with the scene file's type rules (scene_io.cpp);
// throws InputError "key = value: what is allowed" and leaves the scene unchanged.
void read_field_value(Scene& scene, const Field& field, const std::string& key,
                      std::string_view text);

// Shortest text that reads back as the same value: "1.5", "5.802e-06", "nan", "-inf".
std::string format_float(float value);
std::string format_double(double value);
// A TOML float literal that toml++ reads back (via double) as exactly `value`.
std::string toml_float(float value);
// A TOML basic string literal, quoted and escaped.
std::string toml_quote(std::string_view text);

// The text of a small file a user names (a scene file, a camera path): only a regular file of
// at most 1 MiB, read once. Errors are InputErrors "<path>: cannot read the <what>: <why>",
// with `too_large` as the why of a larger file.
std::string read_small_text_file(const std::string& path, const std::string& what,
                                 const std::string& too_large);

}  // namespace nephele::scene_detail

// nephele-view — the scene being viewed, and the one way it is edited.
//
// Panel edits and script `set` lines go through SceneEditor::set: set_scene_value on a copy of
// the current scene, then validate_scene, as a scene file is checked. Only a scene that passes
// both replaces the current one; otherwise the error is kept (for the panel to show beside the
// field, for the script to print) and the last valid scene keeps rendering.
#pragma once

#include <string>
#include <vector>

#include "nephele/scene.h"

namespace nephele::view {

class SceneEditor {
 public:
  explicit SceneEditor(Scene scene) : scene_(std::move(scene)) {}

  // The current scene: always one that validate_scene accepts.
  const Scene& scene() const { return scene_; }

  // Sets `key` to TOML literal text. Returns "" when the scene took it, else the one-line
  // message ("clouds.coverage = 1.5: must be in [0, 1]"), also kept in error().
  std::string set(const std::string& key, const std::string& value);
  // Replaces the whole scene (a preset, a scene file), validated like set.
  std::string replace(const Scene& scene, const std::string& what);
  // Changes the viewer makes itself (camera, clock, render size); they must keep the scene
  // valid, and are refused (returning the message) when they do not.
  template <typename Change>
  std::string change(Change&& change) {
    Scene next = scene_;
    change(next);
    return accept(next, "");
  }

  // The last refused edit: its key ("" for a whole scene) and message; empty after a success.
  const std::string& error() const { return error_; }
  const std::string& error_key() const { return error_key_; }
  // Bumped on every accepted change (the view is not still then).
  long revision() const { return revision_; }

 private:
  std::string accept(const Scene& next, const std::string& key);

  Scene scene_;
  std::string error_, error_key_;
  long revision_ = 0;
};

// The panel's groups, as the scene file is grouped, each with the keys of scene_parameters()
// it shows; every key is in exactly one.
struct ParameterGroup {
  std::string title;              // "Clouds"
  std::vector<std::string> keys;  // "clouds.coverage", ...
};
const std::vector<ParameterGroup>& parameter_groups();

// --- TOML literal text <-> widget values -------------------------------------------------

// The numbers of a float, int or vector literal ("0.45", "[8.0, 2.0]", "nan", "-inf").
std::vector<double> parse_numbers(const std::string& literal);
// The shortest text that reads back as `value` ("0.45", "1e+06", "nan", "-inf").
std::string float_literal(float value);
// "[a, b]" / "[a, b, c]".
std::string vector_literal(const float* values, int count);
// A TOML basic string, quoted and escaped; and back (a literal that is not a string gives "").
std::string quote_string(const std::string& text);
std::string unquote_string(const std::string& literal);

}  // namespace nephele::view

// nephele-view — the panel's scene parameters: one widget per key of scene_parameters(), in the
// scene file's groups, with its note as a tooltip; edits go through SceneEditor::set.
#pragma once

#include "scene_editor.h"

namespace nephele::view {

// Draws one group's widgets (inside the caller's ImGui window). Returns true when an edit was
// made (accepted or not).
bool draw_parameter_group(const ParameterGroup& group, SceneEditor& editor);

}  // namespace nephele::view

// nephele-view — the panel's scene-parameter widgets.
#include "panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "nephele/scene_io.h"

namespace nephele::view {
namespace {

const SceneParameter* find_parameter(const std::string& key) {
  static const std::map<std::string, const SceneParameter*> index = [] {
    std::map<std::string, const SceneParameter*> m;
    for (const SceneParameter& p : scene_parameters()) m[p.key] = &p;
    return m;
  }();
  auto it = index.find(key);
  return it == index.end() ? nullptr : it->second;
}

// A drag speed for a value of this size: 1/200 of it, so that a long drag spans decades.
float drag_speed(double value) {
  const double magnitude = std::fabs(value);
  return float(magnitude > 0.0 && std::isfinite(magnitude) ? magnitude * 0.005 : 0.001);
}

void tooltip(const SceneParameter& p) {
  if (!ImGui::IsItemHovered()) return;
  ImGui::BeginTooltip();
  ImGui::TextUnformatted(p.key.c_str());
  if (!p.note.empty()) {
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
    ImGui::TextUnformatted(p.note.c_str());
    ImGui::PopTextWrapPos();
  }
  ImGui::EndTooltip();
}

// The drag's limits from the parameter's declared range (0, 0: none). An open end is nudged
// inside; an "off" value outside the range widens it, so that the drag can reach it.
void drag_limits(const SceneParameter& p, float& low, float& high) {
  low = high = 0.0f;
  if (std::isnan(p.min) || std::isnan(p.max)) return;
  double min = p.min, max = p.max;
  if (p.off) {
    min = std::min(min, *p.off);
    max = std::max(max, *p.off);
  }
  low = float(min);
  high = float(max);
  if (p.min_open && !(p.off && *p.off <= p.min)) low = std::nextafter(low, high);
  if (p.max_open && !(p.off && *p.off >= p.max)) high = std::nextafter(high, low);
}

// One widget; returns the new TOML text when it was edited, "" otherwise.
std::string draw_widget(const SceneParameter& p, const std::string& label, const std::string& value) {
  using K = SceneValueKind;
  switch (p.kind) {
    case K::kFloat: {
      const std::vector<double> n = parse_numbers(value);
      float v = n.empty() ? 0.0f : float(n[0]);
      float low, high;
      drag_limits(p, low, high);
      if (ImGui::DragFloat(label.c_str(), &v, drag_speed(v), low, high, "%.6g"))
        return float_literal(v);
      break;
    }
    case K::kVec2:
    case K::kVec3: {
      const std::vector<double> n = parse_numbers(value);
      const int count = p.kind == K::kVec2 ? 2 : 3;
      float v[3] = {0.0f, 0.0f, 0.0f};
      double largest = 0.0;
      for (int i = 0; i < count && i < int(n.size()); ++i) {
        v[i] = float(n[size_t(i)]);
        largest = std::max(largest, std::fabs(n[size_t(i)]));
      }
      float low, high;
      drag_limits(p, low, high);
      const bool edited =
          count == 2 ? ImGui::DragFloat2(label.c_str(), v, drag_speed(largest), low, high, "%.5g")
                     : ImGui::DragFloat3(label.c_str(), v, drag_speed(largest), low, high, "%.5g");
      if (edited) return vector_literal(v, count);
      break;
    }
    case K::kInt: {
      int v = int(std::strtol(value.c_str(), nullptr, 10));
      float low, high;
      drag_limits(p, low, high);
      if (ImGui::DragInt(label.c_str(), &v, 0.25f, int(low), int(high))) return std::to_string(v);
      break;
    }
    case K::kUint: {
      uint32_t v = uint32_t(std::strtoul(value.c_str(), nullptr, 10));
      const uint32_t step = 1;
      if (ImGui::InputScalar(label.c_str(), ImGuiDataType_U32, &v, &step))
        return std::to_string(v);
      break;
    }
    case K::kBool: {
      bool v = value == "true";
      if (ImGui::Checkbox(label.c_str(), &v)) return v ? "true" : "false";
      break;
    }
    case K::kEnum: {
      const std::string current = unquote_string(value);
      std::string chosen;
      if (ImGui::BeginCombo(label.c_str(), current.c_str())) {
        for (const std::string& option : p.allowed)
          if (ImGui::Selectable(option.c_str(), option == current) && option != current)
            chosen = option;
        ImGui::EndCombo();
      }
      if (!chosen.empty()) return quote_string(chosen);
      break;
    }
    case K::kString: {
      // Applied on Enter: a half-typed path or time is not an edit.
      char buffer[1024];
      const std::string text = unquote_string(value);
      std::snprintf(buffer, sizeof buffer, "%s", text.c_str());
      if (ImGui::InputText(label.c_str(), buffer, sizeof buffer,
                           ImGuiInputTextFlags_EnterReturnsTrue))
        return quote_string(buffer);
      break;
    }
  }
  return "";
}

}  // namespace

bool draw_parameter_group(const ParameterGroup& group, SceneEditor& editor) {
  bool edited = false;
  bool table_open = true;
  std::string current_table;  // the keyframe whose tree node is being drawn, "" for none
  for (const std::string& key : group.keys) {
    const SceneParameter* p = find_parameter(key);
    if (!p) continue;
    // Keyframes (conditions.good.night.hour): one tree node per keyframe.
    const size_t dot = key.rfind('.');
    const std::string table = key.substr(0, dot == std::string::npos ? 0 : dot);
    const bool nested = std::count(key.begin(), key.end(), '.') >= 3;
    if (nested && table != current_table) {
      if (!current_table.empty() && table_open) ImGui::TreePop();
      current_table = table;
      table_open = ImGui::TreeNode(table.c_str());
    } else if (!nested && !current_table.empty()) {
      if (table_open) ImGui::TreePop();
      current_table.clear();
      table_open = true;
    }
    if (nested && !table_open) continue;

    ImGui::PushID(key.c_str());
    const std::string label = key.substr(dot == std::string::npos ? 0 : dot + 1);
    const std::string text = draw_widget(*p, label, get_scene_value(editor.scene(), key));
    tooltip(*p);
    if (!text.empty()) {
      editor.set(key, text);
      edited = true;
    }
    // The refused edit's message, in red, beside the field it names.
    const std::string& error = editor.error();
    if (!error.empty() && (editor.error_key() == key || error.starts_with(key + " ="))) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.35f, 0.3f, 1.0f));
      ImGui::PushTextWrapPos(0.0f);
      ImGui::TextUnformatted(error.c_str());
      ImGui::PopTextWrapPos();
      ImGui::PopStyleColor();
    }
    ImGui::PopID();
  }
  if (!current_table.empty() && table_open) ImGui::TreePop();
  return edited;
}

}  // namespace nephele::view

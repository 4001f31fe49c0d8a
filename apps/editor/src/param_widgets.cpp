#include "param_widgets.hpp"

#include <imgui.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace sylva::editor {
namespace {

ImGuiDataType data_type(ParamType t) {
  switch (t) {
    case ParamType::kInt32: return ImGuiDataType_S32;
    case ParamType::kUInt32: return ImGuiDataType_U32;
    case ParamType::kInt64: return ImGuiDataType_S64;
    case ParamType::kUInt64: return ImGuiDataType_U64;
    case ParamType::kFloat: return ImGuiDataType_Float;
    case ParamType::kDouble: return ImGuiDataType_Double;
    default: return ImGuiDataType_Float;
  }
}

std::size_t type_size(ParamType t) {
  switch (t) {
    case ParamType::kInt32: case ParamType::kUInt32: case ParamType::kFloat: return 4;
    case ParamType::kInt64: case ParamType::kUInt64: case ParamType::kDouble: return 8;
    default: return 4;
  }
}

// Writes a value of the widget's storage back as set_string text.
std::string component_text(ParamType t, const unsigned char* p) {
  switch (t) {
    case ParamType::kInt32: { std::int32_t v; std::memcpy(&v, p, 4); return fmt::format("{}", v); }
    case ParamType::kUInt32: { std::uint32_t v; std::memcpy(&v, p, 4); return fmt::format("{}", v); }
    case ParamType::kInt64: { std::int64_t v; std::memcpy(&v, p, 8); return fmt::format("{}", v); }
    case ParamType::kUInt64: { std::uint64_t v; std::memcpy(&v, p, 8); return fmt::format("{}", v); }
    case ParamType::kFloat: { float v; std::memcpy(&v, p, 4); return fmt::format("{}", v); }
    case ParamType::kDouble: { double v; std::memcpy(&v, p, 8); return fmt::format("{}", v); }
    default: return "";
  }
}

// Bounds in the widget's type (clamped to what the type holds).
template <class T>
void bounds_as(const ParamInfo& info, unsigned char* lo, unsigned char* hi) {
  const double min_t = static_cast<double>(std::numeric_limits<T>::lowest());
  const double max_t = static_cast<double>(std::numeric_limits<T>::max());
  const T a = static_cast<T>(std::clamp(info.min, min_t, max_t));
  const T b = static_cast<T>(std::clamp(info.max, min_t, max_t));
  std::memcpy(lo, &a, sizeof(T));
  std::memcpy(hi, &b, sizeof(T));
}

void bounds(ParamType t, const ParamInfo& info, unsigned char* lo, unsigned char* hi) {
  switch (t) {
    case ParamType::kInt32: bounds_as<std::int32_t>(info, lo, hi); break;
    case ParamType::kUInt32: bounds_as<std::uint32_t>(info, lo, hi); break;
    case ParamType::kInt64: bounds_as<std::int64_t>(info, lo, hi); break;
    case ParamType::kUInt64: bounds_as<std::uint64_t>(info, lo, hi); break;
    case ParamType::kFloat: bounds_as<float>(info, lo, hi); break;
    case ParamType::kDouble: bounds_as<double>(info, lo, hi); break;
    default: break;
  }
}

bool is_colour(const ParamDescriptor& p) {
  if (p.ref.type != ParamType::kFloat || (p.ref.components != 3 && p.ref.components != 4)) return false;
  const std::string unit = p.info.unit;
  return unit.find("RGB") != std::string::npos || p.path.find("color") != std::string::npos ||
         p.path.find("colour") != std::string::npos;
}

void tooltip(const ParamDescriptor& p) {
  if (!ImGui::IsItemHovered()) return;
  ImGui::BeginTooltip();
  ImGui::TextUnformatted(p.path.c_str());
  if (p.info.help[0]) ImGui::TextUnformatted(p.info.help);
  std::string facts = p.type_name();
  if (p.info.unit[0]) facts += fmt::format(", {}", p.info.unit);
  if (std::isfinite(p.info.min) || std::isfinite(p.info.max)) facts += fmt::format(", range [{}, {}]", p.info.min, p.info.max);
  if (p.info.rebuild != Rebuild::kNone) facts += fmt::format(", changing it rebuilds: {}", to_string(p.info.rebuild));
  ImGui::TextDisabled("%s", facts.c_str());
  ImGui::EndTooltip();
}

}  // namespace

ParamWidgetResult param_widget(const ParamDescriptor& p, const char* label) {
  ParamWidgetResult r;
  ImGui::PushID(p.path.c_str());
  bool changed = false;
  std::string text;
  switch (p.ref.type) {
    case ParamType::kBool: {
      bool v = *static_cast<const bool*>(p.ref.ptr);
      if (ImGui::Checkbox(label, &v)) {
        changed = true;
        text = v ? "true" : "false";
      }
      break;
    }
    case ParamType::kEnum: {
      const EnumTable& table = *p.ref.enum_table;
      const std::int64_t current = table.get(p.ref.ptr);
      const char* name = table.name_of(current);
      if (ImGui::BeginCombo(label, name ? name : "?")) {
        for (const auto& [value, entry] : table.entries) {
          if (ImGui::Selectable(entry.c_str(), value == current) && value != current) {
            changed = true;
            text = entry;
          }
        }
        ImGui::EndCombo();
      }
      break;
    }
    case ParamType::kString: {
      const std::string& v = *static_cast<const std::string*>(p.ref.ptr);
      char buffer[512];
      std::snprintf(buffer, sizeof(buffer), "%s", v.c_str());
      if (ImGui::InputText(label, buffer, sizeof(buffer), ImGuiInputTextFlags_EnterReturnsTrue) && v != buffer) {
        changed = true;
        text = buffer;
      }
      break;
    }
    default: {
      const std::size_t size = type_size(p.ref.type);
      const int n = p.ref.components;
      unsigned char value[32];
      std::memcpy(value, p.ref.ptr, size * static_cast<std::size_t>(n));
      if (is_colour(p)) {
        changed = n == 3 ? ImGui::ColorEdit3(label, reinterpret_cast<float*>(value), ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR)
                         : ImGui::ColorEdit4(label, reinterpret_cast<float*>(value), ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR);
      } else {
        unsigned char lo[8] = {}, hi[8] = {};
        bounds(p.ref.type, p.info, lo, hi);
        const bool bounded = std::isfinite(p.info.min) && std::isfinite(p.info.max) && p.info.max - p.info.min <= 1.0e7 &&
                             !(p.info.log_scale && p.info.min <= 0.0);
        const ImGuiDataType type = data_type(p.ref.type);
        const bool integer = p.ref.type != ParamType::kFloat && p.ref.type != ParamType::kDouble;
        const char* format = integer ? nullptr : "%.4g";
        if (bounded && n == 1) {
          changed = ImGui::SliderScalar(label, type, value, lo, hi, format,
                                        p.info.log_scale ? ImGuiSliderFlags_Logarithmic : ImGuiSliderFlags_None);
        } else {
          double magnitude = 0.0;
          if (p.ref.type == ParamType::kFloat) { float f; std::memcpy(&f, value, 4); magnitude = std::fabs(f); }
          if (p.ref.type == ParamType::kDouble) { double d; std::memcpy(&d, value, 8); magnitude = std::fabs(d); }
          const float speed = p.info.step > 0.0 ? static_cast<float>(p.info.step)
                              : integer        ? 0.2f
                                               : static_cast<float>(std::max(0.01 * magnitude, 1e-3));
          changed = ImGui::DragScalarN(label, type, value, n, speed, std::isfinite(p.info.min) ? lo : nullptr,
                                       std::isfinite(p.info.max) ? hi : nullptr, format,
                                       p.info.log_scale ? ImGuiSliderFlags_Logarithmic : ImGuiSliderFlags_None);
        }
      }
      if (changed) {
        for (int c = 0; c < n; ++c) {
          text += (c ? "," : "") + component_text(p.ref.type, value + static_cast<std::size_t>(c) * size);
        }
      }
      break;
    }
  }
  tooltip(p);
  if (changed) {
    r.new_text = text;
    r.continuing = ImGui::IsItemActive() && !ImGui::IsItemActivated();
  }
  ImGui::PopID();
  return r;
}

}  // namespace sylva::editor

#pragma once
// Dear ImGui widgets generated from parameter descriptors (DESIGN.md §2: no module hand-writes
// its UI). Each widget edits a copy of the value; a change comes back as the text that
// ParamDescriptor::set_string accepts, so the caller applies it through the editor session
// (validated, undoable) instead of writing through the descriptor.
//
//   bool -> checkbox; enum -> combo of its names; numbers -> slider when both bounds are finite
//   (logarithmic when log_scale), drag otherwise (speed from `step`); vec3/vec4 whose unit or
//   name says colour -> colour edit; other vectors -> drag per component; strings -> text input.
//   The tooltip shows help, unit, range and what a change rebuilds.

#include <sylva/core/params.hpp>

#include <optional>
#include <string>

namespace sylva::editor {

struct ParamWidgetResult {
  std::optional<std::string> new_text;  // set when the user changed the value this frame
  bool continuing = false;              // the change continues a drag begun in an earlier frame
};

// `label` is what is shown (usually the last path segment).
ParamWidgetResult param_widget(const ParamDescriptor& param, const char* label);

}  // namespace sylva::editor

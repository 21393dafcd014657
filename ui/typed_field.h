// Typed number fields that refuse what they cannot take. Dear ImGui's drag fields keep a number
// typed with Ctrl+click as typed, outside the range the drag itself keeps to (-1 kg, a 0 m box,
// 1e999); a body or a view built from it then fails far from the field. These keep the old value
// and say why in one line, in the style of every bad input (docs/sandbox.md, "Bad input").
//
// Needs: Dear ImGui, inside a window or menu.
#pragma once

#include <string>

namespace cablelab::ui {

/// ImGui::DragFloat("label", v, speed, lo, hi, format) whose typed value must be a number from
/// `lo` to `hi`: anything else leaves `*v` as it was, sets `*complaint` to
/// "SOURCE: LABEL: must be a number from LO to HI (got VALUE); it stays OLD" and returns false.
bool typedDrag(const char* source, const char* label, float* v, float speed, float lo, float hi,
               const char* format, std::string* complaint);

/// The same for a pair (ImGui::DragFloat2): both typed values must be in range.
bool typedDrag2(const char* source, const char* label, float v[2], float speed, float lo, float hi,
                const char* format, std::string* complaint);

/// The line typedDrag shows for `got` typed into LABEL of SOURCE (range lo..hi, kept `old`).
std::string typedRangeComplaint(const char* source, const char* label, float lo, float hi,
                                float got, float old);

}  // namespace cablelab::ui

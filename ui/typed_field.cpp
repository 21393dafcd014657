#include "ui/typed_field.h"

#include <imgui.h>

#include <cmath>
#include <cstdio>

namespace cablelab::ui {
namespace {

std::string typedNumberText(float v) {
  if (std::isnan(v)) return "not a number";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", static_cast<double>(v));
  return buf;
}

bool typedInRange(float v, float lo, float hi) {
  return std::isfinite(v) && v >= lo && v <= hi;
}

}  // namespace

std::string typedRangeComplaint(const char* source, const char* label, float lo, float hi,
                                float got, float old) {
  return std::string(source) + ": " + label + ": must be a number from " + typedNumberText(lo) +
         " to " + typedNumberText(hi) + " (got " + typedNumberText(got) + "); it stays " +
         typedNumberText(old);
}

bool typedDrag(const char* source, const char* label, float* v, float speed, float lo, float hi,
               const char* format, std::string* complaint) {
  float typed = *v;
  if (!ImGui::DragFloat(label, &typed, speed, lo, hi, format)) return false;
  if (!typedInRange(typed, lo, hi)) {
    *complaint = typedRangeComplaint(source, label, lo, hi, typed, *v);
    return false;
  }
  *v = typed;
  return true;
}

bool typedDrag2(const char* source, const char* label, float v[2], float speed, float lo, float hi,
                const char* format, std::string* complaint) {
  float typed[2] = {v[0], v[1]};
  if (!ImGui::DragFloat2(label, typed, speed, lo, hi, format)) return false;
  for (int k = 0; k < 2; ++k)
    if (!typedInRange(typed[k], lo, hi)) {
      *complaint = typedRangeComplaint(source, label, lo, hi, typed[k], v[k]);
      return false;
    }
  v[0] = typed[0];
  v[1] = typed[1];
  return true;
}

}  // namespace cablelab::ui

#include "ui/plain_words.h"

#include <cmath>
#include <cstdio>

namespace cablelab::ui {
namespace {

/// The first quoted name after `prefix` in `text` ("cable 'rope': ..." -> rope), empty if none.
std::string quotedAfter(const std::string& text, const std::string& prefix) {
  const size_t at = text.find(prefix + "'");
  if (at == std::string::npos) return "";
  const size_t from = at + prefix.size() + 1, to = text.find('\'', from);
  return to == std::string::npos ? "" : text.substr(from, to - from);
}

}  // namespace

std::string plainBanner(const std::string& warning, const UserAction& action) {
  if (action.kind == UserAction::Kind::None) return "";
  // A rigid cable left longer than its rest length (World::reportOverstretch): the only guard a
  // user's pull or edit explains and can undo.
  const bool overstretched = warning.find("longer than its rest length") != std::string::npos;
  if (!overstretched) return "";
  const std::string cable = quotedAfter(warning, "cable ");
  const std::string which = cable.empty() ? "a cable" : "the cable '" + cable + "'";
  if (action.kind == UserAction::Kind::Drag)
    return "You pulled '" + action.body + "' harder than " + which +
           " can hold, so it stretched for a moment. Let go and it pulls back; a smaller drag "
           "limit (View) keeps it taut.";
  return "After your change " + which +
         " is longer than it may be; it pulls back as the scene runs. Undo the change to keep "
         "the old length.";
}

std::string energyReadout(double joules) {
  // Rounding left over from summing kinetic and potential energies of order 1..1e3 J.
  constexpr double kNoise = 1e-9;  // J
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", std::abs(joules) < kNoise ? 0.0 : joules);
  return text;
}

}  // namespace cablelab::ui

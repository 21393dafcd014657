// The parameter settings the built-in scenes' descriptions invite a user to try ("try --set
// NAME=VALUE"), one World each: issue 36 item 7 asks that none steps more than 3x slower than
// its scene's defaults. Shared by the engine test that bounds their work and the benchmark that
// times them (tests/bench/settings_bench.cpp).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace cablelab::test {

struct ListedSetting {
  std::string scene;
  std::vector<std::pair<std::string, double>> set;  // empty: the defaults
};

inline std::string settingName(const ListedSetting& s) {
  std::string name = s.scene;
  for (const auto& [key, value] : s.set) name += " " + key + "=" + std::to_string(value);
  return name;
}

// Each scene's "try" list, in its description's order (m1=m2 of the wheel: m1 at m2's default).
inline const std::vector<ListedSetting>& listedSettings() {
  static const std::vector<ListedSetting> settings = {
      {"capstan", {{"m_load", 6.0}}},
      {"capstan", {{"mu", 0.0}}},
      {"capstan", {{"turns", 1.75}}},
      {"tackle", {{"m_effort", 1.0}}},
      {"tackle", {{"m_effort", 0.5}}},
      {"wheel", {{"I", 0.0}}},
      {"wheel", {{"m1", 1.0}}},
      {"winch", {{"omega", -2.0}}},
      {"winch", {{"omega", 0.0}}},
      {"winch", {{"r", 0.2}}},
      // Not in a description: a load ten times the default slides onto the hold weight and
      // rests with it at the drum, the rope at the capstan ratio (6.7 iterations a step before
      // the solve merged its spans from the start, docs/wheels.md).
      {"capstan", {{"m_load", 30.0}}},
      // Not in a description: a light load rises to the top sheave and rests there from 1.5 s,
      // where the defaults still move until 3.5 s (3.2x their step time before a body resting
      // at its pulley kept its impulses, docs/floors.md).
      {"tackle", {{"m_load", 0.8}}},
  };
  return settings;
}

}  // namespace cablelab::test

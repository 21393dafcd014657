// Small helpers shared by the subcommands: value checks, output files, medians.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/progress.h"  // every long command draws one
#include "engine/core/error.h"
#include "engine/core/file_input.h"
#include "engine/core/parse.h"

namespace cablelab::app {

/// A bad command-line value: "command line: --dt: must be in (0, 1] s (got 0)".
[[noreturn]] inline void badOption(const std::string& option, const std::string& what) {
  throw InputError(kCommandLine, option, what);
}

/// Throws unless lo <= v <= hi and finite.
inline void requireFinite(double v, const std::string& option, double lo, double hi) {
  requireInRange(v, kCommandLine, option, lo, hi);
}

/// Fails at once, before a long run, if an output file given by `option` cannot be written.
inline void requireOutputFile(const std::string& path, const std::string& option) {
  if (!path.empty()) requireWritable(path, option);
}

inline double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

}  // namespace cablelab::app

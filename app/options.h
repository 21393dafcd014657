// Small helpers shared by the subcommands: value checks, output files, medians, progress.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

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

/// Prints "label: 42% (eta 3 s)" on stderr at most twice a second, only for runs longer than 2 s.
class Progress {
 public:
  Progress(std::string label, long total)
      : label_(std::move(label)), total_(total), start_(Clock::now()) {}
  void update(long done) {
    const auto now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    if (elapsed < 2.0 || std::chrono::duration<double>(now - last_).count() < 0.5 || total_ <= 0)
      return;
    last_ = now;
    const double share = static_cast<double>(done) / total_;
    std::fprintf(stderr, "\r%s: %3.0f%% (eta %.0f s)   ", label_.c_str(), 100 * share,
                 elapsed * (1 - share) / std::max(share, 1e-9));
    printed_ = true;
  }
  void done() {
    if (printed_)
      std::fprintf(stderr, "\r%s: done in %.1f s        \n", label_.c_str(),
                   std::chrono::duration<double>(Clock::now() - start_).count());
  }

 private:
  using Clock = std::chrono::steady_clock;
  std::string label_;
  long total_;
  Clock::time_point start_, last_;
  bool printed_ = false;
};

}  // namespace cablelab::app

#include "app/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace cablelab::app {

namespace {
constexpr double kFirstDrawAfter = 0.5;  // s: quick commands never flash a bar
constexpr double kRedrawEvery = 0.1;     // s
constexpr int kBarWidth = 30;            // characters
}  // namespace

Progress::Progress(std::string label, long total)
    : label_(std::move(label)),
      total_(std::max(total, 1L)),
      terminal_(isatty(fileno(stderr)) != 0),
      start_(Clock::now()) {}

Progress::~Progress() {
  if (shown_ && !finished_) std::fputc('\n', stderr);
}

void Progress::update(long done, const std::string& note) {
  if (!terminal_) return;
  if (!note.empty()) note_ = note;
  const auto now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (elapsed < kFirstDrawAfter) return;
  if (shown_ && std::chrono::duration<double>(now - lastDraw_).count() < kRedrawEvery) return;
  lastDraw_ = now;
  const double share = std::clamp(static_cast<double>(done) / total_, 0.0, 1.0);
  char eta[40] = "";
  if (share > 0) std::snprintf(eta, sizeof eta, "  eta %.0f s", elapsed * (1 - share) / share);
  draw(done, eta);
}

void Progress::done() {
  if (shown_ && !finished_) {
    char took[40];
    std::snprintf(took, sizeof took, "  %.1f s",
                  std::chrono::duration<double>(Clock::now() - start_).count());
    note_.clear();
    draw(total_, took);
    std::fputc('\n', stderr);
  }
  finished_ = true;
}

void Progress::draw(long done, const std::string& tail) {
  const double share = std::clamp(static_cast<double>(done) / total_, 0.0, 1.0);
  const int filled = static_cast<int>(share * kBarWidth);
  std::string bar(static_cast<size_t>(filled), '#');
  bar.resize(kBarWidth, '-');
  // "\r" back to the line's start, "\x1b[K" clears what a longer earlier line left.
  const int percent = static_cast<int>(share * 100);  // 100 only when all is done
  std::fprintf(stderr, "\r%s [%s] %3d%%  %ld/%ld%s%s%s\x1b[K", label_.c_str(), bar.c_str(), percent,
               std::min(done, total_), total_, tail.c_str(), note_.empty() ? "" : "  ",
               note_.c_str());
  std::fflush(stderr);
  shown_ = true;
}

}  // namespace cablelab::app

#include "ui/recorder.h"

#include <cmath>
#include <cstdio>

namespace cablelab::ui {
namespace {
constexpr size_t kMaxQueued = 8;  // frames waiting for the encoder before add() blocks
}

std::vector<std::string> clipNotes(const std::string& name, double time) {
  char text[48];
  std::snprintf(text, sizeof text, "t = %.2f s", time);
  return {name, text};
}

std::vector<std::string> clipNotes(const World& world, const std::string& fallbackName) {
  return clipNotes(world.scene().name.empty() ? fallbackName : world.scene().name, world.time());
}

Recorder::~Recorder() {
  if (recording()) stop();
}

void Recorder::start(const std::string& path, int width, int height, double fps, double now) {
  if (recording()) stop();
  clipSize(clipFormatFor(path), width, height);
  writer_ = openClip(path, width, height, 1 / fps);
  path_ = path;
  error_.clear();
  failed_ = false;
  width_ = width, height_ = height, queued_ = 0;
  frameSeconds_ = 1 / fps;
  next_ = now;
  finishing_ = false;
  worker_ = std::thread([this] { work(); });
}

void Recorder::follow(double now) {
  if (recording() && now < next_ - frameSeconds_ - 1e-9) next_ = now;
}

bool Recorder::due(double now) const {
  return recording() && now >= next_ - 1e-9;
}

void Recorder::add(Image frame, double now) {
  if (!recording()) return;
  // Skip ahead by whole frames: a fast-forwarded stretch keeps the simulated frame rate.
  next_ += frameSeconds_ * std::max(1.0, std::floor((now - next_) / frameSeconds_ + 1));
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return queue_.size() < kMaxQueued; });
  queue_.push_back(std::move(frame));
  ++queued_;
  changed_.notify_all();
}

void Recorder::work() {
  for (;;) {
    Image frame;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return finishing_ || !queue_.empty(); });
      if (queue_.empty()) return;
      frame = std::move(queue_.front());
      queue_.pop_front();
      changed_.notify_all();
    }
    try {
      writer_->add(frame);
    } catch (const std::exception& e) {
      std::lock_guard lock(mutex_);
      if (error_.empty()) error_ = e.what();
    }
  }
}

std::string Recorder::stop() {
  if (!recording()) return "not recording";
  {
    std::lock_guard lock(mutex_);
    finishing_ = true;
    changed_.notify_all();
  }
  worker_.join();
  try {
    writer_->close();
  } catch (const std::exception& e) {
    if (error_.empty()) error_ = e.what();
  }
  const int frames = writer_->frames();
  writer_.reset();
  failed_ = !error_.empty();
  if (failed_) return "recording failed: " + error_;
  char text[512];
  std::snprintf(text, sizeof text, "recorded %d frames (%.2f s) to %s", frames,
                frames * frameSeconds_, path_.c_str());
  return text;
}

}  // namespace cablelab::ui

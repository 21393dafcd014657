// Recorder: the sandbox's "Record GIF" button. Frames captured from the window are encoded by a
// worker thread (giflib's quantiser takes ~10 ms per 1280x720 frame, too long for the frame
// loop), one frame per 1/fps s of *simulated* time, so a recording plays at the real speed of
// the simulation whatever the frame rate of the window and whatever the speed setting.
//
// Needs: ui/gif.h (giflib), std::thread. No SDL, no GL: the caller captures the pixels.
#pragma once

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "ui/gif.h"
#include "ui/image.h"

namespace cablelab::ui {

class Recorder {
 public:
  Recorder() = default;
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  /// Starts a width x height recording into `path` at `fps` frames per simulated second,
  /// beginning at simulated time `now`; throws std::runtime_error if the file cannot be made.
  void start(const std::string& path, int width, int height, double fps, double now);
  /// True while recording and a frame is due at simulated time `now` (then call add()).
  bool due(double now) const;
  /// Queues a frame for simulated time `now` (cropped by the caller to the recording's size).
  void add(Image frame, double now);
  /// Finishes the file (waits for the queue); returns a one-line summary or the error.
  std::string stop();

  bool recording() const { return writer_ != nullptr; }
  int frames() const { return queued_; }
  int width() const { return width_; }
  int height() const { return height_; }
  const std::string& path() const { return path_; }

 private:
  void work();

  std::unique_ptr<GifWriter> writer_;
  std::string path_, error_;
  int width_ = 0, height_ = 0, queued_ = 0;
  double frameSeconds_ = 1.0 / 30, next_ = 0;
  std::thread worker_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Image> queue_;
  bool finishing_ = false;
};

}  // namespace cablelab::ui

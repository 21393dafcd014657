// Recorder: one clip recorder for the sandbox's Record button and `cablelab record`. Frames are
// encoded by a worker thread (an encoder takes milliseconds per frame, too long for the window's
// frame loop), one frame per 1/fps s of *simulated* time, so a clip plays at the real speed of
// the simulation whatever the frame rate of the window and whatever the speed setting. The file
// name picks the format (ui/clip.h: .mp4 where FFmpeg is built in, else GIF); clipNotes() is
// what every clip's frame shows over the scene, in the window and headless alike.
//
// Needs: ui/clip.h, the engine's World (for the notes), std::thread. No SDL, no GL: the caller
// captures or renders the pixels.
#pragma once

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include <vector>

#include "engine/dynamics/world.h"
#include "ui/clip.h"
#include "ui/image.h"

namespace cablelab::ui {

/// The lines a clip's frames carry in their top-left corner: the scene's title `name` and the
/// simulated time `time` (s), "t = 1.23 s".
std::vector<std::string> clipNotes(const std::string& name, double time);
/// The same with the scene's own name (else `fallbackName`) and the world's time.
std::vector<std::string> clipNotes(const World& world, const std::string& fallbackName);

class Recorder {
 public:
  Recorder() = default;
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  /// Starts a width x height recording into `path` at `fps` frames per simulated second,
  /// beginning at simulated time `now`; throws std::runtime_error if the file cannot be made.
  /// The clip's size may be a pixel less per side than asked (ui/clip.h, clipSize): crop the
  /// frames to width() x height().
  void start(const std::string& path, int width, int height, double fps, double now);
  /// The simulated clock went back (a reset, a demo starting again, a rewind): the clip goes on
  /// from `now`. Call every frame before due().
  void follow(double now);
  /// True while recording and a frame is due at simulated time `now` (then call add()).
  bool due(double now) const;
  /// Queues a frame for simulated time `now` (cropped by the caller to the recording's size).
  void add(Image frame, double now);
  /// Finishes the file (waits for the queue); returns a one-line summary or the error
  /// ("recording failed: ...", then failed() is true).
  std::string stop();
  bool failed() const { return failed_; }

  bool recording() const { return writer_ != nullptr; }
  int frames() const { return queued_; }
  /// The clip's length so far (s of simulated time, as it plays).
  double seconds() const { return queued_ * frameSeconds_; }
  int width() const { return width_; }
  int height() const { return height_; }
  const std::string& path() const { return path_; }

 private:
  void work();

  std::unique_ptr<ClipWriter> writer_;
  std::string path_, error_;
  int width_ = 0, height_ = 0, queued_ = 0;
  double frameSeconds_ = 1.0 / 30, next_ = 0;
  std::thread worker_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Image> queue_;
  bool finishing_ = false;
  bool failed_ = false;
};

}  // namespace cablelab::ui

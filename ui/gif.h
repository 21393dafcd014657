// GifWriter: an animated GIF written frame by frame with giflib (Debian's libgif), small
// because it uses what GIF does well: one global palette of 127 colours chosen from the first
// two frames (ui/gif_palette.h), and each later frame only the rectangle of the pixels that changed
// visibly since the frame before (by more than a few levels), every other pixel written as the
// transparent index ("do not dispose": the viewer keeps the previous frame under them). Long
// transparent runs are what LZW compresses best, and no dithering changes pixels that did not
// move. What is left is the moving edges and the first frame (docs/sandbox.md, Clips).
//
// Needs: giflib only (no GL), ui/image.h. Frames must all have the writer's size. The delay
// of each frame is in GIF's centiseconds; frameSeconds that are not a whole number of them
// are spread (3, 3, 4, 3, 3, 4 cs for 30 fps) so the animation keeps the right average rate.
// The file loops forever (the NETSCAPE2.0 extension browsers understand).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ui/clip.h"
#include "ui/image.h"

struct GifFileType;

namespace cablelab::ui {

class GifPalette;

class GifWriter : public ClipWriter {
 public:
  /// Opens `path` for a width x height animation at one frame per `frameSeconds`; throws
  /// std::runtime_error naming the path if it cannot be written.
  GifWriter(const std::string& path, int width, int height, double frameSeconds);
  ~GifWriter() override;  ///< closes the file if close() was not called (errors then ignored)
  GifWriter(const GifWriter&) = delete;
  GifWriter& operator=(const GifWriter&) = delete;

  /// Appends one frame (its size must be the writer's); throws std::runtime_error on failure.
  void add(const Image& frame) override;
  /// Finishes the file; throws std::runtime_error naming the path on failure.
  void close() override;

  int frames() const override { return frames_; }
  const std::string& path() const { return path_; }

 private:
  /// The screen descriptor with the global palette (from `frames`, or one colour without a
  /// frame) and the looping extension.
  void writeHeader(const std::vector<const Image*>& frames);
  /// Writes one frame: what changed since the frame before.
  void writeFrame(const Image& frame);

  std::string path_;
  GifFileType* gif_ = nullptr;
  int width_, height_;
  double frameSeconds_;
  double written_ = 0;           ///< centiseconds of delay written so far
  int frames_ = 0, stored_ = 0;  ///< frames added, frames written
  /// The first frame, held until the second: the palette is chosen from both (the second has
  /// the colours of the cables' first tensions, which a scene at rest lacks).
  std::unique_ptr<Image> first_;
  std::unique_ptr<GifPalette> palette_;  ///< from the first two frames
  std::vector<std::uint8_t> shown_;      ///< width x height: the index a viewer shows now
};

/// One decoded GIF (for tests and tools): every frame as an RGBA image (frames composed as a
/// viewer shows them: each covers the previous one) and its delay in centiseconds.
struct GifAnimation {
  std::vector<Image> frames;
  std::vector<int> delays;
  bool loops = false;  ///< has the NETSCAPE2.0 looping extension
};

/// Reads a GIF with giflib; throws std::runtime_error naming the path on failure.
GifAnimation readGif(const std::string& path);

}  // namespace cablelab::ui

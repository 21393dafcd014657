// Clips: an animation written frame by frame, in the format its file name asks for. `.mp4` is
// H.264 through FFmpeg's libraries (ui/mp4.h) where the build found them; `.gif` is giflib
// (ui/gif.h). The sandbox's recorder and `cablelab record` both open their files here.
//
// Needs: ui/image.h only; the MP4 half is compiled in when CMake finds libavcodec, libavformat,
// libswscale and libavutil with pkg-config (CABLELAB_HAVE_MP4).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "ui/image.h"

namespace cablelab::ui {

/// One animation being written: frames of one size, one every frameSeconds.
class ClipWriter {
 public:
  virtual ~ClipWriter() = default;
  /// Appends one frame of the clip's size; throws std::runtime_error on failure.
  virtual void add(const Image& frame) = 0;
  /// Finishes the file; throws std::runtime_error naming the path on failure.
  virtual void close() = 0;
  virtual int frames() const = 0;
};

enum class ClipFormat { Gif, Mp4 };

/// The format a file name asks for: MP4 for ".mp4" (any letter case), GIF for any other name
/// (as `cablelab record` has always written).
ClipFormat clipFormatFor(const std::string& path);

/// True when this build writes MP4 (FFmpeg's libraries were found).
bool mp4Available();

/// The sentence shown when an MP4 is asked for and this build has no FFmpeg.
extern const char* const kNoMp4;

/// The frame rate a window clip gets unless the user picks one: MP4 30 fps; GIF 10 fps, the
/// rate screen recorders give GIF animations (a GIF stores every frame's moving edges again:
/// 4.7 s of the hexagon turning in a 1280x720 window are 346 kB at 15 fps, 245 kB at 10 fps;
/// the time stamp is each frame's own simulated time). A GIF is the fallback: MP4 keeps 30.
double defaultClipFps(ClipFormat format);

/// The largest frame rate a format plays back faithfully (GIF: whole centiseconds of delay,
/// viewers slow frames under 2 cs down to 10 cs).
double maxClipFps(ClipFormat format);

/// The clip size a format stores for a width x height view: H.264 in 4:2:0 needs even sides,
/// so an MP4 drops the last odd column and row.
void clipSize(ClipFormat format, int& width, int& height);

/// Opens `path` for a width x height animation (sizes as clipSize() leaves them) at one frame
/// per `frameSeconds`; throws std::runtime_error naming the path when it cannot, and kNoMp4
/// for an MP4 in a build without FFmpeg.
std::unique_ptr<ClipWriter> openClip(const std::string& path, int width, int height,
                                     double frameSeconds);

/// A decoded clip (for tests and tools): every frame as an RGBA image and its start time (s).
struct DecodedClip {
  std::vector<Image> frames;
  std::vector<double> times;
};

/// Reads a GIF or an MP4 back; throws std::runtime_error naming the path on failure.
DecodedClip readClip(const std::string& path);

}  // namespace cablelab::ui

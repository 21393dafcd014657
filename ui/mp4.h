// Mp4Writer: an H.264 MP4 written frame by frame through FFmpeg's libraries (Debian's
// libavcodec with libx264, libavformat, libswscale), and the reader the tests decode it with.
//
// Needs: FFmpeg 5.1 (compiled only when CMake finds it: CABLELAB_HAVE_MP4), ui/clip.h. Frames
// are RGBA, converted to 4:2:0 YUV (BT.601, limited range, tagged so players convert back the
// same way); sides must be even (clipSize()). Quality: x264's constant-quality mode at CRF 23
// tuned for animation (flat colours, sharp edges), which keeps text and one-pixel lines
// readable; the index sits at the front of the file ("faststart") so that browsers start
// playing before the whole file is loaded.
#pragma once

#include <string>

#include "ui/clip.h"

struct AVFormatContext;
struct AVCodecContext;
struct AVStream;
struct AVFrame;
struct AVPacket;
struct SwsContext;

namespace cablelab::ui {

class Mp4Writer : public ClipWriter {
 public:
  /// Opens `path` for a width x height video (even sides) at one frame per `frameSeconds`;
  /// throws std::runtime_error naming the path when it cannot.
  Mp4Writer(const std::string& path, int width, int height, double frameSeconds);
  ~Mp4Writer() override;  ///< closes the file if close() was not called (errors then ignored)
  Mp4Writer(const Mp4Writer&) = delete;
  Mp4Writer& operator=(const Mp4Writer&) = delete;

  void add(const Image& frame) override;
  void close() override;
  int frames() const override { return frames_; }

 private:
  void encode(const AVFrame* frame);  ///< sends one frame (nullptr: flush), writes its packets
  void release();

  std::string path_;
  int width_, height_;
  int frames_ = 0;
  AVFormatContext* format_ = nullptr;
  AVCodecContext* codec_ = nullptr;
  AVStream* stream_ = nullptr;
  AVFrame* frame_ = nullptr;
  AVPacket* packet_ = nullptr;
  SwsContext* convert_ = nullptr;
  bool headerWritten_ = false;
};

/// Decodes every frame of an MP4 (any codec FFmpeg reads) to RGBA with its time (s).
DecodedClip readMp4(const std::string& path);

}  // namespace cablelab::ui

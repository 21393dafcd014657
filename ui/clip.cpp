#include "ui/clip.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <stdexcept>

#include "ui/gif.h"
#ifdef CABLELAB_HAVE_MP4
#include "ui/mp4.h"
#endif

namespace cablelab::ui {

const char* const kNoMp4 =
    "this build cannot write MP4 (FFmpeg's libavcodec, libavformat and libswscale were not found "
    "when it was built: install them with scripts/deps.sh and rebuild, or record a .gif)";

ClipFormat clipFormatFor(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".mp4" ? ClipFormat::Mp4 : ClipFormat::Gif;
}

bool mp4Available() {
#ifdef CABLELAB_HAVE_MP4
  return true;
#else
  return false;
#endif
}

double defaultClipFps(ClipFormat format) {
  return format == ClipFormat::Gif ? 10 : 30;
}

double maxClipFps(ClipFormat format) {
  return format == ClipFormat::Gif ? 50 : 120;
}

void clipSize(ClipFormat format, int& width, int& height) {
  if (format != ClipFormat::Mp4) return;
  width -= width % 2;
  height -= height % 2;
}

std::unique_ptr<ClipWriter> openClip(const std::string& path, int width, int height,
                                     double frameSeconds) {
  if (clipFormatFor(path) == ClipFormat::Gif)
    return std::make_unique<GifWriter>(path, width, height, frameSeconds);
#ifdef CABLELAB_HAVE_MP4
  return std::make_unique<Mp4Writer>(path, width, height, frameSeconds);
#else
  throw std::runtime_error(path + ": " + kNoMp4);
#endif
}

DecodedClip readClip(const std::string& path) {
  if (clipFormatFor(path) == ClipFormat::Mp4) {
#ifdef CABLELAB_HAVE_MP4
    return readMp4(path);
#else
    throw std::runtime_error(path + ": " + kNoMp4);
#endif
  }
  GifAnimation gif = readGif(path);
  DecodedClip clip;
  double t = 0;
  for (size_t k = 0; k < gif.frames.size(); ++k) {
    clip.frames.push_back(std::move(gif.frames[k]));
    clip.times.push_back(t);
    t += gif.delays[k] / 100.0;
  }
  return clip;
}

}  // namespace cablelab::ui

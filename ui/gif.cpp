#include "ui/gif.h"

#include "ui/gif_palette.h"

#include <fcntl.h>
#include <gif_lib.h>
#include <unistd.h>

#include <cerrno>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace cablelab::ui {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what, int code) {
  const char* reason = GifErrorString(code);
  throw std::runtime_error(path + ": " + what + " (" + (reason ? reason : "giflib error") + ")");
}

/// 127 colours and, last, the transparent index ("keep what the frame before showed"): a
/// 128-entry palette makes LZW start from 8-bit codes instead of 9 (8% smaller clips) and
/// still holds the scene's flat fills exactly and its anti-aliasing ramps to a few levels.
constexpr int kPaletteSize = 128;
constexpr int kColours = kPaletteSize - 1;
constexpr std::uint8_t kTransparent = kPaletteSize - 1;

/// A pixel is written again only when what the viewer shows is more than this many levels
/// (of 255, in any channel) from the render and the palette has a nearer colour: a cable whose
/// tension colour drifts a little is not rewritten in every frame.
constexpr int kTolerance = 12;

int channelError(const std::uint8_t* rgb, const GifPalette::Rgb& colour) {
  return std::max(
      {std::abs(rgb[0] - colour[0]), std::abs(rgb[1] - colour[1]), std::abs(rgb[2] - colour[2])});
}

}  // namespace

GifWriter::GifWriter(const std::string& path, int width, int height, double frameSeconds)
    : path_(path), width_(width), height_(height), frameSeconds_(frameSeconds) {
  if (width <= 0 || height <= 0 || width > 65535 || height > 65535)
    throw std::runtime_error(path + ": GIF size must be 1..65535 pixels per side");
  if (!(frameSeconds > 0)) throw std::runtime_error(path + ": frame time must be positive");
  // Opened here rather than by EGifOpenFileName, which creates files readable by their owner
  // only (0600): the umask decides, as for every other output.
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
  if (fd < 0)
    throw std::runtime_error(path + ": cannot write the GIF (" + std::strerror(errno) + ")");
  int error = 0;
  gif_ = EGifOpenFileHandle(fd, &error);  // owns fd from here on, closed by EGifCloseFile
  if (!gif_) {
    ::close(fd);
    fail(path, "cannot write the GIF", error);
  }
  EGifSetGifVersion(gif_, true);  // GIF89a: delays, transparency and looping
  shown_.assign(static_cast<size_t>(width) * height, kTransparent);  // nothing shown yet
}

void GifWriter::writeHeader(const std::vector<const Image*>& frames) {
  GifColorType colours[kPaletteSize];
  std::memset(colours, 0, sizeof colours);
  if (!frames.empty()) {
    palette_ = std::make_unique<GifPalette>(frames, kColours);
    const auto& chosen = palette_->colours();
    for (size_t i = 0; i < chosen.size(); ++i)
      colours[i] = {chosen[i][0], chosen[i][1], chosen[i][2]};
  }
  ColorMapObject* map = GifMakeMapObject(kPaletteSize, colours);
  if (!map) throw std::runtime_error(path_ + ": out of memory for the GIF palette");
  const bool ok = EGifPutScreenDesc(gif_, width_, height_, map->BitsPerPixel, 0, map) != GIF_ERROR;
  GifFreeMapObject(map);
  if (!ok) fail(path_, "cannot write the GIF header", gif_->Error);
  // NETSCAPE2.0 application extension, loop count 0 = forever.
  static const GifByteType kApp[] = "NETSCAPE2.0";
  static const GifByteType kLoop[] = {1, 0, 0};
  if (EGifPutExtensionLeader(gif_, APPLICATION_EXT_FUNC_CODE) == GIF_ERROR ||
      EGifPutExtensionBlock(gif_, 11, kApp) == GIF_ERROR ||
      EGifPutExtensionBlock(gif_, 3, kLoop) == GIF_ERROR ||
      EGifPutExtensionTrailer(gif_) == GIF_ERROR)
    fail(path_, "cannot write the GIF loop extension", gif_->Error);
}

GifWriter::~GifWriter() {
  if (gif_) {
    int error = 0;
    EGifCloseFile(gif_, &error);
  }
}

void GifWriter::add(const Image& frame) {
  if (!gif_) throw std::runtime_error(path_ + ": GIF already closed");
  if (frame.width != width_ || frame.height != height_)
    throw std::runtime_error(path_ + ": frame size " + std::to_string(frame.width) + "x" +
                             std::to_string(frame.height) + " differs from the GIF's");
  ++frames_;
  if (!palette_ && !first_) {
    first_ = std::make_unique<Image>(frame);
    return;
  }
  if (!palette_) {
    writeHeader({first_.get(), &frame});
    writeFrame(*first_);
    first_.reset();
  }
  writeFrame(frame);
}

void GifWriter::writeFrame(const Image& frame) {
  // The frame in palette indices (kTransparent where what is shown is close enough), and the
  // rectangle of the pixels to write.
  const auto& colours = palette_->colours();
  std::vector<std::uint8_t> indices(shown_.size());
  int x0 = width_, y0 = height_, x1 = -1, y1 = -1;
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const size_t i = static_cast<size_t>(y) * width_ + x;
      const std::uint8_t* rgb = frame.pixel(x, y);
      const std::uint8_t index = palette_->indexOf(rgb);
      const bool keep =
          shown_[i] == index || (shown_[i] != kTransparent &&
                                 channelError(rgb, colours[shown_[i]]) <=
                                     std::max(kTolerance, channelError(rgb, colours[index])));
      indices[i] = keep ? kTransparent : index;
      if (!keep)
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  if (x1 < 0) x0 = y0 = x1 = y1 = 0;  // nothing changed: one transparent pixel (no empty frame)
  const int w = x1 - x0 + 1, h = y1 - y0 + 1;
  // Whole centiseconds per frame, spread so that the total stays on frames * frameSeconds.
  const double end = std::round((stored_ + 1) * frameSeconds_ * 100);
  const int delay = static_cast<int>(end - written_);
  written_ = end;
  GraphicsControlBlock gcb{};
  gcb.DisposalMode = DISPOSE_DO_NOT;
  gcb.DelayTime = delay;
  gcb.TransparentColor = kTransparent;
  GifByteType extension[4];
  const size_t length = EGifGCBToExtension(&gcb, extension);
  bool ok = EGifPutExtension(gif_, GRAPHICS_EXT_FUNC_CODE, static_cast<int>(length), extension) !=
                GIF_ERROR &&
            EGifPutImageDesc(gif_, x0, y0, w, h, false, nullptr) != GIF_ERROR;
  std::vector<GifByteType> line(w);
  for (int y = y0; ok && y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const size_t i = static_cast<size_t>(y) * width_ + x;
      line[x - x0] = indices[i];
      if (indices[i] != kTransparent) shown_[i] = indices[i];
    }
    ok = EGifPutLine(gif_, line.data(), w) != GIF_ERROR;
  }
  if (!ok) fail(path_, "cannot write GIF frame " + std::to_string(stored_), gif_->Error);
  ++stored_;
}

void GifWriter::close() {
  if (!gif_) return;
  if (!palette_) {  // no frame or one
    writeHeader(first_ ? std::vector<const Image*>{first_.get()} : std::vector<const Image*>{});
    if (first_) writeFrame(*first_);
    first_.reset();
  }
  int error = 0;
  const int result = EGifCloseFile(gif_, &error);
  gif_ = nullptr;
  if (result == GIF_ERROR) fail(path_, "cannot finish the GIF", error);
}

GifAnimation readGif(const std::string& path) {
  int error = 0;
  GifFileType* gif = DGifOpenFileName(path.c_str(), &error);
  if (!gif) fail(path, "cannot open the GIF", error);
  struct Closer {
    GifFileType* g;
    ~Closer() {
      int e = 0;
      DGifCloseFile(g, &e);
    }
  } closer{gif};
  if (DGifSlurp(gif) == GIF_ERROR) fail(path, "cannot decode the GIF", gif->Error);
  GifAnimation animation;
  Image canvas;
  canvas.width = gif->SWidth;
  canvas.height = gif->SHeight;
  canvas.rgba.assign(static_cast<size_t>(canvas.width) * canvas.height * 4, 255);
  for (int k = 0; k < gif->ImageCount; ++k) {
    const SavedImage& image = gif->SavedImages[k];
    for (int e = 0; e < image.ExtensionBlockCount; ++e) {
      const ExtensionBlock& block = image.ExtensionBlocks[e];
      if (block.Function == APPLICATION_EXT_FUNC_CODE && block.ByteCount == 11 &&
          std::memcmp(block.Bytes, "NETSCAPE2.0", 11) == 0)
        animation.loops = true;
    }
    const GifImageDesc& d = image.ImageDesc;
    const ColorMapObject* map = d.ColorMap ? d.ColorMap : gif->SColorMap;
    if (!map) throw std::runtime_error(path + ": frame " + std::to_string(k) + " has no palette");
    GraphicsControlBlock gcb{};
    gcb.TransparentColor = NO_TRANSPARENT_COLOR;
    DGifSavedExtensionToGCB(gif, k, &gcb);
    for (int y = 0; y < d.Height; ++y)
      for (int x = 0; x < d.Width; ++x) {
        const int cx = d.Left + x, cy = d.Top + y;
        if (cx < 0 || cy < 0 || cx >= canvas.width || cy >= canvas.height) continue;
        const int index = image.RasterBits[static_cast<size_t>(y) * d.Width + x];
        if (index == gcb.TransparentColor || index >= map->ColorCount) continue;
        std::uint8_t* p = canvas.pixel(cx, cy);
        p[0] = map->Colors[index].Red;
        p[1] = map->Colors[index].Green;
        p[2] = map->Colors[index].Blue;
        p[3] = 255;
      }
    animation.frames.push_back(canvas);
    animation.delays.push_back(gcb.DelayTime);
  }
  return animation;
}

}  // namespace cablelab::ui

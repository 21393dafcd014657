#include "ui/mp4.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <stdexcept>

namespace cablelab::ui {
namespace {

[[noreturn]] void videoFailure(const std::string& path, const std::string& what, int code = 0) {
  std::string reason;
  if (code < 0) {
    char text[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(code, text, sizeof text);
    reason = std::string(" (") + text + ")";
  }
  throw std::runtime_error(path + ": " + what + reason);
}

/// Colour tags for BT.601 limited-range YUV: what swscale's defaults produce.
void tagColoursBt601(AVCodecContext* c) {
  c->colorspace = AVCOL_SPC_SMPTE170M;
  c->color_primaries = AVCOL_PRI_SMPTE170M;
  c->color_trc = AVCOL_TRC_SMPTE170M;
  c->color_range = AVCOL_RANGE_MPEG;
}

}  // namespace

Mp4Writer::Mp4Writer(const std::string& path, int width, int height, double frameSeconds)
    : path_(path), width_(width), height_(height) {
  if (width < 2 || height < 2 || width % 2 || height % 2)
    throw std::runtime_error(path + ": an MP4 needs an even width and height (got " +
                             std::to_string(width) + "x" + std::to_string(height) + ")");
  if (!(frameSeconds > 0)) throw std::runtime_error(path + ": frame time must be positive");
  try {
    av_log_set_level(AV_LOG_ERROR);  // x264 prints its settings and statistics otherwise
    int code = avformat_alloc_output_context2(&format_, nullptr, "mp4", path.c_str());
    if (code < 0 || !format_) videoFailure(path, "cannot make an MP4", code);
    const AVCodec* h264 = avcodec_find_encoder_by_name("libx264");
    if (!h264) videoFailure(path, "this FFmpeg has no H.264 encoder (libx264)");
    stream_ = avformat_new_stream(format_, nullptr);
    codec_ = avcodec_alloc_context3(h264);
    frame_ = av_frame_alloc();
    packet_ = av_packet_alloc();
    if (!stream_ || !codec_ || !frame_ || !packet_) videoFailure(path, "out of memory for the MP4");
    const AVRational rate = av_d2q(1 / frameSeconds, 100000);
    codec_->width = width;
    codec_->height = height;
    codec_->pix_fmt = AV_PIX_FMT_YUV420P;
    codec_->time_base = av_inv_q(rate);
    codec_->framerate = rate;
    codec_->thread_count = 2;  // the machine is shared; the encoder keeps up with two
    tagColoursBt601(codec_);
    if (format_->oformat->flags & AVFMT_GLOBALHEADER) codec_->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    AVDictionary* options = nullptr;
    av_dict_set(&options, "preset", "veryfast", 0);
    av_dict_set(&options, "tune", "animation", 0);
    av_dict_set(&options, "crf", "23", 0);
    code = avcodec_open2(codec_, h264, &options);
    av_dict_free(&options);
    if (code < 0) videoFailure(path, "cannot start the H.264 encoder", code);
    code = avcodec_parameters_from_context(stream_->codecpar, codec_);
    if (code < 0) videoFailure(path, "cannot describe the video stream", code);
    stream_->time_base = codec_->time_base;
    stream_->avg_frame_rate = rate;
    code = avio_open(&format_->pb, path.c_str(), AVIO_FLAG_WRITE);
    if (code < 0) videoFailure(path, "cannot write the MP4", code);
    AVDictionary* mux = nullptr;
    av_dict_set(&mux, "movflags", "+faststart", 0);
    code = avformat_write_header(format_, &mux);
    av_dict_free(&mux);
    if (code < 0) videoFailure(path, "cannot write the MP4 header", code);
    headerWritten_ = true;
    frame_->format = codec_->pix_fmt;
    frame_->width = width;
    frame_->height = height;
    code = av_frame_get_buffer(frame_, 0);
    if (code < 0) videoFailure(path, "out of memory for a video frame", code);
    convert_ = sws_getContext(width, height, AV_PIX_FMT_RGBA, width, height, AV_PIX_FMT_YUV420P,
                              SWS_BICUBIC, nullptr, nullptr, nullptr);
    if (!convert_) videoFailure(path, "cannot convert RGBA to YUV");
  } catch (...) {
    release();
    throw;
  }
}

Mp4Writer::~Mp4Writer() {
  try {
    close();
  } catch (const std::exception&) {  // a destructor cannot report: close() does
  }
}

void Mp4Writer::add(const Image& frame) {
  if (!codec_) throw std::runtime_error(path_ + ": MP4 already closed");
  if (frame.width != width_ || frame.height != height_)
    throw std::runtime_error(path_ + ": frame size " + std::to_string(frame.width) + "x" +
                             std::to_string(frame.height) + " differs from the video's");
  int code = av_frame_make_writable(frame_);
  if (code < 0) videoFailure(path_, "cannot reuse the video frame", code);
  const std::uint8_t* source[1] = {frame.rgba.data()};
  const int stride[1] = {4 * width_};
  sws_scale(convert_, source, stride, 0, height_, frame_->data, frame_->linesize);
  frame_->pts = frames_;
  encode(frame_);
  ++frames_;
}

void Mp4Writer::encode(const AVFrame* frame) {
  int code = avcodec_send_frame(codec_, frame);
  if (code < 0) videoFailure(path_, "cannot encode video frame " + std::to_string(frames_), code);
  for (;;) {
    code = avcodec_receive_packet(codec_, packet_);
    if (code == AVERROR(EAGAIN) || code == AVERROR_EOF) return;
    if (code < 0) videoFailure(path_, "cannot encode video frame " + std::to_string(frames_), code);
    av_packet_rescale_ts(packet_, codec_->time_base, stream_->time_base);
    packet_->stream_index = stream_->index;
    code = av_interleaved_write_frame(format_, packet_);  // takes the packet's data
    if (code < 0) videoFailure(path_, "cannot write video frame " + std::to_string(frames_), code);
  }
}

void Mp4Writer::close() {
  if (!codec_) return;
  try {
    encode(nullptr);  // the encoder holds frames back for its look-ahead
    const int code = av_write_trailer(format_);
    if (code < 0) videoFailure(path_, "cannot finish the MP4", code);
  } catch (...) {
    release();
    throw;
  }
  release();
}

void Mp4Writer::release() {
  sws_freeContext(convert_);
  convert_ = nullptr;
  av_frame_free(&frame_);
  av_packet_free(&packet_);
  avcodec_free_context(&codec_);
  if (format_ && format_->pb) avio_closep(&format_->pb);
  avformat_free_context(format_);
  format_ = nullptr;
  stream_ = nullptr;
}

DecodedClip readMp4(const std::string& path) {
  AVFormatContext* format = nullptr;
  int code = avformat_open_input(&format, path.c_str(), nullptr, nullptr);
  if (code < 0) videoFailure(path, "cannot open the video", code);
  AVCodecContext* codec = nullptr;
  AVFrame* frame = av_frame_alloc();
  AVPacket* packet = av_packet_alloc();
  SwsContext* convert = nullptr;
  struct Release {
    AVFormatContext*& f;
    AVCodecContext*& c;
    AVFrame*& fr;
    AVPacket*& p;
    SwsContext*& s;
    ~Release() {
      sws_freeContext(s);
      av_frame_free(&fr);
      av_packet_free(&p);
      avcodec_free_context(&c);
      avformat_close_input(&f);
    }
  } release{format, codec, frame, packet, convert};
  if ((code = avformat_find_stream_info(format, nullptr)) < 0)
    videoFailure(path, "cannot read the video's streams", code);
  const AVCodec* decoder = nullptr;
  const int index = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
  if (index < 0 || !decoder) videoFailure(path, "has no video stream", index);
  const AVStream* stream = format->streams[index];
  codec = avcodec_alloc_context3(decoder);
  if (!codec || !frame || !packet) videoFailure(path, "out of memory");
  avcodec_parameters_to_context(codec, stream->codecpar);
  if ((code = avcodec_open2(codec, decoder, nullptr)) < 0)
    videoFailure(path, "cannot start the decoder", code);

  DecodedClip clip;
  auto receive = [&] {
    while ((code = avcodec_receive_frame(codec, frame)) >= 0) {
      convert = sws_getCachedContext(
          convert, frame->width, frame->height, static_cast<AVPixelFormat>(frame->format),
          frame->width, frame->height, AV_PIX_FMT_RGBA, SWS_BICUBIC, nullptr, nullptr, nullptr);
      if (!convert) videoFailure(path, "cannot convert the video to RGBA");
      Image image;
      image.width = frame->width;
      image.height = frame->height;
      image.rgba.resize(static_cast<size_t>(image.width) * image.height * 4);
      std::uint8_t* target[1] = {image.rgba.data()};
      const int stride[1] = {4 * image.width};
      sws_scale(convert, frame->data, frame->linesize, 0, frame->height, target, stride);
      clip.frames.push_back(std::move(image));
      clip.times.push_back(static_cast<double>(frame->best_effort_timestamp) *
                           av_q2d(stream->time_base));
    }
    if (code != AVERROR(EAGAIN) && code != AVERROR_EOF)
      videoFailure(path, "cannot decode a frame", code);
  };
  while (av_read_frame(format, packet) >= 0) {
    if (packet->stream_index == index) {
      code = avcodec_send_packet(codec, packet);
      av_packet_unref(packet);
      if (code < 0) videoFailure(path, "cannot decode a packet", code);
      receive();
    } else {
      av_packet_unref(packet);
    }
  }
  avcodec_send_packet(codec, nullptr);  // drain
  receive();
  return clip;
}

}  // namespace cablelab::ui

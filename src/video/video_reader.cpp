#include "tumble/video_reader.hpp"

extern "C" {
#include <libavutil/pixdesc.h>
}

#include <string>

#include "ffmpeg_handles.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

// swscale's name for the Y'CbCr matrix a stream is tagged with. An untagged stream (or a matrix
// swscale lacks) is decoded as the ffmpeg tool decodes it, with BT.601: untagged streams mostly
// come from FFmpeg itself, whose RGB -> Y'CbCr default is BT.601, so `ffmpeg -i clip -pix_fmt
// rgb24` reproduces these pixels. tumble's own clips are tagged BT.709.
int sws_colorspace(AVColorSpace space) {
  switch (space) {
    case AVCOL_SPC_BT709:
      return SWS_CS_ITU709;
    case AVCOL_SPC_BT470BG:
    case AVCOL_SPC_SMPTE170M:
      return SWS_CS_ITU601;
    case AVCOL_SPC_SMPTE240M:
      return SWS_CS_SMPTE240M;
    case AVCOL_SPC_FCC:
      return SWS_CS_FCC;
    case AVCOL_SPC_BT2020_NCL:
    case AVCOL_SPC_BT2020_CL:
      return SWS_CS_BT2020;
    default:
      return SWS_CS_DEFAULT;  // BT.601
  }
}

// Full range ("JPEG", 0–255) when tagged so or when the pixel format is one of the yuvj* ones
// (which FFmpeg uses for full-range Y'CbCr); otherwise limited ("MPEG", Y' 16–235), the
// broadcast convention H.264 streams follow unless they say otherwise.
bool is_full_range(AVColorRange range, AVPixelFormat format) {
  if (range == AVCOL_RANGE_JPEG) return true;
  if (range == AVCOL_RANGE_MPEG) return false;
  switch (format) {
    case AV_PIX_FMT_YUVJ420P:
    case AV_PIX_FMT_YUVJ422P:
    case AV_PIX_FMT_YUVJ444P:
    case AV_PIX_FMT_YUVJ440P:
    case AV_PIX_FMT_YUVJ411P:
      return true;
    default:
      return false;
  }
}

bool is_ycbcr(AVPixelFormat format) {
  const AVPixFmtDescriptor* d = av_pix_fmt_desc_get(format);
  return d != nullptr && (d->flags & AV_PIX_FMT_FLAG_RGB) == 0 && d->nb_components >= 3;
}

}  // namespace

struct VideoReader::Impl {
  explicit Impl(const fs::path& file);

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(ErrorKind::BadInput, "cannot decode \"" + path.string() + "\": " + what);
  }
  [[noreturn]] void fail(const std::string& what, int code) const {
    fail(what + ": " + av_error_text(code));
  }
  // Sends the next packet of the video stream to the decoder, or the end-of-stream signal.
  void feed();
  void convert(const AVFrame& frame, Image& out);

  fs::path path;
  InputFormatPtr demuxer;
  CodecContextPtr decoder;
  int stream_index = -1;
  PacketPtr packet;
  FramePtr frame;
  bool draining = false;               // the end-of-stream signal has been sent
  std::optional<double> frame_time_s;  // of the frame next() returned last

  // The conversion to RGB, remade only when what it converts from changes.
  SwsPtr converter;
  int converter_width = 0, converter_height = 0;
  AVPixelFormat converter_format = AV_PIX_FMT_NONE;
  AVColorSpace converter_space = AVCOL_SPC_UNSPECIFIED;
  AVColorRange converter_range = AVCOL_RANGE_UNSPECIFIED;
};

VideoReader::Impl::Impl(const fs::path& file) : path(file) {
  silence_ffmpeg_log();
  // The "file:" protocol prefix keeps a ':' in a name from being read as a protocol.
  const std::string url = "file:" + path.string();
  AVFormatContext* raw_demuxer = nullptr;
  int result = avformat_open_input(&raw_demuxer, url.c_str(), nullptr, nullptr);
  if (result < 0) fail(av_error_text(result));  // FFmpeg freed the context
  demuxer.reset(raw_demuxer);
  result = avformat_find_stream_info(demuxer.get(), nullptr);
  if (result < 0) fail("cannot read stream information", result);

  const AVCodec* codec = nullptr;
  result = av_find_best_stream(demuxer.get(), AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
  if (result == AVERROR_STREAM_NOT_FOUND) fail("no video stream in it");
  if (result < 0 || codec == nullptr) fail("no decoder for its video stream");
  stream_index = result;
  // Only the video stream's packets are wanted: the demuxer skips the rest.
  for (unsigned i = 0; i < demuxer->nb_streams; ++i)
    if (static_cast<int>(i) != stream_index) demuxer->streams[i]->discard = AVDISCARD_ALL;
  const AVStream* stream = demuxer->streams[stream_index];

  decoder.reset(avcodec_alloc_context3(codec));
  packet.reset(av_packet_alloc());
  frame.reset(av_frame_alloc());
  if (!decoder || !packet || !frame) fail("out of memory", AVERROR(ENOMEM));
  result = avcodec_parameters_to_context(decoder.get(), stream->codecpar);
  if (result < 0) fail("bad stream parameters", result);
  decoder->pkt_timebase = stream->time_base;
  result = avcodec_open2(decoder.get(), codec, nullptr);
  if (result < 0) fail(std::string("cannot open the ") + codec->name + " decoder", result);
  if (decoder->width <= 0 || decoder->height <= 0) fail("the video stream has no frame size");
}

void VideoReader::Impl::feed() {
  for (;;) {
    int result = av_read_frame(demuxer.get(), packet.get());
    if (result == AVERROR_EOF) {
      // Ask for the frames the decoder still holds (reordering, frame threads).
      result = avcodec_send_packet(decoder.get(), nullptr);
      if (result < 0) fail("decoding failed", result);
      draining = true;
      return;
    }
    if (result < 0) fail("read failed", result);
    if (packet->stream_index != stream_index) {
      av_packet_unref(packet.get());
      continue;
    }
    result = avcodec_send_packet(decoder.get(), packet.get());
    av_packet_unref(packet.get());
    if (result < 0) fail("decoding failed", result);
    return;
  }
}

void VideoReader::Impl::convert(const AVFrame& decoded, Image& out) {
  const auto format = static_cast<AVPixelFormat>(decoded.format);
  if (!converter || decoded.width != converter_width || decoded.height != converter_height ||
      format != converter_format || decoded.colorspace != converter_space ||
      decoded.color_range != converter_range) {
    // The same flags as Mp4Writer's conversion: bit-exact whichever SIMD path this CPU takes.
    constexpr int kFlags = SWS_BICUBIC | SWS_ACCURATE_RND | SWS_BITEXACT;
    converter.reset(sws_getContext(decoded.width, decoded.height, format, decoded.width,
                                   decoded.height, AV_PIX_FMT_RGB24, kFlags, nullptr, nullptr,
                                   nullptr));
    if (!converter) {
      const char* name = av_get_pix_fmt_name(format);
      fail(std::string("cannot convert pixel format ") + (name ? name : "(unknown)") + " to RGB");
    }
    if (is_ycbcr(format)) {
      // swscale assumes BT.601 unless told; a BT.709 stream decoded as BT.601 is off by about 12
      // levels on saturated colours.
      const int* matrix = sws_getCoefficients(sws_colorspace(decoded.colorspace));
      const int full_range = is_full_range(decoded.color_range, format) ? 1 : 0;
      constexpr int kRgbFullRange = 1;
      constexpr int kBrightness = 0, kUnitContrast = 1 << 16, kUnitSaturation = 1 << 16;  // 16.16
      // The second matrix is the output's, unused for RGB output.
      sws_setColorspaceDetails(converter.get(), matrix, full_range, matrix, kRgbFullRange,
                               kBrightness, kUnitContrast, kUnitSaturation);
    }
    converter_width = decoded.width;
    converter_height = decoded.height;
    converter_format = format;
    converter_space = decoded.colorspace;
    converter_range = decoded.color_range;
  }
  if (out.width != decoded.width || out.height != decoded.height || out.channels != 3)
    out = Image(decoded.width, decoded.height, 3);
  std::uint8_t* planes[4] = {out.pixels.data(), nullptr, nullptr, nullptr};
  int strides[4] = {static_cast<int>(out.stride()), 0, 0, 0};
  sws_scale(converter.get(), decoded.data, decoded.linesize, 0, decoded.height, planes, strides);
}

VideoReader::VideoReader(const fs::path& path) : impl_(std::make_unique<Impl>(path)) {}

VideoReader::~VideoReader() = default;

bool VideoReader::next(Image& out) {
  Impl& m = *impl_;
  for (;;) {
    const int result = avcodec_receive_frame(m.decoder.get(), m.frame.get());
    if (result == 0) break;
    if (result == AVERROR_EOF) return false;
    if (result != AVERROR(EAGAIN) || m.draining) m.fail("decoding failed", result);
    m.feed();
  }
  m.convert(*m.frame, out);
  // best_effort_timestamp: the pts, or the decoder's guess where the container has none. The
  // stream's start is subtracted so the first frame is at 0 whatever the muxer's offset.
  const AVStream* stream = m.demuxer->streams[m.stream_index];
  const std::int64_t pts = m.frame->best_effort_timestamp;
  if (pts == AV_NOPTS_VALUE) {
    m.frame_time_s.reset();
  } else {
    const std::int64_t start = stream->start_time == AV_NOPTS_VALUE ? 0 : stream->start_time;
    m.frame_time_s = static_cast<double>(pts - start) * av_q2d(stream->time_base);
  }
  av_frame_unref(m.frame.get());
  return true;
}

std::optional<double> VideoReader::frame_time_s() const {
  return impl_->frame_time_s;
}

int VideoReader::width() const {
  return impl_->decoder->width;
}

int VideoReader::height() const {
  return impl_->decoder->height;
}

}  // namespace tumble

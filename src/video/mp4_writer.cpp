#include "tumble/mp4_writer.hpp"

extern "C" {
#include <libavutil/hwcontext.h>
}

#include <cassert>
#include <limits>
#include <system_error>

#include "ffmpeg_handles.hpp"
#include "h264_encoder.hpp"
#include "tumble/atomic_file.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void bad_settings(const std::string& message) {
  throw Error(ErrorKind::BadInput, message);
}

void check(const Mp4Settings& settings) {
  if (settings.width <= 0 || settings.height <= 0)
    bad_settings("video size must be positive; got " + std::to_string(settings.width) + "x" +
                 std::to_string(settings.height));
  if (settings.width % 2 != 0 || settings.height % 2 != 0)
    bad_settings("H.264 (yuv420p) needs an even width and height; got " +
                 std::to_string(settings.width) + "x" + std::to_string(settings.height));
  if (settings.fps <= 0) bad_settings("fps must be positive; got " + std::to_string(settings.fps));
  if (settings.crf < 0 || settings.crf > 51)
    bad_settings("crf must be in [0, 51]; got " + std::to_string(settings.crf));
}

}  // namespace

struct Mp4Writer::Impl {
  Impl(const fs::path& path, const Mp4Settings& settings);

  [[noreturn]] void fail_writing(const std::string& what, int code) const {
    throw Error(ErrorKind::Environment, "cannot write \"" + final_path.string() + "\": " + what +
                                            ": " + av_error_text(code));
  }
  [[noreturn]] void fail_encoding(int code) const {
    throw Error(ErrorKind::Environment,
                "encoder " + encoder_name + " failed: " + av_error_text(code));
  }
  void use_input_format(AVPixelFormat format);
  void encode(const AVFrame* frame);
  // Sends `picture` (converted already) as frame number `frames`.
  void submit_picture();

  Mp4Settings settings;
  fs::path final_path;
  // Declared before the muxer, so its temporary is removed after the muxer has closed it.
  StagedFile staged;
  FormatContextPtr muxer;
  H264Encoder encoder;
  std::string encoder_name;
  AVStream* stream = nullptr;  // owned by the muxer
  SwsPtr converter;
  AVPixelFormat converter_input = AV_PIX_FMT_NONE;
  FramePtr picture;           // the converted frame, in encoder.input_format
  FramePtr hardware_picture;  // its upload, for encoders that take hardware frames
  PacketPtr packet;
  long frames = 0;
  bool finished = false;
};

Mp4Writer::Impl::Impl(const fs::path& path, const Mp4Settings& s)
    : settings(s), final_path(path), staged(path) {
  check(settings);
  // The "file:" protocol prefix keeps a ':' in a folder name from being read as a protocol. The
  // muxer reopens this URL in av_write_trailer to move the moov box to the front (+faststart).
  const std::string url = "file:" + staged.temporary_path().string();
  AVFormatContext* raw_muxer = nullptr;
  int result = avformat_alloc_output_context2(&raw_muxer, nullptr, "mp4", url.c_str());
  if (result < 0) fail_writing("MP4 muxer", result);
  muxer.reset(raw_muxer);

  encoder = open_h264_encoder(settings, (muxer->oformat->flags & AVFMT_GLOBALHEADER) != 0);
  encoder_name = encoder.context->codec->name;
  AVCodecContext* codec = encoder.context.get();

  stream = avformat_new_stream(muxer.get(), nullptr);
  if (stream == nullptr) fail_writing("MP4 stream", AVERROR(ENOMEM));
  stream->time_base = codec->time_base;
  stream->avg_frame_rate = codec->framerate;
  result = avcodec_parameters_from_context(stream->codecpar, codec);
  if (result < 0) fail_writing("MP4 stream", result);

  picture.reset(av_frame_alloc());
  packet.reset(av_packet_alloc());
  if (!picture || !packet) fail_writing("frame buffers", AVERROR(ENOMEM));
  picture->format = encoder.input_format;
  picture->width = settings.width;
  picture->height = settings.height;
  picture->color_primaries = codec->color_primaries;
  picture->color_trc = codec->color_trc;
  picture->colorspace = codec->colorspace;
  picture->color_range = codec->color_range;
  result = av_frame_get_buffer(picture.get(), 0);
  if (result < 0) fail_writing("frame buffers", result);
  if (encoder.hardware_frames) {
    hardware_picture.reset(av_frame_alloc());
    if (!hardware_picture) fail_writing("frame buffers", AVERROR(ENOMEM));
  }

  result = avio_open(&muxer->pb, url.c_str(), AVIO_FLAG_WRITE);
  if (result < 0)
    throw Error(ErrorKind::Environment,
                "cannot write \"" + final_path.string() + "\": " + av_error_text(result));
  AvOptions options;
  options.set("movflags", "+faststart");  // moov before mdat: playable while downloading
  // The movie's own clock (mvhd, tkhd, the edit list) ticks in 1/(1000 fps) s rather than the
  // muxer's default milliseconds, so the container says N / fps exactly, as the stream does.
  options.set("movie_timescale", std::to_string(1000L * settings.fps));
  result = avformat_write_header(muxer.get(), options.get());
  if (result < 0) fail_writing("MP4 header", result);
}

// Full-range RGB in, BT.709 limited-range ("MPEG") 4:2:0 out. swscale defaults to BT.601, which
// would shift hues once a player decodes with the BT.709 the stream is tagged with.
void Mp4Writer::Impl::use_input_format(AVPixelFormat format) {
  if (converter && converter_input == format) return;
  // BITEXACT + ACCURATE_RND: the same bytes whichever SIMD path this CPU takes (about +0.1 ms
  // on 1.9 ms per 720p frame here), so a clip's hash does not depend on the machine.
  constexpr int kFlags = SWS_BICUBIC | SWS_ACCURATE_RND | SWS_BITEXACT;
  converter.reset(sws_getContext(settings.width, settings.height, format, settings.width,
                                 settings.height, encoder.input_format, kFlags, nullptr, nullptr,
                                 nullptr));
  if (!converter) fail_encoding(AVERROR(ENOMEM));
  converter_input = format;
  const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
  constexpr int kFullRange = 1, kLimitedRange = 0;
  constexpr int kBrightness = 0, kUnitContrast = 1 << 16, kUnitSaturation = 1 << 16;  // 16.16
  sws_setColorspaceDetails(converter.get(), bt709, kFullRange, bt709, kLimitedRange, kBrightness,
                           kUnitContrast, kUnitSaturation);
}

void Mp4Writer::Impl::encode(const AVFrame* frame) {
  int result = avcodec_send_frame(encoder.context.get(), frame);
  if (result < 0) fail_encoding(result);
  for (;;) {
    result = avcodec_receive_packet(encoder.context.get(), packet.get());
    if (result == AVERROR(EAGAIN) || result == AVERROR_EOF) return;
    if (result < 0) fail_encoding(result);
    // Every packet is one frame. libx264 leaves the duration 0, and the MP4's last sample (so its
    // total duration) would come out short.
    packet->duration = 1;
    av_packet_rescale_ts(packet.get(), encoder.context->time_base, stream->time_base);
    packet->stream_index = stream->index;
    result = av_interleaved_write_frame(muxer.get(), packet.get());  // unrefs the packet
    if (result < 0) fail_writing("write failed", result);
  }
}

Mp4Writer::Mp4Writer(const fs::path& path, const Mp4Settings& settings)
    : impl_(std::make_unique<Impl>(path, settings)) {}

Mp4Writer::~Mp4Writer() = default;

void Mp4Writer::add_frame(const std::uint8_t* pixels, int channels, std::ptrdiff_t stride,
                          bool bottom_up) {
  Impl& m = *impl_;
  assert(!m.finished);
  assert(channels == 3 || channels == 4);
  assert(stride >= std::ptrdiff_t{m.settings.width} * channels &&
         stride <= std::numeric_limits<int>::max());
  m.use_input_format(channels == 4 ? AV_PIX_FMT_RGBA : AV_PIX_FMT_RGB24);

  // The encoder may still hold the previous picture (hardware encoders keep references).
  int result = av_frame_make_writable(m.picture.get());
  if (result < 0) m.fail_encoding(result);
  // Bottom-up rows (glReadPixels) are flipped for free: start at the last row, step backwards.
  const std::uint8_t* first_row =
      bottom_up ? pixels + std::ptrdiff_t{m.settings.height - 1} * stride : pixels;
  const int row_step = static_cast<int>(bottom_up ? -stride : stride);
  sws_scale(m.converter.get(), &first_row, &row_step, 0, m.settings.height, m.picture->data,
            m.picture->linesize);
  m.submit_picture();
}

void Mp4Writer::repeat_frame() {
  Impl& m = *impl_;
  assert(!m.finished && m.frames > 0);
  // A copy if the encoder still holds the picture; av_frame_make_writable keeps its pixels.
  const int result = av_frame_make_writable(m.picture.get());
  if (result < 0) m.fail_encoding(result);
  m.submit_picture();
}

void Mp4Writer::Impl::submit_picture() {
  Impl& m = *this;
  int result = 0;
  m.picture->pts = m.frames;  // frame k at k/fps (time base 1/fps)

  AVFrame* to_encode = m.picture.get();
  if (m.encoder.hardware_frames) {
    av_frame_unref(m.hardware_picture.get());
    result = av_hwframe_get_buffer(m.encoder.hardware_frames.get(), m.hardware_picture.get(), 0);
    if (result >= 0)
      result = av_hwframe_transfer_data(m.hardware_picture.get(), m.picture.get(), 0);
    if (result >= 0) result = av_frame_copy_props(m.hardware_picture.get(), m.picture.get());
    if (result < 0) m.fail_encoding(result);
    to_encode = m.hardware_picture.get();
  }
  m.encode(to_encode);
  ++m.frames;
}

void Mp4Writer::finish() {
  Impl& m = *impl_;
  assert(!m.finished);
  m.encode(nullptr);  // drain the frames the encoder still holds (lookahead, frame threads)
  int result = av_write_trailer(m.muxer.get());  // writes moov, then moves it before mdat
  if (result < 0) m.fail_writing("MP4 trailer", result);
  result = avio_closep(&m.muxer->pb);
  if (result < 0) m.fail_writing("close failed (disk full?)", result);
  m.staged.commit();
  m.finished = true;
}

const std::string& Mp4Writer::encoder_name() const {
  return impl_->encoder_name;
}

long Mp4Writer::frames() const {
  return impl_->frames;
}

std::vector<std::string> Mp4Writer::available_h264_encoders() {
  silence_ffmpeg_log();
  return h264_encoder_names();
}

namespace {

// A small picture every encoder takes (hardware ones have minimum sizes around 64-256 px).
Mp4Settings probe_settings(const std::string& encoder) {
  Mp4Settings s;
  s.width = 320;
  s.height = 240;
  s.fps = 30;
  s.encoder = encoder;
  return s;
}

}  // namespace

std::vector<std::string> Mp4Writer::usable_h264_encoders() {
  silence_ffmpeg_log();
  std::vector<std::string> usable;
  for (const std::string& name : h264_encoder_names()) {
    try {
      open_h264_encoder(probe_settings(name), true);
      usable.push_back(name);
    } catch (const Error&) {
      // compiled in, but no device, driver or library for it here
    }
  }
  return usable;
}

std::string Mp4Writer::auto_h264_encoder() {
  silence_ffmpeg_log();
  try {
    return open_h264_encoder(probe_settings("auto"), true).context->codec->name;
  } catch (const Error&) {
    return "";
  }
}

}  // namespace tumble

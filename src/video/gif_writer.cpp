#include "tumble/gif_writer.hpp"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <optional>
#include <set>
#include <string>

#include "ffmpeg_handles.hpp"
#include "filter_graph.hpp"
#include "frame_store.hpp"
#include "tumble/atomic_file.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

// Browsers (Chrome, Firefox, Safari) play a GIF delay of 0 or 1 cs as 10 cs: 2 cs is the
// shortest that plays as written.
constexpr int kMinDelayCs = 2;

// GIF stores sizes in 16 bits.
constexpr int kMaxGifSide = 65535;

// The palette pass: one palette for every frame of the clip. stats_mode=full counts every pixel
// of every frame, so the still floor, which fills most of each frame, keeps smooth tones, and
// the moving body's colours are there as often as they are seen. With alpha, one entry is kept
// for transparency.
std::string palettegen_description(bool alpha) {
  return std::string("[in0]palettegen=max_colors=256:stats_mode=full:reserve_transparent=") +
         (alpha ? "1" : "0") + "[out]";
}

// Ordered (Bayer) dithering: deterministic and the same pattern in every frame, so still areas
// do not shimmer and compress well between frames (an error-diffusion dither would crawl);
// bayer_scale 3 keeps the pattern fine. Only the rectangle that changed is remapped, so still
// pixels keep their indices exactly and the encoder's frame differences stay small.
constexpr const char* kPaletteuseDescription =
    "[in0][in1]paletteuse=dither=bayer:bayer_scale=3:diff_mode=rectangle:alpha_threshold=128"
    "[out]";

// RGBA bytes → FFmpeg's RGB32 (one native-endian 0xAARRGGBB word per pixel), which the palette
// filters take: written as words, so the byte order is right on any CPU.
void to_rgb32(const std::uint8_t* rgba, std::uint8_t* out, int width) {
  for (int x = 0; x < width; ++x, rgba += 4, out += 4) {
    const std::uint32_t word = std::uint32_t{rgba[3]} << 24 | std::uint32_t{rgba[0]} << 16 |
                               std::uint32_t{rgba[1]} << 8 | std::uint32_t{rgba[2]};
    std::memcpy(out, &word, 4);
  }
}

}  // namespace

GifTiming GifTiming::for_clip(int fps, long clip_frames) {
  assert(fps > 0);
  GifTiming t;
  t.fps = fps;
  // The smallest step with 100·step/fps >= 2 cs: ceil(fps / 50).
  t.frame_step = std::max(1, (fps + 49) / 50);
  t.clip_frames = clip_frames;
  return t;
}

long GifTiming::frames() const {
  return (clip_frames + frame_step - 1) / frame_step;
}

long GifTiming::start_cs(long j) const {
  // round(100·j·step / fps), halves up, in integers: exact for any clip length.
  const long long num = 200LL * j * frame_step + fps;
  return static_cast<long>(num / (2LL * fps));
}

int GifTiming::delay_cs(long j) const {
  const long end = j + 1 < frames() ? start_cs(j + 1)
                                    : static_cast<long>((200LL * clip_frames + fps) / (2LL * fps));
  // Only the last frame can come out under 2 cs (a clip whose length is not a whole number of
  // steps); it is lengthened rather than played at 10 cs.
  return static_cast<int>(std::max<long>(kMinDelayCs, end - start_cs(j)));
}

struct GifWriter::Impl {
  Impl(const fs::path& path, const GifSettings& s)
      : settings(s),
        timing(GifTiming::for_clip(s.fps, s.clip_frames)),
        final_path(path),
        palette_pass(palettegen_description(s.alpha),
                     {{AV_PIX_FMT_RGB32, s.width, s.height, AVRational{1, 100}}}),
        frame(av_frame_alloc()) {
    if (!frame) fail("frame buffers", AVERROR(ENOMEM));
    frame->format = AV_PIX_FMT_RGB32;
    frame->width = s.width;
    frame->height = s.height;
    const int result = av_frame_get_buffer(frame.get(), 0);
    if (result < 0) fail("frame buffers", result);
  }

  [[noreturn]] void fail(const std::string& what, int code) const {
    throw Error(ErrorKind::Environment, "cannot write \"" + final_path.string() + "\": " + what +
                                            ": " + av_error_text(code));
  }

  std::size_t frame_bytes() const { return std::size_t(settings.width) * settings.height * 4; }

  // The kept frame j, unpacked into `frame` (rows tightly packed in the store).
  void load(std::size_t j, std::vector<std::uint8_t>& scratch) {
    store.get(j, scratch.data(), scratch.size());
    const int result = av_frame_make_writable(frame.get());
    if (result < 0) fail("frame buffers", result);
    for (int y = 0; y < settings.height; ++y)
      std::memcpy(frame->data[0] + std::ptrdiff_t(y) * frame->linesize[0],
                  scratch.data() + std::size_t(y) * settings.width * 4,
                  std::size_t(settings.width) * 4);
  }

  void encode(AVCodecContext* codec, AVFormatContext* muxer, AVStream* stream,
              const AVFrame* picture, AVPacket* packet) {
    int result = avcodec_send_frame(codec, picture);
    if (result < 0) fail("gif encoder", result);
    for (;;) {
      result = avcodec_receive_packet(codec, packet);
      if (result == AVERROR(EAGAIN) || result == AVERROR_EOF) return;
      if (result < 0) fail("gif encoder", result);
      av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      result = av_interleaved_write_frame(muxer, packet);  // unrefs the packet
      if (result < 0) fail("write failed", result);
    }
  }

  void finish();

  GifSettings settings;
  GifTiming timing;
  fs::path final_path;
  FilterGraph palette_pass;
  FramePtr frame;  // RGB32 scratch for the palette pass and the second pass
  FrameStore store;
  std::vector<std::uint8_t> row_scratch;
  long offered = 0;
  bool finished = false;
};

void GifWriter::Impl::finish() {
  palette_pass.close(0);
  FramePtr palette(av_frame_alloc());
  if (!palette) fail("frame buffers", AVERROR(ENOMEM));
  if (!palette_pass.pull(palette.get())) fail("palettegen gave no palette", AVERROR_BUG);

  // The file is opened only now: a run that fails before its end leaves no trace of it.
  StagedFile staged(final_path);
  const std::string url = "file:" + staged.temporary_path().string();
  AVFormatContext* raw_muxer = nullptr;
  int result = avformat_alloc_output_context2(&raw_muxer, nullptr, "gif", url.c_str());
  if (result < 0) fail("GIF muxer", result);
  FormatContextPtr muxer(raw_muxer);

  const AVCodec* gif = avcodec_find_encoder(AV_CODEC_ID_GIF);
  if (!gif) fail("this FFmpeg has no gif encoder", AVERROR_ENCODER_NOT_FOUND);
  CodecContextPtr codec(avcodec_alloc_context3(gif));
  if (!codec) fail("gif encoder", AVERROR(ENOMEM));
  codec->width = settings.width;
  codec->height = settings.height;
  codec->pix_fmt = AV_PIX_FMT_PAL8;
  codec->time_base = AVRational{1, 100};  // centiseconds: what a GIF delay counts
  codec->thread_count = 1;
  codec->flags |= AV_CODEC_FLAG_BITEXACT;
  result = avcodec_open2(codec.get(), gif, nullptr);
  if (result < 0) fail("gif encoder", result);

  AVStream* stream = avformat_new_stream(muxer.get(), nullptr);
  if (!stream) fail("GIF stream", AVERROR(ENOMEM));
  stream->time_base = codec->time_base;
  result = avcodec_parameters_from_context(stream->codecpar, codec.get());
  if (result < 0) fail("GIF stream", result);
  result = avio_open(&muxer->pb, url.c_str(), AVIO_FLAG_WRITE);
  if (result < 0)
    throw Error(ErrorKind::Environment,
                "cannot write \"" + final_path.string() + "\": " + av_error_text(result));
  muxer->flags |= AVFMT_FLAG_BITEXACT;
  AvOptions options;
  options.set("loop", "0");  // the NETSCAPE2.0 extension with 0: loop forever
  // The muxer takes each delay from the next frame's start; the last has none.
  options.set("final_delay", std::to_string(timing.delay_cs(timing.frames() - 1)));
  result = avformat_write_header(muxer.get(), options.get());
  if (result < 0) fail("GIF header", result);

  FilterGraph remap(kPaletteuseDescription,
                    {{AV_PIX_FMT_RGB32, settings.width, settings.height, AVRational{1, 100}},
                     {static_cast<AVPixelFormat>(palette->format), palette->width, palette->height,
                      AVRational{1, 100}}});
  palette->pts = 0;
  remap.push(1, palette.get());
  remap.close(1);
  PacketPtr packet(av_packet_alloc());
  FramePtr mapped(av_frame_alloc());
  if (!packet || !mapped) fail("frame buffers", AVERROR(ENOMEM));
  std::vector<std::uint8_t> scratch(frame_bytes());
  for (std::size_t j = 0; j < store.size(); ++j) {
    load(j, scratch);
    frame->pts = timing.start_cs(static_cast<long>(j));
    remap.push(0, frame.get());
    while (remap.pull(mapped.get()))
      encode(codec.get(), muxer.get(), stream, mapped.get(), packet.get());
  }
  remap.close(0);
  while (remap.pull(mapped.get()))
    encode(codec.get(), muxer.get(), stream, mapped.get(), packet.get());
  encode(codec.get(), muxer.get(), stream, nullptr, packet.get());  // drain
  result = av_write_trailer(muxer.get());
  if (result < 0) fail("GIF trailer", result);
  result = avio_closep(&muxer->pb);
  if (result < 0) fail("close failed (disk full?)", result);
  staged.commit();
  finished = true;
}

GifWriter::GifWriter(const fs::path& path, const GifSettings& settings) {
  if (settings.width < 1 || settings.height < 1 || settings.width > kMaxGifSide ||
      settings.height > kMaxGifSide)
    throw Error(ErrorKind::BadInput, "a GIF is at most " + std::to_string(kMaxGifSide) +
                                         " pixels a side; got " + std::to_string(settings.width) +
                                         "x" + std::to_string(settings.height));
  if (settings.fps < 1 || settings.clip_frames < 1)
    throw Error(ErrorKind::BadInput, "a GIF needs at least one frame");
  silence_ffmpeg_log();
  impl_ = std::make_unique<Impl>(path, settings);
}

GifWriter::~GifWriter() = default;

bool GifWriter::keeps_next_frame() const {
  const long k = impl_->offered;
  return k % impl_->timing.frame_step == 0 && k / impl_->timing.frame_step < impl_->timing.frames();
}

void GifWriter::add_frame(const std::uint8_t* rgba, std::ptrdiff_t stride, bool bottom_up) {
  Impl& m = *impl_;
  assert(!m.finished);
  const bool kept = keeps_next_frame();
  const long k = m.offered++;
  if (!kept) return;
  const int w = m.settings.width, h = m.settings.height;
  // Packed rows for the store and the same rows into the frame for the palette pass.
  m.row_scratch.resize(m.frame_bytes());
  const int result = av_frame_make_writable(m.frame.get());
  if (result < 0) m.fail("frame buffers", result);
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* in =
        rgba + (bottom_up ? std::ptrdiff_t(h - 1 - y) : std::ptrdiff_t(y)) * stride;
    std::uint8_t* packed = m.row_scratch.data() + std::size_t(y) * w * 4;
    to_rgb32(in, packed, w);
    std::memcpy(m.frame->data[0] + std::ptrdiff_t(y) * m.frame->linesize[0], packed,
                std::size_t(w) * 4);
  }
  m.frame->pts = m.timing.start_cs(k / m.timing.frame_step);
  m.palette_pass.push(0, m.frame.get());
  m.store.add(m.row_scratch.data(), m.row_scratch.size());
}

void GifWriter::finish() {
  assert(!impl_->finished);
  impl_->finish();
}

const GifTiming& GifWriter::timing() const {
  return impl_->timing;
}

std::vector<int> GifWriter::delays_cs() const {
  std::set<int> distinct;
  for (long j = 0; j < impl_->timing.frames(); ++j) distinct.insert(impl_->timing.delay_cs(j));
  return {distinct.begin(), distinct.end()};
}

}  // namespace tumble

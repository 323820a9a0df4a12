#include "tumble/webp_writer.hpp"

#include <cassert>
#include <cstring>
#include <set>
#include <string>
#include <string_view>

#include "ffmpeg_handles.hpp"
#include "tumble/atomic_file.hpp"
#include "tumble/error.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

std::uint32_t read_le(const std::string& b, std::size_t at, int bytes) {
  std::uint32_t v = 0;
  for (int i = bytes - 1; i >= 0; --i)
    v = v << 8 | static_cast<unsigned char>(b[at + static_cast<std::size_t>(i)]);
  return v;
}
void write_le(std::string& b, std::size_t at, std::uint32_t v, int bytes) {
  for (int i = 0; i < bytes; ++i, v >>= 8) b[at + static_cast<std::size_t>(i)] = char(v & 0xff);
}

// Sets the animation's loop count to 0 (forever) and the duration of its last frame so the
// animation ends at `end_ms`. FFmpeg's wrapper never tells libwebp when the last frame ends
// (WebPAnimEncoderAdd with no picture), so libwebp gives it the average duration of the others,
// truncated: at 60 fps a 4 s clip would last 3.999 s. The fields are the container's own (RIFF
// chunks "ANIM" and "ANMF", WebP Container Specification): nothing else changes. A single
// frame comes as a still WebP, which has neither and is left as it is. Returns false when the
// bytes are not a WebP.
bool set_loop_and_end(std::string& webp, std::uint32_t end_ms) {
  if (webp.size() < 12 || webp.compare(0, 4, "RIFF") != 0 || webp.compare(8, 4, "WEBP") != 0)
    return false;
  std::size_t at = 12, anim = 0, last_frame = 0;
  std::uint32_t elapsed_ms = 0, last_duration = 0;
  while (at + 8 <= webp.size()) {
    const std::string_view fourcc(webp.data() + at, 4);
    const std::uint32_t size = read_le(webp, at + 4, 4);
    if (at + 8 + size > webp.size()) return false;
    if (fourcc == "ANIM" && size >= 6) anim = at + 8;
    if (fourcc == "ANMF" && size >= 16) {
      elapsed_ms += last_duration;
      last_frame = at + 8;
      last_duration = read_le(webp, last_frame + 12, 3);
    }
    at += 8 + size + (size & 1);  // chunks are padded to an even size
  }
  if (!anim && !last_frame) return true;  // a still image
  if (!anim || !last_frame || end_ms <= elapsed_ms) return false;
  write_le(webp, anim + 4, 0, 2);
  write_le(webp, last_frame + 12, end_ms - elapsed_ms, 3);
  return true;
}

}  // namespace

WebpTiming WebpTiming::for_clip(int fps, long clip_frames) {
  assert(fps > 0);
  WebpTiming t;
  t.fps = fps;
  // Every frame lasts at least floor(1000 / fps) ms: >= 11 ms (plays as written) up to 90 fps.
  // Above, the smallest step with 1000·step / fps >= 20 ms: ceil(fps / 50).
  t.frame_step = 11 * fps <= 1000 ? 1 : (fps + 49) / 50;
  t.clip_frames = clip_frames;
  return t;
}

long WebpTiming::frames() const {
  const long n = (clip_frames + frame_step - 1) / frame_step;
  // The last of n frames starts at clip frame (n-1)·step: when fewer than `step` clip frames
  // are left it would be shorter than every other, so the frame before lasts to the end.
  if (n > 1 && (n - 1) * frame_step + frame_step > clip_frames) return n - 1;
  return n;
}

bool WebpTiming::keeps(long k) const {
  return k % frame_step == 0 && k / frame_step < frames();
}

long WebpTiming::start_ms(long j) const {
  // round(1000·j·step / fps), halves up, in integers: exact for any clip length.
  return static_cast<long>((2000LL * j * frame_step + fps) / (2LL * fps));
}

long WebpTiming::end_ms() const {
  return static_cast<long>((2000LL * clip_frames + fps) / (2LL * fps));
}

int WebpTiming::duration_ms(long j) const {
  return static_cast<int>((j + 1 < frames() ? start_ms(j + 1) : end_ms()) - start_ms(j));
}

struct WebpWriter::Impl {
  [[noreturn]] void fail(const std::string& what, int code) const {
    throw Error(ErrorKind::Environment, "cannot write \"" + final_path.string() + "\": " + what +
                                            ": " + av_error_text(code));
  }

  void encode(const AVFrame* picture) {
    int result = avcodec_send_frame(codec.get(), picture);
    if (result < 0) fail("libwebp_anim encoder", result);
    for (;;) {
      result = avcodec_receive_packet(codec.get(), packet.get());
      if (result == AVERROR(EAGAIN) || result == AVERROR_EOF) return;
      if (result < 0) fail("libwebp_anim encoder", result);
      // The encoder returns the whole animation as one packet when it is flushed.
      assembled.append(reinterpret_cast<const char*>(packet->data),
                       static_cast<std::size_t>(packet->size));
      av_packet_unref(packet.get());
    }
  }

  WebpSettings settings;
  WebpTiming timing;
  fs::path final_path;
  CodecContextPtr codec;
  FramePtr frame;
  PacketPtr packet;
  std::string assembled;
  long offered = 0;  // clip frames offered
  long frames = 0;   // WebP frames encoded
  bool finished = false;
};

WebpWriter::WebpWriter(const fs::path& path, const WebpSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.settings = settings;
  m.timing = WebpTiming::for_clip(settings.fps, settings.clip_frames);
  m.final_path = path;
  if (settings.width < 1 || settings.height < 1 || settings.width > kMaxSide ||
      settings.height > kMaxSide)
    throw Error(ErrorKind::BadInput, "a WebP is at most " + std::to_string(kMaxSide) +
                                         " pixels a side; got " + std::to_string(settings.width) +
                                         "x" + std::to_string(settings.height));
  assert(settings.fps > 0);
  silence_ffmpeg_log();
  const AVCodec* webp = avcodec_find_encoder_by_name("libwebp_anim");
  if (!webp) m.fail("this FFmpeg has no libwebp_anim encoder", AVERROR_ENCODER_NOT_FOUND);
  m.codec.reset(avcodec_alloc_context3(webp));
  m.frame.reset(av_frame_alloc());
  m.packet.reset(av_packet_alloc());
  if (!m.codec || !m.frame || !m.packet) m.fail("encoder", AVERROR(ENOMEM));
  m.codec->width = settings.width;
  m.codec->height = settings.height;
  // RGB32: libwebp converts to its own 4:2:0 itself (sharper edges than a generic swscale pass,
  // and no conversion to keep bit-exact here), and takes the alpha channel from the same words.
  m.codec->pix_fmt = AV_PIX_FMT_RGB32;
  m.codec->time_base = AVRational{1, 1000};  // milliseconds: what a WebP duration counts
  m.codec->thread_count = 1;
  AvOptions options;
  options.set("lossless", "0");
  options.set("quality", "75");  // libwebp's default: small, and clean on flat shading
  const int result = avcodec_open2(m.codec.get(), webp, options.get());
  if (result < 0) m.fail("libwebp_anim encoder", result);
  m.frame->format = AV_PIX_FMT_RGB32;
  m.frame->width = settings.width;
  m.frame->height = settings.height;
  const int got = av_frame_get_buffer(m.frame.get(), 0);
  if (got < 0) m.fail("frame buffers", got);
}

WebpWriter::~WebpWriter() = default;

void WebpWriter::add_frame(const std::uint8_t* rgba, std::ptrdiff_t stride, bool bottom_up) {
  Impl& m = *impl_;
  assert(!m.finished);
  if (!m.timing.keeps(m.offered++)) return;
  const int w = m.settings.width, h = m.settings.height;
  int result = av_frame_make_writable(m.frame.get());
  if (result < 0) m.fail("frame buffers", result);
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* in =
        rgba + (bottom_up ? std::ptrdiff_t(h - 1 - y) : std::ptrdiff_t(y)) * stride;
    std::uint8_t* out = m.frame->data[0] + std::ptrdiff_t(y) * m.frame->linesize[0];
    // One native-endian 0xAARRGGBB word per pixel, whatever the CPU's byte order.
    for (int x = 0; x < w; ++x, in += 4, out += 4) {
      const std::uint32_t alpha = m.settings.alpha ? in[3] : 255u;
      const std::uint32_t word =
          alpha << 24 | std::uint32_t{in[0]} << 16 | std::uint32_t{in[1]} << 8 | in[2];
      std::memcpy(out, &word, 4);
    }
  }
  m.frame->pts = m.timing.start_ms(m.frames);
  m.encode(m.frame.get());
  ++m.frames;
}

void WebpWriter::finish() {
  Impl& m = *impl_;
  assert(!m.finished);
  assert(m.frames == m.timing.frames() && "every clip frame offered");
  m.encode(nullptr);
  if (!set_loop_and_end(m.assembled, static_cast<std::uint32_t>(m.timing.end_ms())))
    m.fail("libwebp_anim gave no animation", AVERROR_BUG);
  write_file_atomically(m.final_path, m.assembled);
  m.finished = true;
}

bool WebpWriter::keeps_next_frame() const {
  return impl_->timing.keeps(impl_->offered);
}

const WebpTiming& WebpWriter::timing() const {
  return impl_->timing;
}

long WebpWriter::frames() const {
  return impl_->frames;
}

std::vector<int> WebpWriter::durations_ms() const {
  std::set<int> distinct;
  for (long j = 0; j < impl_->frames; ++j) distinct.insert(impl_->timing.duration_ms(j));
  return {distinct.begin(), distinct.end()};
}

}  // namespace tumble

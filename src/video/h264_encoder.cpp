#include "h264_encoder.hpp"

extern "C" {
#include <libavutil/hwcontext.h>
#include <libavutil/log.h>
}

#include <algorithm>
#include <array>
#include <cstdarg>
#include <cstdio>
#include <optional>
#include <string_view>

#include "tumble/error.hpp"

namespace tumble {
namespace {

// Hardware encoders "auto" tries, in this order, before libx264. On a machine without the
// hardware or its driver they fail to open, which is the normal case and not reported.
constexpr std::array<const char*, 3> kHardwareEncoders = {"h264_nvenc", "h264_vaapi", "h264_qsv"};
constexpr const char* kSoftwareEncoder = "libx264";
// The H.264 encoders FFmpeg can be built with (libavcodec's names): one of these that the
// running FFmpeg does not have is "encoder missing", not a typing mistake.
constexpr std::array<std::string_view, 14> kKnownH264Encoders = {
    "libx264",  "libx264rgb",      "libopenh264",       "h264_amf",     "h264_nvenc",
    "h264_qsv", "h264_vaapi",      "h264_videotoolbox", "h264_v4l2m2m", "h264_omx",
    "h264_mf",  "h264_mediacodec", "h264_vulkan",       "nvenc_h264"};

// Frames in a VAAPI upload pool: the encoder holds a few in flight (reference + lookahead).
constexpr int kHardwarePoolFrames = 20;

// How frames reach an encoder.
struct InputPlan {
  AVPixelFormat software_format = AV_PIX_FMT_NONE;
  AVHWDeviceType device = AV_HWDEVICE_TYPE_NONE;  ///< NONE: the encoder takes software frames
  AVPixelFormat hardware_format = AV_PIX_FMT_NONE;
};

bool offers(const AVPixelFormat* formats, AVPixelFormat format) {
  for (; *formats != AV_PIX_FMT_NONE; ++formats)
    if (*formats == format) return true;
  return false;
}

bool is_h264_video_encoder(const AVCodec* codec) {
  return codec && av_codec_is_encoder(codec) && codec->type == AVMEDIA_TYPE_VIDEO &&
         codec->id == AV_CODEC_ID_H264;
}

// Software 4:2:0 when the encoder takes it; otherwise NV12 uploaded into hardware frames. None
// for encoders of other layouts (libx264rgb encodes RGB 4:4:4, which is not what clip.mp4 is).
std::optional<InputPlan> plan_input(const AVCodec* codec) {
  if (codec->pix_fmts == nullptr) return InputPlan{AV_PIX_FMT_YUV420P};
  if (offers(codec->pix_fmts, AV_PIX_FMT_YUV420P)) return InputPlan{AV_PIX_FMT_YUV420P};
  if (offers(codec->pix_fmts, AV_PIX_FMT_NV12)) return InputPlan{AV_PIX_FMT_NV12};
  for (int i = 0;; ++i) {
    const AVCodecHWConfig* config = avcodec_get_hw_config(codec, i);
    if (config == nullptr) break;
    if ((config->methods & AV_CODEC_HW_CONFIG_METHOD_HW_FRAMES_CTX) &&
        offers(codec->pix_fmts, config->pix_fmt))
      return InputPlan{AV_PIX_FMT_NV12, config->device_type, config->pix_fmt};
  }
  return std::nullopt;
}

// Quality and speed settings. libx264 takes the CRF as such; each hardware encoder gets its
// nearest constant-quality mode, on the same 0-51 quantiser scale.
void set_quality(const AVCodec* codec, int crf, AVCodecContext* context, AvOptions& options) {
  const std::string_view name = codec->name;
  if (name == kSoftwareEncoder) {
    options.set("preset", "veryfast");
    options.set("crf", std::to_string(crf));
    context->thread_count = kX264Threads;
    context->thread_type = FF_THREAD_FRAME;  // frame threads; sliced threads would split frames
  } else if (name == "h264_nvenc") {
    options.set("rc", "vbr");
    options.set("cq", std::to_string(crf));
  } else {
    context->global_quality = crf;  // h264_qsv: ICQ; h264_vaapi: CQP/ICQ
  }
}

// One attempt to open `codec`: the encoder, or (context empty) the reason it did not open.
struct Attempt {
  H264Encoder encoder;
  std::string failure;
};

Attempt failed(std::string why) {
  return Attempt{{}, std::move(why)};
}

// A pool of hardware frames on the default device of `plan.device`, for encoders that take only
// hardware frames. Empty buffer and the reason when the device or the pool cannot be made.
Attempt make_hardware_frames(const InputPlan& plan, const Mp4Settings& settings) {
  AVBufferRef* raw_device = nullptr;
  int result = av_hwdevice_ctx_create(&raw_device, plan.device, nullptr, nullptr, 0);
  const BufferPtr device(raw_device);
  if (result < 0)
    return failed(std::string("no ") + av_hwdevice_get_type_name(plan.device) +
                  " device: " + av_error_text(result));
  Attempt attempt;
  attempt.encoder.hardware_frames.reset(av_hwframe_ctx_alloc(device.get()));
  if (!attempt.encoder.hardware_frames) return failed("out of memory");
  auto* pool = reinterpret_cast<AVHWFramesContext*>(attempt.encoder.hardware_frames->data);
  pool->format = plan.hardware_format;
  pool->sw_format = plan.software_format;
  pool->width = settings.width;
  pool->height = settings.height;
  pool->initial_pool_size = kHardwarePoolFrames;
  result = av_hwframe_ctx_init(attempt.encoder.hardware_frames.get());
  if (result < 0) return failed("hardware frames: " + av_error_text(result));
  return attempt;
}

Attempt try_open(const AVCodec* codec, const InputPlan& plan, const Mp4Settings& settings,
                 bool global_header) {
  CodecContextPtr context(avcodec_alloc_context3(codec));
  if (!context) return failed("out of memory");
  context->width = settings.width;
  context->height = settings.height;
  // Frame k has pts k: the time base is one frame, so frame k is shown at exactly k/fps.
  context->time_base = AVRational{1, settings.fps};
  context->framerate = AVRational{settings.fps, 1};
  context->sample_aspect_ratio = AVRational{1, 1};
  context->pix_fmt =
      plan.device == AV_HWDEVICE_TYPE_NONE ? plan.software_format : plan.hardware_format;
  // What the swscale conversion in mp4_writer.cpp produces, written into the stream (H.264 VUI and
  // the MP4 colr box) so that players convert back with the same matrix and range.
  context->color_primaries = AVCOL_PRI_BT709;
  context->color_trc = AVCOL_TRC_BT709;
  context->colorspace = AVCOL_SPC_BT709;
  context->color_range = AVCOL_RANGE_MPEG;
  // No B-frames: packets come out in presentation order with dts = pts = frame index, so the MP4
  // starts at t = 0 without an edit list and its duration is exactly N/fps.
  context->max_b_frames = 0;
  if (global_header) context->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  AvOptions options;
  set_quality(codec, settings.crf, context.get(), options);

  Attempt attempt;
  if (plan.device != AV_HWDEVICE_TYPE_NONE) {
    attempt = make_hardware_frames(plan, settings);
    if (!attempt.encoder.hardware_frames) return attempt;
    context->hw_frames_ctx = av_buffer_ref(attempt.encoder.hardware_frames.get());
    if (!context->hw_frames_ctx) return failed("out of memory");
  }
  std::string logged;  // errors the codec logs while opening (see log_quietly)
  context->opaque = &logged;
  const int result = avcodec_open2(context.get(), codec, options.get());
  context->opaque = nullptr;
  if (result < 0) return failed(logged.empty() ? av_error_text(result) : logged);
  attempt.encoder.context = std::move(context);
  attempt.encoder.input_format = plan.software_format;
  return attempt;
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& name : names) s += (s.empty() ? "" : ", ") + name;
  return s;
}

}  // namespace

H264Encoder open_h264_encoder(const Mp4Settings& settings, bool global_header) {
  silence_ffmpeg_log();
  if (settings.encoder == "auto") {
    for (const char* name : kHardwareEncoders) {
      const AVCodec* codec = avcodec_find_encoder_by_name(name);
      if (!is_h264_video_encoder(codec)) continue;
      const std::optional<InputPlan> plan = plan_input(codec);
      if (!plan) continue;
      Attempt attempt = try_open(codec, *plan, settings, global_header);
      if (attempt.encoder.context) return std::move(attempt.encoder);
    }
    const AVCodec* codec = avcodec_find_encoder_by_name(kSoftwareEncoder);
    if (!is_h264_video_encoder(codec))
      throw Error(ErrorKind::Environment,
                  "no H.264 encoder could be opened: no hardware encoder worked and this FFmpeg "
                  "has no libx264");
    Attempt attempt = try_open(codec, *plan_input(codec), settings, global_header);
    if (!attempt.encoder.context)
      throw Error(ErrorKind::Environment, std::string("encoder ") + kSoftwareEncoder +
                                              " could not be opened: " + attempt.failure);
    return std::move(attempt.encoder);
  }

  const AVCodec* codec = avcodec_find_encoder_by_name(settings.encoder.c_str());
  // An H.264 encoder that FFmpeg has but this build lacks is missing from the environment
  // (exit 3); any other name is a mistake on the command line (exit 2).
  if (!codec && std::find(std::begin(kKnownH264Encoders), std::end(kKnownH264Encoders),
                          std::string_view(settings.encoder)) != std::end(kKnownH264Encoders))
    throw Error(ErrorKind::Environment,
                "encoder \"" + settings.encoder +
                    "\" is missing: this FFmpeg was built without it; use auto or one of: " +
                    joined(h264_encoder_names()));
  const std::optional<InputPlan> plan =
      is_h264_video_encoder(codec) ? plan_input(codec) : std::nullopt;
  if (!plan)
    throw Error(ErrorKind::BadInput, "\"" + settings.encoder +
                                         "\" is not an H.264 encoder of this FFmpeg; use auto or "
                                         "one of: " +
                                         joined(h264_encoder_names()));
  Attempt attempt = try_open(codec, *plan, settings, global_header);
  if (!attempt.encoder.context)
    throw Error(ErrorKind::Environment,
                "encoder " + settings.encoder + " could not be opened: " + attempt.failure);
  return std::move(attempt.encoder);
}

std::vector<std::string> h264_encoder_names() {
  std::vector<std::string> names;
  void* iterator = nullptr;
  while (const AVCodec* codec = av_codec_iterate(&iterator))
    if (is_h264_video_encoder(codec) && plan_input(codec)) names.emplace_back(codec->name);
  return names;
}

}  // namespace tumble

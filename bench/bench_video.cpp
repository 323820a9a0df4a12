// Cost per 1280x720 frame of the video sinks: RGB(A) -> BT.709 yuv420p (swscale) + libx264
// through Mp4Writer, and write_png. Run: build/release/bench/bench_video (figures go in the issue
// notes, never in a test). Real time is wall time; CPU time is the whole process's, because
// libx264 encodes on its own threads.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "tumble/image.hpp"
#include "tumble/mp4_writer.hpp"
#include "tumble/png.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 1280;
constexpr int kHeight = 720;
constexpr int kFps = 60;
constexpr int kClipFrames = 60;      // one second per benchmark iteration
constexpr int kDistinctFrames = 20;  // precomputed, so no frame is drawn while x264 works

fs::path bench_dir() {
  const fs::path dir = fs::temp_directory_path() / "tumble_bench_video";
  fs::create_directories(dir);
  return dir;
}

// Frame k of something like a rendered clip, as flat-shaded as tumble's: a sky-coloured
// background, a floor darkening towards the horizon with a checker, and an orange box with three
// lit faces sliding across. Content decides both encoders' costs, so it should look like ours.
Image scene_like_frame(int k, int channels) {
  Image image(kWidth, kHeight, channels);
  const int horizon = kHeight * 11 / 20;
  const int box_x = 200 + 12 * k, box_y = 260 + static_cast<int>(40 * std::sin(0.3 * k));
  const int box = 180;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      std::uint8_t rgb[3] = {0xdf, 0xe6, 0xee};
      if (y >= horizon) {
        const int depth = (y - horizon) * 255 / (kHeight - horizon);
        const bool dark = ((x * (depth + 40) / 4000) + (y - horizon) / 24) % 2 == 0;
        const auto shade = static_cast<std::uint8_t>(120 + depth / 3 - (dark ? 25 : 0));
        rgb[0] = rgb[1] = rgb[2] = shade;
      }
      const int dx = x - box_x, dy = y - box_y;
      if (dx >= 0 && dx < box && dy >= 0 && dy < box) {
        const int face = dy < box / 4 ? 0 : (dx < box / 2 ? 1 : 2);
        const double light[3] = {1.0, 0.8, 0.6};
        rgb[0] = static_cast<std::uint8_t>(217 * light[face]);
        rgb[1] = static_cast<std::uint8_t>(87 * light[face]);
        rgb[2] = static_cast<std::uint8_t>(43 * light[face]);
      }
      std::uint8_t* p = image.row(y) + x * channels;
      std::copy_n(rgb, 3, p);
      if (channels == 4) p[3] = 255;
    }
  return image;
}

std::vector<Image> scene_like_frames(int channels) {
  std::vector<Image> frames;
  for (int k = 0; k < kDistinctFrames; ++k) frames.push_back(scene_like_frame(k, channels));
  return frames;
}

// A whole one-second clip per iteration (open, 60 frames, flush, faststart rewrite, rename), so
// the frames x264 still holds in its lookahead and frame threads are paid for. Arg: 4 = RGBA
// bottom-up rows as glReadPixels returns them, 3 = RGB top-down as an Image.
void BM_Mp4ClipPerFrame720p(benchmark::State& state) {
  const int channels = static_cast<int>(state.range(0));
  const std::vector<Image> frames = scene_like_frames(channels);
  const fs::path file = bench_dir() / "clip.mp4";
  Mp4Settings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.fps = kFps;
  settings.encoder = "libx264";
  for (auto _ : state) {
    Mp4Writer writer(file, settings);
    for (int k = 0; k < kClipFrames; ++k) {
      const Image& frame = frames[k % kDistinctFrames];
      writer.add_frame(frame.pixels.data(), channels, static_cast<std::ptrdiff_t>(frame.stride()),
                       channels == 4);
    }
    writer.finish();
  }
  state.counters["bytes"] = static_cast<double>(fs::file_size(file));
  state.counters["per_frame"] =
      benchmark::Counter(kClipFrames * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["fps"] = benchmark::Counter(kClipFrames * static_cast<double>(state.iterations()),
                                             benchmark::Counter::kIsRate);
}

// One PNG per iteration. Arg: 3 = RGB, 4 = RGBA (alpha dropped while writing).
void BM_WritePng720p(benchmark::State& state) {
  const int channels = static_cast<int>(state.range(0));
  const std::vector<Image> frames = scene_like_frames(channels);
  const fs::path file = bench_dir() / "frame.png";
  long k = 0;
  for (auto _ : state) write_png(file, frames[k++ % kDistinctFrames]);
  state.counters["bytes"] = static_cast<double>(fs::file_size(file));
}

BENCHMARK(BM_Mp4ClipPerFrame720p)
    ->Arg(4)
    ->Arg(3)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();
BENCHMARK(BM_WritePng720p)->Arg(3)->Arg(4)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tumble

BENCHMARK_MAIN();

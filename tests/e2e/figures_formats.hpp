#pragma once
// Reading tumble's documentation figures back in the end-to-end tests, independently of tumble:
// PNG headers and RGBA pixels (through the ffmpeg tool, i.e. libavcodec), a GIF's blocks, a
// WebP's RIFF chunks (FFmpeg 5.1 cannot decode animated WebP), and an SVG's polylines and tick
// labels.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "run_tumble.hpp"
#include "trajectory_csv.hpp"

namespace tumble_e2e {

/// `ffprobe … -of default=nw=1` of the first video stream of an MP4 or GIF: key → value
/// ("codec_name" → "h264"); the format's duration arrives under "duration". ffprobe must report
/// no error.
inline std::map<std::string, std::string> probe(const fs::path& file) {
  const RunResult r = run_program(
      "ffprobe",
      {"-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
       "stream=codec_name,pix_fmt,nb_read_frames,width,height,time_base", "-show_entries",
       "format=duration", "-of", "default=nw=1", fs::absolute(file).string()},
      "/");
  std::map<std::string, std::string> values;
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(r.err, "") << "ffprobe reports errors in " << file.string();
  for (const std::string& line : split(r.out, '\n')) {
    const std::size_t eq = line.find('=');
    if (eq != std::string::npos) values[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return values;
}

struct PngInfo {
  bool valid = false;
  std::uint32_t width = 0, height = 0;
  int bit_depth = 0, color_type = 0;  ///< 2 = RGB, 6 = RGBA
};

/// The PNG signature and IHDR chunk of a file.
inline PngInfo png_info(const fs::path& path) {
  const std::string d = read_file(path);
  PngInfo h;
  if (d.size() < 33 || d.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 || d.compare(12, 4, "IHDR") != 0)
    return h;
  auto u32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = v << 8 | static_cast<unsigned char>(d[at + i]);
    return v;
  };
  h.valid = true;
  h.width = u32(16);
  h.height = u32(20);
  h.bit_depth = static_cast<unsigned char>(d[24]);
  h.color_type = static_cast<unsigned char>(d[25]);
  return h;
}

/// An image decoded by the ffmpeg tool to 8-bit RGBA, top-down (a GIF: its first frame).
struct Rgba {
  int width = 0, height = 0;
  std::string bytes;
  const unsigned char* at(int x, int y) const {
    return reinterpret_cast<const unsigned char*>(bytes.data()) +
           (static_cast<std::size_t>(y) * width + x) * 4;
  }
  int alpha(int x, int y) const { return at(x, y)[3]; }
};

inline Rgba decode_rgba(const fs::path& file, int width, int height) {
  const RunResult r = run_program("ffmpeg",
                                  {"-v", "error", "-i", fs::absolute(file).string(), "-frames:v",
                                   "1", "-f", "rawvideo", "-pix_fmt", "rgba", "-"},
                                  "/");
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  Rgba image;
  image.width = width;
  image.height = height;
  image.bytes = r.out;
  EXPECT_EQ(image.bytes.size(), static_cast<std::size_t>(width) * height * 4)
      << file.string() << " did not decode to " << width << "x" << height << " RGBA";
  if (image.bytes.size() != static_cast<std::size_t>(width) * height * 4) image.bytes.clear();
  return image;
}

/// The blocks of a GIF89a that say how it plays.
struct GifFile {
  bool valid = false;
  int width = 0, height = 0;
  bool global_palette = false;
  std::optional<int> loop_count;  ///< NETSCAPE2.0 application extension
  std::vector<int> delays_cs;     ///< one per graphic control extension, in order
  std::vector<bool> transparent;  ///< its transparency flag
  int images = 0;                 ///< image descriptors
};

/// Walks the GIF block by block (header, screen descriptor, extensions with their sub-blocks,
/// images with their LZW data, trailer): a byte search could match inside compressed data.
inline GifFile parse_gif(const std::string& d) {
  GifFile g;
  auto u8 = [&](std::size_t at) { return static_cast<unsigned char>(d.at(at)); };
  auto u16 = [&](std::size_t at) { return u8(at) | u8(at + 1) << 8; };
  try {
    if (d.compare(0, 6, "GIF89a") != 0) return g;
    g.width = u16(6);
    g.height = u16(8);
    const int flags = u8(10);
    std::size_t at = 13;
    if (flags & 0x80) {
      g.global_palette = true;
      at += 3u * (2u << (flags & 7));
    }
    // Skips data sub-blocks (size byte, bytes ... until a 0 size); returns the first one.
    auto sub_blocks = [&](std::size_t& p) {
      std::string first;
      bool got_first = false;
      for (;;) {
        const std::size_t n = u8(p++);
        if (n == 0) return first;
        if (!got_first) first = d.substr(p, n), got_first = true;
        p += n;
      }
    };
    for (;;) {
      const int introducer = u8(at++);
      if (introducer == 0x3b) break;  // trailer
      if (introducer == 0x21) {
        const int label = u8(at++);
        if (label == 0xf9) {  // graphic control: size 4, flags, delay (LE), transparent index
          g.transparent.push_back((u8(at + 1) & 1) != 0);
          g.delays_cs.push_back(u16(at + 2));
          sub_blocks(at);
        } else if (label == 0xff) {
          const std::string id = sub_blocks(at);
          (void)id;
          // The application identifier is the first sub-block; the loop count is in the second.
        } else {
          sub_blocks(at);
        }
        continue;
      }
      if (introducer != 0x2c) return g;
      ++g.images;
      const int image_flags = u8(at + 8);
      at += 9;
      if (image_flags & 0x80) at += 3u * (2u << (image_flags & 7));
      ++at;  // LZW minimum code size
      sub_blocks(at);
    }
    // NETSCAPE2.0: "!\xff\x0bNETSCAPE2.0\x03\x01" then the loop count (LE).
    const std::size_t n = d.find("\x21\xff\x0bNETSCAPE2.0\x03\x01");
    if (n != std::string::npos) g.loop_count = u16(n + 16);
    g.valid = true;
  } catch (const std::out_of_range&) {
  }
  return g;
}

/// The chunks of a WebP file that say how it plays.
struct WebpFile {
  bool valid = false;
  bool animation_flag = false, alpha_flag = false;  ///< VP8X flags
  std::optional<int> loop_count;                    ///< ANIM
  std::vector<int> durations_ms;                    ///< one per ANMF
  int alpha_chunks = 0;                             ///< ALPH inside the frames
};

inline WebpFile parse_webp(const std::string& d) {
  WebpFile w;
  auto le = [&](std::size_t at, int bytes) {
    std::uint32_t v = 0;
    for (int i = bytes - 1; i >= 0; --i)
      v = v << 8 | static_cast<unsigned char>(d.at(at + static_cast<std::size_t>(i)));
    return v;
  };
  try {
    if (d.compare(0, 4, "RIFF") != 0 || d.compare(8, 4, "WEBP") != 0) return w;
    if (le(4, 4) + 8 != d.size()) return w;  // the RIFF size covers the whole file
    // Chunks from `begin` to `end`; ANMF frames hold chunks of their own after 16 bytes.
    auto walk = [&](auto& self, std::size_t at, std::size_t end) -> bool {
      while (at + 8 <= end) {
        const std::string fourcc = d.substr(at, 4);
        const std::size_t size = le(at + 4, 4);
        if (at + 8 + size > end) return false;
        if (fourcc == "VP8X") {
          w.alpha_flag = (d.at(at + 8) & 0x10) != 0;
          w.animation_flag = (d.at(at + 8) & 0x02) != 0;
        } else if (fourcc == "ANIM") {
          w.loop_count = static_cast<int>(le(at + 12, 2));
        } else if (fourcc == "ANMF") {
          w.durations_ms.push_back(static_cast<int>(le(at + 8 + 12, 3)));
          if (!self(self, at + 8 + 16, at + 8 + size)) return false;
        } else if (fourcc == "ALPH") {
          ++w.alpha_chunks;
        }
        at += 8 + size + (size & 1);
      }
      return at == end;
    };
    w.valid = walk(walk, 12, d.size());
  } catch (const std::out_of_range&) {
    w.valid = false;
  }
  return w;
}

/// The value of attribute `name` in the element text `element` ("" when absent).
inline std::string attribute(const std::string& element, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const std::size_t at = element.find(key);
  if (at == std::string::npos) return "";
  const std::size_t start = at + key.size();
  return element.substr(start, element.find('"', start) - start);
}

/// Every element `<tag .../>` or `<tag ...>` of `svg`, as its opening text.
inline std::vector<std::string> elements(const std::string& svg, const std::string& tag) {
  std::vector<std::string> out;
  const std::string open = "<" + tag + " ";
  for (std::size_t at = svg.find(open); at != std::string::npos; at = svg.find(open, at + 1))
    out.push_back(svg.substr(at, svg.find('>', at) - at + 1));
  return out;
}

/// A polyline's points.
inline std::vector<std::pair<double, double>> polyline_points(const std::string& element) {
  std::vector<std::pair<double, double>> points;
  const std::string text = attribute(element, "points");
  for (const std::string& pair : split(text, ' ')) {
    const std::size_t comma = pair.find(',');
    if (comma == std::string::npos) continue;
    points.emplace_back(std::strtod(pair.substr(0, comma).c_str(), nullptr),
                        std::strtod(pair.substr(comma + 1).c_str(), nullptr));
  }
  return points;
}

/// y = a·x + b fitted by least squares, and the largest residual.
struct LineFit {
  double a = 0.0, b = 0.0, worst = 0.0;
};
inline LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  LineFit f;
  const double denominator = n * sxx - sx * sx;
  f.a = denominator != 0.0 ? (n * sxy - sx * sy) / denominator : 0.0;
  f.b = (sy - f.a * sx) / n;
  for (std::size_t i = 0; i < x.size(); ++i)
    f.worst = std::max(f.worst, std::abs(f.a * x[i] + f.b - y[i]));
  return f;
}

}  // namespace tumble_e2e

#pragma once
// Frames kept for a second pass (a GIF's palette is known only once every frame was seen):
// each deflated in memory with zlib at level 1. Rendered frames are mostly flat floor and sky,
// so they shrink several-fold for about a millisecond per 480x270 frame, and a clip's frames fit
// in memory at any length a GIF is made for.

#include <cstdint>
#include <vector>

namespace tumble {

class FrameStore {
 public:
  /// Keeps a copy of `size` bytes. Throws tumble::Error (Environment) when zlib fails.
  void add(const std::uint8_t* bytes, std::size_t size);
  /// Frame i (in the order added) back into `out`, which holds exactly its size.
  void get(std::size_t i, std::uint8_t* out, std::size_t size) const;
  std::size_t size() const { return frames_.size(); }
  /// Bytes held, deflated.
  std::size_t stored_bytes() const;

 private:
  std::vector<std::vector<std::uint8_t>> frames_;
};

}  // namespace tumble

#include "frame_store.hpp"

#include <zlib.h>  // zlib comes with libpng (PNG::PNG links it)

#include <string>

#include "tumble/error.hpp"

namespace tumble {

void FrameStore::add(const std::uint8_t* bytes, std::size_t size) {
  uLongf packed_size = compressBound(static_cast<uLong>(size));
  std::vector<std::uint8_t> packed(packed_size);
  // Level 1: most of what deflate finds in a rendered frame (long runs) at a fraction of the
  // time of the default level.
  const int result =
      compress2(packed.data(), &packed_size, bytes, static_cast<uLong>(size), Z_BEST_SPEED);
  if (result != Z_OK)
    throw Error(ErrorKind::Environment,
                "zlib: cannot keep a frame (error " + std::to_string(result) + ")");
  packed.resize(packed_size);
  packed.shrink_to_fit();
  frames_.push_back(std::move(packed));
}

void FrameStore::get(std::size_t i, std::uint8_t* out, std::size_t size) const {
  const std::vector<std::uint8_t>& packed = frames_.at(i);
  uLongf unpacked_size = static_cast<uLongf>(size);
  const int result = uncompress(out, &unpacked_size, packed.data(), packed.size());
  if (result != Z_OK || unpacked_size != size)
    throw Error(ErrorKind::Environment,
                "zlib: a kept frame does not unpack (error " + std::to_string(result) + ")");
}

std::size_t FrameStore::stored_bytes() const {
  std::size_t n = 0;
  for (const auto& f : frames_) n += f.size();
  return n;
}

}  // namespace tumble

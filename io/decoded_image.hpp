#pragma once
// An 8-bit image as the map image readers and io/png.hpp return it.

#include <cstdint>
#include <vector>

namespace retrace::io {

/// Interleaved 8-bit channels (1 grey, 2 grey + alpha, 3 colour, 4 colour + alpha), row 0 at the
/// top.
struct DecodedImage {
  int width = 0;
  int height = 0;
  int channels = 1;
  std::vector<std::uint8_t> data;
};

}  // namespace retrace::io

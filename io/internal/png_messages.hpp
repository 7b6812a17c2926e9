#pragma once
// libpng's messages caught, for io's PNG reader and writer: an error is kept, for one
// core::IoError, and libpng jumps back to the caller's setjmp; warnings (an sRGB profile it
// dislikes, an ancillary chunk's CRC) are benign by libpng's definition and are dropped rather
// than printed beside retrace's output.

#include <png.h>

#include <cstring>

namespace retrace::io::internal {

/// What libpng said when it gave up: the struct's error pointer.
struct PngMessage {
  char text[256] = {};
};

inline void OnPngError(png_structp png, png_const_charp message) {
  auto* kept = static_cast<PngMessage*>(png_get_error_ptr(png));
  std::strncpy(kept->text, message != nullptr ? message : "unknown error", sizeof(kept->text) - 1);
  png_longjmp(png, 1);
}

inline void OnPngWarning(png_structp, png_const_charp) {}

}  // namespace retrace::io::internal

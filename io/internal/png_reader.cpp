#include "io/internal/png_reader.hpp"

#include <png.h>

#include <csetjmp>
#include <cstring>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "io/internal/png_messages.hpp"

namespace retrace::io::internal {
namespace {

struct Source {
  std::string_view bytes;
  std::size_t at = 0;
  PngMessage message;  // libpng's, when it gives up
};

void OnRead(png_structp png, png_bytep out, png_size_t size) {
  auto* source = static_cast<Source*>(png_get_io_ptr(png));
  if (size > source->bytes.size() - source->at) png_error(png, "the file ends inside a chunk");
  std::memcpy(out, source->bytes.data() + source->at, size);
  source->at += size;
}

struct ReadStruct {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~ReadStruct() { png_destroy_read_struct(&png, info != nullptr ? &info : nullptr, nullptr); }
};

// The part that may longjmp: it creates no object with a destructor, and `image` and `rows`
// belong to the caller, so nothing is skipped or left indeterminate when libpng jumps back.
// Returns false with source.message set when libpng refused the file; sets `bit_depth` to the
// file's and returns true without decoding when it is 16.
bool Decode(png_structp png, png_infop info, Source& source, DecodedImage& image,
            std::vector<png_bytep>& rows, int& bit_depth) {
  if (setjmp(png_jmpbuf(png)) != 0) return false;
  png_set_read_fn(png, &source, OnRead);
  png_read_info(png, info);
  bit_depth = png_get_bit_depth(png, info);
  if (bit_depth == 16) return true;
  const int colour_type = png_get_color_type(png, info);
  if (colour_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colour_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS) != 0) png_set_tRNS_to_alpha(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  image.width = static_cast<int>(png_get_image_width(png, info));
  image.height = static_cast<int>(png_get_image_height(png, info));
  image.channels = png_get_channels(png, info);
  const std::size_t row_bytes = png_get_rowbytes(png, info);
  if (row_bytes !=
      static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.channels)) {
    png_error(png, "unexpected row layout");
  }
  image.data.resize(row_bytes * static_cast<std::size_t>(image.height));
  rows.resize(static_cast<std::size_t>(image.height));
  for (std::size_t r = 0; r < rows.size(); ++r) rows[r] = image.data.data() + r * row_bytes;
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  return true;
}

}  // namespace

DecodedImage ReadPng(std::string_view bytes, const std::filesystem::path& path) {
  Source source;
  source.bytes = bytes;
  ReadStruct read;
  read.png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, &source.message, OnPngError, OnPngWarning);
  if (read.png != nullptr) read.info = png_create_info_struct(read.png);
  if (read.png == nullptr || read.info == nullptr) {
    throw core::IoError(path.string() + ": cannot decode PNG: libpng could not start");
  }
  DecodedImage image;
  std::vector<png_bytep> rows;
  int bit_depth = 8;
  if (!Decode(read.png, read.info, source, image, rows, bit_depth)) {
    throw core::IoError(path.string() + ": cannot decode PNG: " + source.message.text);
  }
  if (bit_depth == 16) {
    throw core::IoError(path.string() +
                        ": only 8-bit images are supported (this one has 16-bit channels)");
  }
  return image;
}

}  // namespace retrace::io::internal

#include "io/png.hpp"

#include <png.h>

#include <csetjmp>
#include <vector>

#include "core/errors.hpp"
#include "io/internal/image_header.hpp"
#include "io/internal/png_messages.hpp"
#include "io/internal/png_reader.hpp"
#include "io/read_file.hpp"

namespace retrace::io {
namespace {

struct Sink {
  std::string bytes;
  internal::PngMessage message;  // libpng's, when it gives up
};

void OnWrite(png_structp png, png_bytep data, png_size_t size) {
  static_cast<Sink*>(png_get_io_ptr(png))->bytes.append(reinterpret_cast<const char*>(data), size);
}

void OnFlush(png_structp) {}

struct WriteStruct {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~WriteStruct() { png_destroy_write_struct(&png, info != nullptr ? &info : nullptr); }
};

// The part that may longjmp: it creates no object with a destructor, and `rows` belongs to the
// caller, so nothing is skipped when libpng jumps back. False with sink.message set on failure.
bool Encode(png_structp png, png_infop info, Sink& sink, int width, int height, int channels,
            std::vector<png_bytep>& rows) {
  if (setjmp(png_jmpbuf(png)) != 0) return false;
  png_set_write_fn(png, &sink, OnWrite, OnFlush);
  png_set_compression_level(png, 6);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               channels == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  return true;
}

}  // namespace

std::string EncodePng(std::span<const std::uint8_t> pixels, int width, int height, int channels) {
  if (width <= 0 || height <= 0 || (channels != 1 && channels != 3) ||
      pixels.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) *
                           static_cast<std::size_t>(channels)) {
    throw core::IoError("cannot encode PNG: " + std::to_string(pixels.size()) + " bytes are not " +
                        std::to_string(width) + " x " + std::to_string(height) + " pixels of " +
                        std::to_string(channels) + " channel(s)");
  }
  Sink sink;
  WriteStruct write;
  write.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink.message, internal::OnPngError,
                                      internal::OnPngWarning);
  if (write.png != nullptr) write.info = png_create_info_struct(write.png);
  if (write.png == nullptr || write.info == nullptr) {
    throw core::IoError("cannot encode PNG: libpng could not start");
  }
  const std::size_t row_bytes =
      static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
  std::vector<png_bytep> rows(static_cast<std::size_t>(height));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    // libpng's row type is mutable; it only reads the rows it writes.
    rows[r] = const_cast<png_bytep>(pixels.data() + r * row_bytes);
  }
  if (!Encode(write.png, write.info, sink, width, height, channels, rows)) {
    throw core::IoError(std::string("cannot encode PNG: ") + sink.message.text);
  }
  return std::move(sink.bytes);
}

DecodedImage ReadPngFile(const std::filesystem::path& path) {
  const std::string bytes = ReadFileBytes(path);
  if (bytes.empty()) throw core::IoError(path.string() + ": the image file is empty");
  if (internal::CheckImageHeader(bytes, path).format != internal::ImageFormat::kPng) {
    throw core::IoError(path.string() + ": not a PNG file");
  }
  return internal::ReadPng(bytes, path);
}

}  // namespace retrace::io

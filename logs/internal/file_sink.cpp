#include "logs/internal/file_sink.hpp"

#include "core/errors.hpp"

namespace retrace::logs::internal {

FileSink::FileSink(const std::filesystem::path& file)
    : name_(file.string()), out_(file, std::ios::binary | std::ios::trunc) {
  if (!out_) throw core::IoError(name_ + ": cannot create the file");
}

void FileSink::Put(std::span<const std::uint8_t> bytes) {
  out_.write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  if (!out_) throw core::IoError(name_ + ": cannot write at byte " + std::to_string(pos_));
  pos_ += bytes.size();
}

void FileSink::Patch(std::uint64_t offset, std::span<const std::uint8_t> bytes) {
  out_.seekp(static_cast<std::streamoff>(offset));
  out_.write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  out_.seekp(static_cast<std::streamoff>(pos_));
  if (!out_) throw core::IoError(name_ + ": cannot write at byte " + std::to_string(offset));
}

void FileSink::Finish() {
  out_.close();
  if (!out_) throw core::IoError(name_ + ": cannot finish writing the file");
}

}  // namespace retrace::logs::internal

#pragma once
// A binary file the log writers (MCAP, ROS 1 bags) write front to back, counting its bytes; one
// header may be patched in place before it is finished. Every failure throws core::IoError naming
// the file and, for a write, the byte it failed at.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>

namespace retrace::logs::internal {

class FileSink {
 public:
  /// Creates (or truncates) `file`.
  explicit FileSink(const std::filesystem::path& file);

  /// Appends `bytes`.
  void Put(std::span<const std::uint8_t> bytes);
  /// Overwrites the bytes at `offset` (before pos()) with `bytes`; appending continues at pos().
  void Patch(std::uint64_t offset, std::span<const std::uint8_t> bytes);
  /// Flushes and closes the file.
  void Finish();

  /// Bytes appended so far.
  std::uint64_t pos() const { return pos_; }
  const std::string& name() const { return name_; }

 private:
  std::string name_;
  std::ofstream out_;
  std::uint64_t pos_ = 0;
};

}  // namespace retrace::logs::internal

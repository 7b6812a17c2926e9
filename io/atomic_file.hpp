#pragma once
// Atomic file writes (docs/DESIGN.md §8): the contents go to a temporary file in the target's
// folder, which is flushed, closed and checked, then renamed over the target. A reader sees either
// the old file or the complete new one, never a partial file, and a failed write leaves no
// temporary file behind. Parent folders are created as needed. Not fsync'ed: the guarantee
// is against crashes and errors of the writing process, not against power loss.

#include <filesystem>
#include <fstream>
#include <ostream>
#include <string_view>

namespace retrace::io {

/// Writes `contents` to `path` atomically, replacing an existing file whole.
/// Throws core::IoError (naming the path and the reason) if a folder cannot be created or the
/// file cannot be written or renamed; the target is then untouched and no temporary is left.
void WriteFileAtomic(const std::filesystem::path& path, std::string_view contents);

/// A streamed atomic write: write to `stream()`, then `Commit()`. Destroying the object
/// without a successful Commit() removes the temporary file and leaves the target untouched
/// (so an exception thrown while writing never publishes a partial file).
class AtomicOutputFile {
 public:
  /// Creates missing parent folders and opens a temporary file beside `target` (binary mode).
  /// Throws core::IoError if either fails.
  explicit AtomicOutputFile(std::filesystem::path target);
  ~AtomicOutputFile();

  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;
  AtomicOutputFile(AtomicOutputFile&&) = delete;
  AtomicOutputFile& operator=(AtomicOutputFile&&) = delete;

  /// The stream to write to; valid until Commit().
  std::ostream& stream() { return out_; }
  const std::filesystem::path& target() const { return target_; }

  /// Flushes and closes the temporary file, checks for write errors and renames it over the
  /// target. Throws core::IoError on failure (the temporary file is removed). Call once.
  void Commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temp_;
  std::ofstream out_;
  bool committed_ = false;
};

}  // namespace retrace::io

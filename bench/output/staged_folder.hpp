#pragma once
// Publishes a results folder in one step: everything is written into `<final>.tmp`, which then
// takes the place of `final` atomically, so an interrupted or failed command never leaves a
// half-written results folder behind (the staging folder is removed unless committed).

#include <filesystem>

namespace retrace::bench {

/// Throws core::IoError ("<path>: exists and is not a folder") when `path` exists and is not a
/// folder: the check of an output folder before anything is written.
void RequireFolderOrNothing(const std::filesystem::path& path);

class StagedFolder {
 public:
  /// Creates `<final_dir>.tmp`, empty (an old staging folder, left by a killed command, is
  /// removed first). Throws core::IoError naming the folder when `final_dir` exists and is not a
  /// folder, or when the staging folder cannot be created.
  explicit StagedFolder(std::filesystem::path final_dir);
  ~StagedFolder();
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  const std::filesystem::path& path() const { return staging_; }
  /// Puts the staged folder in the final folder's place. An existing final folder is swapped
  /// with the staged one in one rename (Linux renameat2 RENAME_EXCHANGE) and then removed from
  /// the staging name: a process killed at any moment leaves either the old or the new folder
  /// complete under the final name. Where the filesystem cannot exchange, the old folder is
  /// first renamed to `<final>.old`. Throws core::IoError naming the folder on failure.
  void Commit();

 private:
  std::filesystem::path final_;
  std::filesystem::path staging_;
  bool committed_ = false;
};

}  // namespace retrace::bench

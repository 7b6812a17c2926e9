#pragma once
// Publishes a results folder in one step: everything is written into `<final>.tmp`, which then
// replaces `final`, so an interrupted or failed command never leaves a half-written results
// folder behind (the staging folder is removed unless committed).

#include <filesystem>
#include <system_error>
#include <utility>

namespace retrace::bench {

class StagedFolder {
 public:
  /// Creates `<final_dir>.tmp`, empty (an old staging folder is removed first).
  explicit StagedFolder(std::filesystem::path final_dir)
      : final_(std::move(final_dir)), staging_(final_.string() + ".tmp") {
    std::filesystem::remove_all(staging_);
    std::filesystem::create_directories(staging_);
  }
  ~StagedFolder() {
    std::error_code ignored;
    if (!committed_) std::filesystem::remove_all(staging_, ignored);
  }
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  const std::filesystem::path& path() const { return staging_; }
  /// Replaces the final folder with the staged one.
  void Commit() {
    std::filesystem::remove_all(final_);
    std::filesystem::rename(staging_, final_);
    committed_ = true;
  }

 private:
  std::filesystem::path final_;
  std::filesystem::path staging_;
  bool committed_ = false;
};

}  // namespace retrace::bench

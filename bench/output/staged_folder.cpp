#include "bench/output/staged_folder.hpp"

#include <fcntl.h>
#include <stdio.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>
#include <utility>

#include "core/errors.hpp"

namespace retrace::bench {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void Fail(const fs::path& folder, const std::string& what, const std::error_code& ec) {
  throw core::IoError(folder.string() + ": " + what + ": " + ec.message());
}

}  // namespace

void RequireFolderOrNothing(const fs::path& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::exists(status) && !fs::is_directory(status)) {
    throw core::IoError(path.string() +
                        ": exists and is not a folder (the output must be a folder)");
  }
}

StagedFolder::StagedFolder(fs::path final_dir)
    : final_(std::move(final_dir)), staging_(final_.string() + ".tmp") {
  RequireFolderOrNothing(final_);
  std::error_code ec;
  fs::remove_all(staging_, ec);
  if (ec) Fail(staging_, "cannot remove the staging folder of an earlier command", ec);
  fs::create_directories(staging_, ec);
  if (ec) Fail(staging_, "cannot create the staging folder", ec);
}

StagedFolder::~StagedFolder() {
  std::error_code ignored;
  if (!committed_) fs::remove_all(staging_, ignored);
}

void StagedFolder::Commit() {
  std::error_code ec;
  const bool replace = fs::exists(final_, ec);
  if (!replace) {
    fs::rename(staging_, final_, ec);
    if (ec) Fail(final_, "cannot publish the results", ec);
    committed_ = true;
    return;
  }
  if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, final_.c_str(), RENAME_EXCHANGE) == 0) {
    committed_ = true;
    fs::remove_all(staging_, ec);  // the old results, now under the staging name
    if (ec) Fail(staging_, "cannot remove the replaced results", ec);
    return;
  }
  if (errno != EINVAL && errno != ENOSYS && errno != ENOTSUP) {
    Fail(final_, "cannot publish the results", std::error_code(errno, std::generic_category()));
  }
  // No exchange on this filesystem: the old folder steps aside under `.old` first.
  const fs::path old = final_.string() + ".old";
  fs::remove_all(old, ec);
  if (ec) Fail(old, "cannot remove", ec);
  fs::rename(final_, old, ec);
  if (ec) Fail(final_, "cannot move the old results aside", ec);
  fs::rename(staging_, final_, ec);
  if (ec) Fail(final_, "cannot publish the results", ec);
  committed_ = true;
  fs::remove_all(old, ec);
  if (ec) Fail(old, "cannot remove the replaced results", ec);
}

}  // namespace retrace::bench

#include "io/atomic_file.hpp"

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <system_error>
#include <utility>

#include "core/check.hpp"
#include "core/errors.hpp"

namespace retrace::io {
namespace {

std::string ErrnoMessage(int err, const char* fallback) {
  return err != 0 ? std::generic_category().message(err) : std::string(fallback);
}

// A name unique across the threads of this process (counter) and across processes writing
// into the same folder, possibly on other hosts of a shared file system (random prefix).
std::filesystem::path TemporaryPathFor(const std::filesystem::path& target) {
  static const std::uint64_t process_tag = [] {
    std::random_device device;
    return (static_cast<std::uint64_t>(device()) << 32) ^ static_cast<std::uint64_t>(device());
  }();
  static std::atomic<std::uint64_t> counter{0};
  char suffix[48];
  std::snprintf(suffix, sizeof(suffix), ".tmp.%016llx.%llu",
                static_cast<unsigned long long>(process_tag),
                static_cast<unsigned long long>(counter.fetch_add(1)));
  // Hidden, so that globs over the folder do not pick up a half-written file.
  std::string name = ".";
  name += target.filename().string();
  name += suffix;
  return target.parent_path() / name;
}

}  // namespace

AtomicOutputFile::AtomicOutputFile(std::filesystem::path target) : target_(std::move(target)) {
  const std::filesystem::path name = target_.filename();
  if (name.empty() || name == "." || name == "..") {
    throw core::IoError(target_.string() + ": cannot write: not a file name");
  }
  const std::filesystem::path parent = target_.parent_path();
  if (!parent.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(parent, ec);
    if (ec) {
      throw core::IoError(target_.string() + ": cannot create folder " + parent.string() + ": " +
                          ec.message());
    }
  }
  temp_ = TemporaryPathFor(target_);
  errno = 0;
  out_.open(temp_, std::ios::binary | std::ios::trunc);
  if (!out_) {
    const int err = errno;
    std::error_code ignored;
    std::filesystem::remove(temp_, ignored);
    throw core::IoError(target_.string() + ": cannot create a file in " +
                        (parent.empty() ? std::string(".") : parent.string()) + ": " +
                        ErrnoMessage(err, "open failed"));
  }
}

AtomicOutputFile::~AtomicOutputFile() {
  if (committed_) return;
  out_.close();
  std::error_code ignored;
  std::filesystem::remove(temp_, ignored);
}

void AtomicOutputFile::Commit() {
  RETRACE_CHECK(!committed_);
  const bool failed_before = !out_.good();
  const int err_before = errno;
  errno = 0;
  out_.flush();
  out_.close();
  if (failed_before || out_.fail()) {
    const int err = failed_before ? err_before : errno;
    std::error_code ignored;
    std::filesystem::remove(temp_, ignored);
    throw core::IoError(target_.string() +
                        ": cannot write file: " + ErrnoMessage(err, "write error"));
  }
  std::error_code ec;
  std::filesystem::rename(temp_, target_, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(temp_, ignored);
    throw core::IoError(target_.string() + ": cannot replace file: " + ec.message());
  }
  committed_ = true;
}

void WriteFileAtomic(const std::filesystem::path& path, std::string_view contents) {
  AtomicOutputFile file(path);
  file.stream().write(contents.data(), static_cast<std::streamsize>(contents.size()));
  file.Commit();
}

}  // namespace retrace::io

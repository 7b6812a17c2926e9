#pragma once
// A fresh temporary folder for a test, removed with everything in it when the TempDir goes,
// and a fixture holding one:
//
//   retrace::testing::TempDir tmp;
//   const std::filesystem::path route = tmp.Write("route.txt", "0 0\n10 0\n");
//   EXPECT_EQ(tmp.Read("route.txt"), "0 0\n10 0\n");

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>

namespace retrace::testing {

/// A unique folder below std::filesystem::temp_directory_path(), removed with all its contents
/// when the TempDir is destroyed.
class TempDir {
 public:
  /// Creates `<temp>/retrace_<suite>_<test>_<pid>_<n>`: the running test's name, the process
  /// id and a per-process counter, so that parallel ctest runs and several TempDirs in one
  /// test never share a folder.
  TempDir() {
    static std::atomic<int> counter{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    // Built by appending: GCC 12 warns falsely (-Wrestrict) on "..." + std::string(...).
    std::string name = "retrace_";
    if (info != nullptr) {
      name += info->test_suite_name();
      name += '_';
      name += info->name();
    } else {
      name += "notest";
    }
    name += '_';
    name += std::to_string(::getpid());
    name += '_';
    name += std::to_string(counter++);
    for (char& c : name) {
      // Parameterised tests have '/' in their names.
      if (std::isalnum(static_cast<unsigned char>(c)) == 0 && c != '_' && c != '-') c = '_';
    }
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }

  /// Removes the folder even if a test took away its write permission.
  ~TempDir() {
    std::error_code ec;
    std::filesystem::permissions(path_, std::filesystem::perms::owner_all,
                                 std::filesystem::perm_options::add, ec);
    std::filesystem::remove_all(path_, ec);
  }

  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

  /// Writes `bytes` unchanged (binary mode) to `name` inside the folder; returns its path.
  std::filesystem::path Write(const std::filesystem::path& name, std::string_view bytes) const {
    const std::filesystem::path file = path_ / name;
    std::ofstream(file, std::ios::binary) << bytes;
    return file;
  }

  /// The bytes of `file`: a name inside the folder or any absolute path; "" if unreadable.
  std::string Read(const std::filesystem::path& file) const {
    std::ifstream in(path_ / file, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }

 private:
  std::filesystem::path path_;
};

/// A fixture for tests that need nothing but a fresh folder `tmp_`; name it per suite with
/// `using MyTest = retrace::testing::TempDirTest;`.
class TempDirTest : public ::testing::Test {
 protected:
  TempDir tmp_;
};

}  // namespace retrace::testing

#include "io/atomic_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/errors.hpp"

namespace retrace::io {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test, removed afterwards.
class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("retrace_io_" + std::string(info->test_suite_name()) + "_" +
                                        info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(dir_, ec);
  }

  static std::string Slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }

  // Names of every entry below dir_, hidden ones included.
  std::vector<std::string> Entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(dir_)) {
      names.push_back(fs::relative(e.path(), dir_).string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path dir_;
};

TEST_F(AtomicFileTest, WritesFileAndCreatesMissingParentFolders) {
  const fs::path target = dir_ / "a" / "b" / "out.txt";
  WriteFileAtomic(target, "hello\n");
  EXPECT_EQ(Slurp(target), "hello\n");
  EXPECT_EQ(Entries(), (std::vector<std::string>{"a", "a/b", "a/b/out.txt"}));
}

TEST_F(AtomicFileTest, ReplacesExistingTargetWhole) {
  const fs::path target = dir_ / "out.txt";
  WriteFileAtomic(target, std::string(10000, 'x'));
  WriteFileAtomic(target, "short");
  EXPECT_EQ(Slurp(target), "short");
  EXPECT_EQ(Entries(), (std::vector<std::string>{"out.txt"}));
}

TEST_F(AtomicFileTest, WritesEmptyAndBinaryContents) {
  const fs::path target = dir_ / "bin";
  const std::string bytes("a\0b\r\n\xff", 6);
  WriteFileAtomic(target, bytes);
  EXPECT_EQ(Slurp(target), bytes);
  WriteFileAtomic(target, "");
  EXPECT_EQ(fs::file_size(target), 0u);
}

TEST_F(AtomicFileTest, InvalidLocationThrowsIoErrorAndLeavesNothing) {
  // The parent "folder" is a regular file: the folder cannot be created.
  WriteFileAtomic(dir_ / "blocker", "I am a file");
  const fs::path target = dir_ / "blocker" / "sub" / "out.csv";
  try {
    WriteFileAtomic(target, "data");
    FAIL() << "expected IoError";
  } catch (const core::IoError& e) {
    EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(Entries(), (std::vector<std::string>{"blocker"}));
  EXPECT_EQ(Slurp(dir_ / "blocker"), "I am a file");
}

TEST_F(AtomicFileTest, FailedRenameThrowsIoErrorAndRemovesTemporary) {
  // The target is an existing non-empty folder: writing the temporary works, renaming fails.
  fs::create_directories(dir_ / "out.txt" / "keep");
  try {
    WriteFileAtomic(dir_ / "out.txt", "data");
    FAIL() << "expected IoError";
  } catch (const core::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("out.txt"), std::string::npos) << e.what();
  }
  EXPECT_EQ(Entries(), (std::vector<std::string>{"out.txt", "out.txt/keep"}));
}

TEST_F(AtomicFileTest, EmptyFileNameThrowsIoError) {
  EXPECT_THROW(WriteFileAtomic(dir_ / "", "data"), core::IoError);
  EXPECT_THROW(WriteFileAtomic(dir_ / "..", "data"), core::IoError);
}

TEST_F(AtomicFileTest, StreamedWriteIsInvisibleUntilCommit) {
  const fs::path target = dir_ / "out.txt";
  AtomicOutputFile file(target);
  file.stream() << "line " << 1 << "\n";
  EXPECT_FALSE(fs::exists(target));
  const auto entries = Entries();
  ASSERT_EQ(entries.size(), 1u);
  EXPECT_EQ(entries[0].front(), '.') << "temporary files are hidden: " << entries[0];
  file.Commit();
  EXPECT_EQ(Slurp(target), "line 1\n");
  EXPECT_EQ(Entries(), (std::vector<std::string>{"out.txt"}));
}

TEST_F(AtomicFileTest, ExceptionBeforeCommitKeepsOldTargetAndRemovesTemporary) {
  const fs::path target = dir_ / "out.txt";
  WriteFileAtomic(target, "old complete contents");
  try {
    AtomicOutputFile file(target);
    file.stream() << "new but";
    throw std::runtime_error("failure half-way");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(Slurp(target), "old complete contents");
  EXPECT_EQ(Entries(), (std::vector<std::string>{"out.txt"}));
}

TEST_F(AtomicFileTest, ConcurrentWritersUseDistinctTemporaries) {
  AtomicOutputFile a(dir_ / "a.txt");
  AtomicOutputFile b(dir_ / "a.txt");
  a.stream() << "from a";
  b.stream() << "from b";
  a.Commit();
  b.Commit();
  EXPECT_EQ(Slurp(dir_ / "a.txt"), "from b");
  EXPECT_EQ(Entries(), (std::vector<std::string>{"a.txt"}));
}

}  // namespace
}  // namespace retrace::io

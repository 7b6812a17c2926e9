#include "io/atomic_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::io {
namespace {

namespace fs = std::filesystem;

class AtomicFileTest : public ::testing::Test {
 protected:
  // Names of every entry below the folder, hidden ones included.
  std::vector<std::string> Entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(tmp_.path())) {
      names.push_back(fs::relative(e.path(), tmp_.path()).string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

  retrace::testing::TempDir tmp_;
};

TEST_F(AtomicFileTest, WritesFileAndCreatesMissingParentFolders) {
  const fs::path target = tmp_.path() / "a" / "b" / "out.txt";
  WriteFileAtomic(target, "hello\n");
  EXPECT_EQ(tmp_.Read(target), "hello\n");
  EXPECT_EQ(Entries(), (std::vector<std::string>{"a", "a/b", "a/b/out.txt"}));
}

TEST_F(AtomicFileTest, ReplacesExistingTargetWhole) {
  const fs::path target = tmp_.path() / "out.txt";
  WriteFileAtomic(target, std::string(10000, 'x'));
  WriteFileAtomic(target, "short");
  EXPECT_EQ(tmp_.Read(target), "short");
  EXPECT_EQ(Entries(), (std::vector<std::string>{"out.txt"}));
}

TEST_F(AtomicFileTest, WritesEmptyAndBinaryContents) {
  const fs::path target = tmp_.path() / "bin";
  const std::string bytes("a\0b\r\n\xff", 6);
  WriteFileAtomic(target, bytes);
  EXPECT_EQ(tmp_.Read(target), bytes);
  WriteFileAtomic(target, "");
  EXPECT_EQ(fs::file_size(target), 0u);
}

TEST_F(AtomicFileTest, InvalidLocationThrowsIoErrorAndLeavesNothing) {
  // The parent "folder" is a regular file: the folder cannot be created.
  WriteFileAtomic(tmp_.path() / "blocker", "I am a file");
  const fs::path target = tmp_.path() / "blocker" / "sub" / "out.csv";
  try {
    WriteFileAtomic(target, "data");
    FAIL() << "expected IoError";
  } catch (const core::IoError& e) {
    EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(Entries(), (std::vector<std::string>{"blocker"}));
  EXPECT_EQ(tmp_.Read(tmp_.path() / "blocker"), "I am a file");
}

TEST_F(AtomicFileTest, FailedRenameThrowsIoErrorAndRemovesTemporary) {
  // The target is an existing non-empty folder: writing the temporary works, renaming fails.
  fs::create_directories(tmp_.path() / "out.txt" / "keep");
  try {
    WriteFileAtomic(tmp_.path() / "out.txt", "data");
    FAIL() << "expected IoError";
  } catch (const core::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("out.txt"), std::string::npos) << e.what();
  }
  EXPECT_EQ(Entries(), (std::vector<std::string>{"out.txt", "out.txt/keep"}));
}

TEST_F(AtomicFileTest, EmptyFileNameThrowsIoError) {
  EXPECT_THROW(WriteFileAtomic(tmp_.path() / "", "data"), core::IoError);
  EXPECT_THROW(WriteFileAtomic(tmp_.path() / "..", "data"), core::IoError);
}

TEST_F(AtomicFileTest, StreamedWriteIsInvisibleUntilCommit) {
  const fs::path target = tmp_.path() / "out.txt";
  AtomicOutputFile file(target);
  file.stream() << "line " << 1 << "\n";
  EXPECT_FALSE(fs::exists(target));
  const auto entries = Entries();
  ASSERT_EQ(entries.size(), 1u);
  EXPECT_EQ(entries[0].front(), '.') << "temporary files are hidden: " << entries[0];
  file.Commit();
  EXPECT_EQ(tmp_.Read(target), "line 1\n");
  EXPECT_EQ(Entries(), (std::vector<std::string>{"out.txt"}));
}

TEST_F(AtomicFileTest, ExceptionBeforeCommitKeepsOldTargetAndRemovesTemporary) {
  const fs::path target = tmp_.path() / "out.txt";
  WriteFileAtomic(target, "old complete contents");
  try {
    AtomicOutputFile file(target);
    file.stream() << "new but";
    throw std::runtime_error("failure half-way");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(tmp_.Read(target), "old complete contents");
  EXPECT_EQ(Entries(), (std::vector<std::string>{"out.txt"}));
}

TEST_F(AtomicFileTest, ConcurrentWritersUseDistinctTemporaries) {
  AtomicOutputFile a(tmp_.path() / "a.txt");
  AtomicOutputFile b(tmp_.path() / "a.txt");
  a.stream() << "from a";
  b.stream() << "from b";
  a.Commit();
  b.Commit();
  EXPECT_EQ(tmp_.Read(tmp_.path() / "a.txt"), "from b");
  EXPECT_EQ(Entries(), (std::vector<std::string>{"a.txt"}));
}

}  // namespace
}  // namespace retrace::io

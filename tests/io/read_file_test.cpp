#include "io/read_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "core/errors.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::io {
namespace {

using ::testing::EndsWith;

std::string ErrorOf(const std::filesystem::path& path) {
  try {
    ReadFileBytes(path);
  } catch (const core::IoError& e) {
    return e.what();
  }
  return "";
}

TEST(ReadFile, ReturnsEveryByteUnchanged) {
  const retrace::testing::TempDir tmp;
  const std::string bytes("a,b\r\n\0\xff\n", 8);
  std::ofstream(tmp.path() / "f.bin", std::ios::binary) << bytes;
  EXPECT_EQ(ReadFileBytes(tmp.path() / "f.bin"), bytes);
  std::ofstream(tmp.path() / "empty.txt", std::ios::binary).flush();
  EXPECT_EQ(ReadFileBytes(tmp.path() / "empty.txt"), "");
}

TEST(ReadFile, AMissingFileOrAFolderCannotBeOpened) {
  const retrace::testing::TempDir tmp;
  EXPECT_THAT(ErrorOf(tmp.path() / "missing.yaml"), EndsWith("missing.yaml: cannot open file"));
  EXPECT_THAT(ErrorOf(tmp.path()), EndsWith(": cannot open file"));
}

}  // namespace
}  // namespace retrace::io

#include "io/json_writer.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <string>

#include "core/errors.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::io {
namespace {

namespace fs = std::filesystem;

using JsonTest = retrace::testing::TempDirTest;

TEST_F(JsonTest, WritesPrettyTwoSpaceJsonWithNullForNonFinite) {
  nlohmann::json j;
  j["a"] = 0.1;
  j["b"] = std::numeric_limits<double>::quiet_NaN();
  j["c"] = {1, -std::numeric_limits<double>::infinity()};
  const fs::path path = tmp_.path() / "sub" / "metrics.json";
  WriteJsonAtomic(path, j);
  EXPECT_EQ(tmp_.Read(path),
            "{\n"
            "  \"a\": 0.1,\n"
            "  \"b\": null,\n"
            "  \"c\": [\n"
            "    1,\n"
            "    null\n"
            "  ]\n"
            "}\n");
}

TEST_F(JsonTest, RoundTripKeepsDoublesExactly) {
  nlohmann::json j = {{"third", 1.0 / 3.0},
                      {"tiny", 4.9e-324},
                      {"big", 1.7976931348623157e308},
                      {"name", "run \"1\""},
                      {"list", {1, 2, 3}}};
  WriteJsonAtomic(tmp_.path() / "x.json", j);
  const nlohmann::json back = ReadJsonFile(tmp_.path() / "x.json");
  EXPECT_EQ(back, j);
  EXPECT_EQ(back["third"].get<double>(), 1.0 / 3.0);
}

TEST_F(JsonTest, ParseErrorNamesFileLineAndColumn) {
  tmp_.Write("bad.json", "{\n  \"a\": tru, \"b\": 1\n}\n");
  try {
    ReadJsonFile(tmp_.path() / "bad.json");
    FAIL() << "expected IoError";
  } catch (const core::IoError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find((tmp_.path() / "bad.json").string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("line 2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("column"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("json.exception"), std::string::npos) << msg;
  }
}

TEST_F(JsonTest, MissingOrEmptyFileIsIoError) {
  EXPECT_THROW(ReadJsonFile(tmp_.path() / "missing.json"), core::IoError);
  tmp_.Write("empty.json", "");
  EXPECT_THROW(ReadJsonFile(tmp_.path() / "empty.json"), core::IoError);
  EXPECT_THROW(ReadJsonFile(tmp_.path()), core::IoError);
}

TEST_F(JsonTest, WriteIntoInvalidLocationThrowsIoError) {
  tmp_.Write("file", "x");
  EXPECT_THROW(WriteJsonAtomic(tmp_.path() / "file" / "m.json", nlohmann::json::object()),
               core::IoError);
}

}  // namespace
}  // namespace retrace::io

#include "io/json_writer.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "core/errors.hpp"

namespace retrace::io {
namespace {

namespace fs = std::filesystem;

class JsonTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("retrace_io_" + std::string(info->test_suite_name()) + "_" +
                                        info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string Slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }

  fs::path dir_;
};

TEST_F(JsonTest, WritesPrettyTwoSpaceJsonWithNullForNonFinite) {
  nlohmann::json j;
  j["a"] = 0.1;
  j["b"] = std::numeric_limits<double>::quiet_NaN();
  j["c"] = {1, -std::numeric_limits<double>::infinity()};
  const fs::path path = dir_ / "sub" / "metrics.json";
  WriteJsonAtomic(path, j);
  EXPECT_EQ(Slurp(path),
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
  WriteJsonAtomic(dir_ / "x.json", j);
  const nlohmann::json back = ReadJsonFile(dir_ / "x.json");
  EXPECT_EQ(back, j);
  EXPECT_EQ(back["third"].get<double>(), 1.0 / 3.0);
}

TEST_F(JsonTest, ParseErrorNamesFileLineAndColumn) {
  std::ofstream(dir_ / "bad.json") << "{\n  \"a\": tru, \"b\": 1\n}\n";
  try {
    ReadJsonFile(dir_ / "bad.json");
    FAIL() << "expected IoError";
  } catch (const core::IoError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find((dir_ / "bad.json").string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("line 2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("column"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("json.exception"), std::string::npos) << msg;
  }
}

TEST_F(JsonTest, MissingOrEmptyFileIsIoError) {
  EXPECT_THROW(ReadJsonFile(dir_ / "missing.json"), core::IoError);
  std::ofstream(dir_ / "empty.json").close();
  EXPECT_THROW(ReadJsonFile(dir_ / "empty.json"), core::IoError);
  EXPECT_THROW(ReadJsonFile(dir_), core::IoError);
}

TEST_F(JsonTest, WriteIntoInvalidLocationThrowsIoError) {
  std::ofstream(dir_ / "file") << "x";
  EXPECT_THROW(WriteJsonAtomic(dir_ / "file" / "m.json", nlohmann::json::object()), core::IoError);
}

}  // namespace
}  // namespace retrace::io

#include "io/csv_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>

#include "core/errors.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::io {
namespace {

namespace fs = std::filesystem;

using CsvWriterTest = retrace::testing::TempDirTest;

TEST(CsvCell, QuotesOnlyWhereNeeded) {
  EXPECT_EQ(CsvCell("plain").text(), "plain");
  EXPECT_EQ(CsvCell("").text(), "");
  EXPECT_EQ(CsvCell("a,b").text(), "\"a,b\"");
  EXPECT_EQ(CsvCell("say \"hi\"").text(), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(CsvCell("two\nlines").text(), "\"two\nlines\"");
  EXPECT_EQ(CsvCell("cr\r").text(), "\"cr\r\"");
  EXPECT_EQ(CsvCell(" padded").text(), "\" padded\"");
  EXPECT_EQ(CsvCell(std::string("s")).text(), "s");
}

TEST(CsvCell, NumbersUseShortestRoundTripText) {
  EXPECT_EQ(CsvCell(0.1).text(), "0.1");
  EXPECT_EQ(CsvCell(1.0).text(), "1");
  EXPECT_EQ(CsvCell(-2.5e-300).text(), "-2.5e-300");
  EXPECT_EQ(CsvCell(1.0 / 3.0).text(), "0.3333333333333333");
  EXPECT_EQ(std::stod(CsvCell(1.0 / 3.0).text()), 1.0 / 3.0);
  EXPECT_EQ(CsvCell(42).text(), "42");
  EXPECT_EQ(CsvCell(-7L).text(), "-7");
  EXPECT_EQ(CsvCell(std::size_t{18446744073709551615u}).text(), "18446744073709551615");
  EXPECT_EQ(CsvCell(std::int64_t{-9223372036854775807LL - 1}).text(), "-9223372036854775808");
  EXPECT_EQ(CsvCell(true).text(), "true");
  EXPECT_EQ(CsvCell(false).text(), "false");
  EXPECT_EQ(CsvCell(0.5f).text(), "0.5");
}

TEST(CsvCell, NonFiniteNumbersAreNanAndInf) {
  EXPECT_EQ(CsvCell(std::numeric_limits<double>::quiet_NaN()).text(), "nan");
  EXPECT_EQ(CsvCell(-std::numeric_limits<double>::quiet_NaN()).text(), "nan");
  EXPECT_EQ(CsvCell(std::numeric_limits<double>::infinity()).text(), "inf");
  EXPECT_EQ(CsvCell(-std::numeric_limits<double>::infinity()).text(), "-inf");
}

TEST_F(CsvWriterTest, WritesHeaderAndMixedRowsOnCommit) {
  const fs::path path = tmp_.path() / "runs" / "events.csv";
  CsvWriter csv(path, {"t", "event", "value", "count"});
  csv.AddRow({0.05, "switch, map 1", std::numeric_limits<double>::quiet_NaN(), 3});
  csv.AddRow({1e-3, "goal", -std::numeric_limits<double>::infinity(), std::size_t{0}});
  EXPECT_EQ(csv.rows(), 2u);
  EXPECT_EQ(csv.columns(), 4u);
  EXPECT_FALSE(fs::exists(path));
  csv.Commit();
  EXPECT_EQ(tmp_.Read(path),
            "t,event,value,count\n"
            "0.05,\"switch, map 1\",nan,3\n"
            "0.001,goal,-inf,0\n");
}

TEST_F(CsvWriterTest, UncommittedWriterLeavesNoFile) {
  {
    CsvWriter csv(tmp_.path() / "out.csv", {"a"});
    csv.AddRow({1});
  }
  EXPECT_TRUE(fs::is_empty(tmp_.path()));
}

TEST_F(CsvWriterTest, InvalidLocationThrowsIoError) {
  tmp_.Write("file", "x");
  EXPECT_THROW(CsvWriter(tmp_.path() / "file" / "out.csv", {"a"}), core::IoError);
}

}  // namespace
}  // namespace retrace::io

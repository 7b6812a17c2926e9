#include "io/csv_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "io/csv_writer.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::io {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::string ErrorOf(std::string_view text) {
  try {
    ParseCsv(text, "t.csv");
  } catch (const core::IoError& e) {
    return e.what();
  }
  return "";
}

TEST(CsvReader, ReadsBackWhatTheWriterQuotes) {
  retrace::testing::TempDir tmp;
  const auto file = tmp.path() / "t.csv";
  CsvWriter csv(file, {"name", "value"});
  csv.AddRow({"a, b", 1.5});
  csv.AddRow({"say \"hi\"\nthere", std::nan("")});
  csv.AddRow({" pad", -0.25});
  csv.Commit();
  const std::vector<CsvRecord> records = ReadCsvFile(file);
  ASSERT_EQ(records.size(), 4u);
  EXPECT_THAT(records[0].cells, ElementsAre("name", "value"));
  EXPECT_THAT(records[1].cells, ElementsAre("a, b", "1.5"));
  EXPECT_THAT(records[2].cells, ElementsAre("say \"hi\"\nthere", "nan"));
  EXPECT_THAT(records[3].cells, ElementsAre(" pad", "-0.25"));
  // A record starts on the line where it begins; the quoted line break moves the next one on.
  EXPECT_EQ(records[2].line, 3);
  EXPECT_EQ(records[3].line, 5);
}

TEST(CsvReader, TakesCrLfAndSkipsBlankLines) {
  const auto records = ParseCsv("a,b\r\n\r\n1,2\r\n,\n", "t.csv");
  ASSERT_EQ(records.size(), 3u);
  EXPECT_THAT(records[1].cells, ElementsAre("1", "2"));
  EXPECT_EQ(records[1].line, 3);
  EXPECT_THAT(records[2].cells, ElementsAre("", ""));
}

TEST(CsvReader, NamesTheLineOfBrokenQuoting) {
  EXPECT_THAT(ErrorOf("a,b\n1,x\"y\n"), HasSubstr("t.csv:2: a double quote inside a cell"));
  EXPECT_THAT(ErrorOf("a\n\"x\"y\n"), HasSubstr("t.csv:2: text after the closing quote"));
  EXPECT_THAT(ErrorOf("a\nb\n\"open\n"), HasSubstr("t.csv:3: a quoted cell is not closed"));
  EXPECT_EQ(ErrorOf("a,\"b\"\"c\"\n"), "");
}

TEST(CsvReader, SplitsOneRecordOrRefusesIt) {
  EXPECT_THAT(*SplitCsvRecord("x,\"a, b\",,\"\"\"\""), ElementsAre("x", "a, b", "", "\""));
  EXPECT_THAT(*SplitCsvRecord(""), ElementsAre(""));
  EXPECT_FALSE(SplitCsvRecord("\"unterminated,1").has_value());
  EXPECT_FALSE(SplitCsvRecord("\"a\"b,1").has_value());
  EXPECT_FALSE(SplitCsvRecord("a\"b,1").has_value());
  EXPECT_FALSE(SplitCsvRecord("a,\"b\nc\"").has_value());
  EXPECT_FALSE(SplitCsvRecord("a,b\r").has_value());
}

TEST(CsvReader, ParsesNumberCellsAsTheWriterFormatsThem) {
  for (double v : {0.0, -1.25, 1e-300, 3.141592653589793, 1e22}) {
    EXPECT_EQ(ParseCsvNumber(FormatCsvNumber(v)), v);
  }
  EXPECT_TRUE(std::isnan(*ParseCsvNumber("nan")));
  EXPECT_TRUE(std::isnan(*ParseCsvNumber("NaN")));
  EXPECT_EQ(ParseCsvNumber("-inf"), -INFINITY);
  EXPECT_EQ(ParseCsvNumber(" +2.5\t"), 2.5);
  for (const char* bad : {"", " ", "+", "+-1", "1.5x", "1,5", "0x10", "--1", "++1"}) {
    EXPECT_FALSE(ParseCsvNumber(bad).has_value()) << bad;
  }
}

TEST(CsvReader, SaysWhenTheFileCannotBeRead) {
  retrace::testing::TempDir tmp;
  EXPECT_THROW(ReadCsvFile(tmp.path() / "missing.csv"), core::IoError);
  EXPECT_THROW(ReadCsvFile(tmp.path()), core::IoError);
}

}  // namespace
}  // namespace retrace::io

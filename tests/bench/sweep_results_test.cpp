#include "bench/sweep/sweep_results.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "bench/sweep/sweep_summary.hpp"
#include "core/errors.hpp"
#include "io/csv_reader.hpp"
#include "tests/support/temp_dir.hpp"

namespace retrace::bench {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

using SweepResultsTest = retrace::testing::TempDirTest;

const SweepTableSchema kSchema = ResultsSchema({"a.b", "mount"}, {"success_rate", "err"});
const std::string kResultsHeader = "case,combo,repeat,seed,a.b,mount,success_rate,err\n";

std::vector<io::CsvCell> Row(std::size_t id, double err) {
  return {id, id / 2, id % 2, 10 + id % 2, "x", "[1, 2]", 1.0, err};
}

std::string Line(std::size_t id, double err) {
  const auto cells = Row(id, err);
  return CsvLine(cells) + "\n";
}

TEST(SweepCsv, LineQuotesCellsTheWayTheReaderUndoes) {
  const std::vector<io::CsvCell> cells = {"plain", "a, b", "say \"hi\"", " pad",
                                          1.5,     "",     "[0.1, 0, 0]"};
  const std::string line = CsvLine(cells);
  EXPECT_EQ(line, "plain,\"a, b\",\"say \"\"hi\"\"\",\" pad\",1.5,,\"[0.1, 0, 0]\"");
  const auto fields = io::SplitCsvRecord(line);
  ASSERT_TRUE(fields.has_value());
  EXPECT_THAT(*fields,
              ElementsAre("plain", "a, b", "say \"hi\"", " pad", "1.5", "", "[0.1, 0, 0]"));
}

TEST(SweepCsv, RowsNeedTheirFieldCountAndKinds) {
  EXPECT_TRUE(ParseSweepRow("3,1,1,11,x,\"[1, 2]\",1,0.25", kSchema).has_value());
  EXPECT_TRUE(ParseSweepRow("3,1,1,11,x,y,nan,-inf", kSchema).has_value());
  EXPECT_EQ(ParseSweepRow("3,1,1,11,x,y,1,2e-05", kSchema)->case_id, 3u);
  EXPECT_FALSE(ParseSweepRow("3,1,1,11,x,y,1", kSchema).has_value());        // a field short
  EXPECT_FALSE(ParseSweepRow("3,1,1,11,x,y,1,0.2,9", kSchema).has_value());  // a field too many
  EXPECT_FALSE(ParseSweepRow("3,1,1,11,x,y,1,0.2x", kSchema).has_value());   // not a number
  EXPECT_FALSE(ParseSweepRow("3,1,1,11,x,y,1,", kSchema).has_value());       // empty number
  EXPECT_FALSE(ParseSweepRow("-3,1,1,11,x,y,1,0.2", kSchema).has_value());   // not a case id
  EXPECT_FALSE(ParseSweepRow("3,1,1,11,x,\"y,1,0.2", kSchema).has_value());  // cut inside quotes
}

TEST_F(SweepResultsTest, AppendedRowsReadBackInFileOrder) {
  const auto file = tmp_.path() / "results.csv";
  {
    SweepTableAppender appender(file, kSchema, 0);
    appender.Append(Row(5, 0.5));
    appender.Append(Row(2, 0.25));
  }
  EXPECT_EQ(tmp_.Read("results.csv"), kResultsHeader + Line(5, 0.5) + Line(2, 0.25));
  const SweepTable table = ReadSweepTable(file, kSchema, PartialRow::kReject);
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(table.rows[0].case_id, 5u);
  EXPECT_EQ(table.rows[0].line_number, 2);
  EXPECT_EQ(table.rows[1].fields[5], "[1, 2]");
  EXPECT_EQ(table.complete_size, table.file_size);
  EXPECT_TRUE(table.dropped.empty());
}

TEST_F(SweepResultsTest, AMissingTableIsEmpty) {
  const SweepTable table = ReadSweepTable(tmp_.path() / "none.csv", kSchema, PartialRow::kReject);
  EXPECT_FALSE(table.exists);
  EXPECT_TRUE(table.rows.empty());
  EXPECT_EQ(table.complete_size, 0u);
}

// What an interrupted append can leave at the end of the file, and what a resume must drop.
class SweepPartialRow : public retrace::testing::TempDirTest,
                        public ::testing::WithParamInterface<std::string> {};

TEST_P(SweepPartialRow, IsDroppedOnResumeAndTheNextAppendFollowsTheLastGoodRow) {
  const std::string good = kResultsHeader + Line(0, 0.5) + Line(3, 0.75);
  const auto file = tmp_.Write("results.csv", good + GetParam());
  const SweepTable table = ReadSweepTable(file, kSchema, PartialRow::kDrop);
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(table.complete_size, good.size());
  EXPECT_EQ(table.dropped + "\n", GetParam().back() == '\n' ? GetParam() : GetParam() + "\n");
  // A merge wants the table whole.
  EXPECT_THROW(ReadSweepTable(file, kSchema, PartialRow::kReject), core::IoError);
  {
    SweepTableAppender appender(file, kSchema, table.complete_size);
    appender.Append(Row(1, 0.125));
  }
  EXPECT_EQ(tmp_.Read("results.csv"), good + Line(1, 0.125));
}

INSTANTIATE_TEST_SUITE_P(
    SweepTails, SweepPartialRow,
    ::testing::Values("1,0,1,11,x,\"[1, 2]\",1,0.12",  // no line break: cut mid-number
                      "1,0,1,11,x,\"[1,",              // cut inside a quoted field
                      "1,0,1,11,x\n",                  // wrong field count
                      "1,0,1,11,x,y,1,0.1.2\n",        // unparsable number
                      "\n"));                          // an empty line

TEST_F(SweepResultsTest, ABadRowBeforeTheLastIsAnError) {
  const auto file = tmp_.Write("results.csv", kResultsHeader + Line(0, 0.5) + "garbage\n" + Line(3, 0.75));
  try {
    ReadSweepTable(file, kSchema, PartialRow::kDrop);
    FAIL();
  } catch (const core::IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("results.csv:3: not a row of this sweep's table"));
  }
}

TEST_F(SweepResultsTest, ACaseGivenTwiceIsAnError) {
  const auto file = tmp_.Write("results.csv", kResultsHeader + Line(4, 0.5) + Line(4, 0.5));
  EXPECT_THROW(ReadSweepTable(file, kSchema, PartialRow::kDrop), core::IoError);
}

TEST_F(SweepResultsTest, AnotherHeaderIsAnError) {
  const auto file =
      tmp_.Write("results.csv", "case,combo,repeat,seed,other,mount,success_rate,err\n");
  try {
    ReadSweepTable(file, kSchema, PartialRow::kDrop);
    FAIL();
  } catch (const core::IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("its columns are not this sweep's"));
  }
}

TEST_F(SweepResultsTest, AHalfWrittenHeaderStartsTheTableAfresh) {
  const auto file = tmp_.Write("results.csv", kResultsHeader.substr(0, 10));
  const SweepTable table = ReadSweepTable(file, kSchema, PartialRow::kDrop);
  EXPECT_EQ(table.complete_size, 0u);
  {
    SweepTableAppender appender(file, kSchema, table.complete_size);
    appender.Append(Row(0, 0.5));
  }
  EXPECT_EQ(tmp_.Read("results.csv"), kResultsHeader + Line(0, 0.5));
}

TEST_F(SweepResultsTest, SortedRewriteOrdersByCaseId) {
  const auto file =
      tmp_.Write("results.csv", kResultsHeader + Line(7, 0.5) + Line(2, 0.25) + Line(10, 1.0));
  WriteSortedSweepTable(file, kSchema, ReadSweepTable(file, kSchema, PartialRow::kReject).rows);
  EXPECT_EQ(tmp_.Read("results.csv"), kResultsHeader + Line(2, 0.25) + Line(7, 0.5) + Line(10, 1.0));
}

TEST(SweepSummary, AveragesTheFiniteValuesOfEachCombination) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<SweepRow> rows;
  for (const auto& cells :
       std::vector<std::vector<io::CsvCell>>{{0, 0, 0, 1, "x", "m", 1.0, 0.5},
                                             {1, 0, 1, 2, "x", "m", 0.0, nan},
                                             {2, 1, 0, 1, "y", "m", 1.0, nan}}) {
    rows.push_back(*ParseSweepRow(CsvLine(cells), kSchema));
  }
  const std::string table = SweepSummaryTable(kSchema, 2, rows);
  EXPECT_EQ(table,
            "combo  a.b  mount  runs  success_rate  err\n"
            "0      x    m      2     0.5           0.5\n"
            "1      y    m      1     1             -\n");
  EXPECT_THAT(SweepSummaryTable(kSchema, 2, rows, 1), HasSubstr("... 1 more combinations"));
}

}  // namespace
}  // namespace retrace::bench

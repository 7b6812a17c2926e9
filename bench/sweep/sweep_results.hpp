#pragma once
// The tables of a sweep's results folder, one row per case: results.csv (case, combo, repeat,
// seed, the varied parameters, the metrics; no timing, so identical on every machine) and
// timings.csv (case, wall_time_s, the cpu.* metrics).
//
// Crash safety: while a sweep runs, each finished case's row is appended with one write() of
// the complete line to a file opened for appending, then flushed to the disk, so a kill -9 at
// any moment leaves complete rows and at most one partial last line. Reading back cuts that
// partial line off (no line break, wrong field count or an unparsable field); a bad line
// anywhere else is an error. When every case is done the table is rewritten sorted by case id,
// atomically, so the final file does not depend on the order in which cases finished.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "io/csv_writer.hpp"

namespace retrace::bench {

enum class SweepColumn { kInteger, kNumber, kText };

/// The columns of a sweep table; the first is always the case id (an integer).
struct SweepTableSchema {
  std::vector<std::string> header;
  std::vector<SweepColumn> kinds;
};

/// results.csv: case, combo, repeat, seed (integers), the parameters (text), the metrics (numbers).
SweepTableSchema ResultsSchema(const std::vector<std::string>& parameters,
                               const std::vector<std::string>& metrics);
/// timings.csv: case, wall_time_s, the timing metrics (numbers).
SweepTableSchema TimingsSchema(const std::vector<std::string>& timing_metrics);

/// One CSV line (no line break) of the cells.
std::string CsvLine(std::span<const io::CsvCell> cells);

/// One data row: its case id, its fields and the line as written (without the line break).
struct SweepRow {
  std::size_t case_id = 0;
  std::vector<std::string> fields;
  std::string line;
  int line_number = 0;  ///< 1-based, in the file it was read from (the header is line 1)
};

/// Parses a data line; nullopt if it has the wrong number of fields or a field of the wrong
/// kind (numbers as FormatCsvNumber writes them: shortest round trip, nan, inf, -inf).
std::optional<SweepRow> ParseSweepRow(std::string_view line, const SweepTableSchema& schema);

enum class PartialRow {
  kDrop,   ///< resuming: a bad last line is what an interrupted append left; cut it off
  kReject  ///< merging: the table must be whole
};

struct SweepTable {
  bool exists = false;
  std::vector<SweepRow> rows;        ///< in file order
  std::uintmax_t complete_size = 0;  ///< bytes up to the end of the last good line
  std::uintmax_t file_size = 0;
  std::string dropped;  ///< the partial last line left out (kDrop), if any
};

/// Reads a sweep table. A missing file is an empty table. Throws core::IoError naming the file
/// (and line) for a header other than the schema's, a line that does not parse (but the last
/// one with kDrop), and a case id given twice.
SweepTable ReadSweepTable(const std::filesystem::path& file, const SweepTableSchema& schema,
                          PartialRow partial);

/// Appends rows to a sweep table (see the top of this file). Thread-safe.
class SweepTableAppender {
 public:
  /// Cuts the file to `complete_size` bytes (what ReadSweepTable found good; 0 for a new
  /// table), opens it for appending and writes the header if it is empty. Throws core::IoError.
  SweepTableAppender(std::filesystem::path file, const SweepTableSchema& schema,
                     std::uintmax_t complete_size);
  ~SweepTableAppender();
  SweepTableAppender(const SweepTableAppender&) = delete;
  SweepTableAppender& operator=(const SweepTableAppender&) = delete;

  /// Appends one row (as many cells as the header, checked) and flushes it to the disk.
  /// Throws core::IoError.
  void Append(std::span<const io::CsvCell> cells);

 private:
  void WriteLine(const std::string& line);
  std::filesystem::path file_;
  std::size_t columns_ = 0;
  int fd_ = -1;
  std::mutex mutex_;
};

/// Writes header and rows sorted by case id, atomically (io::WriteFileAtomic).
void WriteSortedSweepTable(const std::filesystem::path& file, const SweepTableSchema& schema,
                           std::vector<SweepRow> rows);

}  // namespace retrace::bench

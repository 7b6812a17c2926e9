#pragma once
// CSV tables read back (a sweep's results.csv, a run's est_map.csv): the inverse of
// io/csv_writer. RFC 4180: cells separated by commas, records by LF or CRLF; a cell in double
// quotes may hold commas, line breaks and doubled quotes. Errors name the file and line.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace retrace::io {

/// One record of a CSV text.
struct CsvRecord {
  int line = 0;  ///< 1-based line where the record starts
  std::vector<std::string> cells;
};

/// The records of `text`, blank lines skipped. Throws core::IoError "<source>:<line>: <what>"
/// on a quote inside an unquoted cell, text after a closing quote or an unclosed quote.
std::vector<CsvRecord> ParseCsv(std::string_view text, const std::string& source);

/// The whole file at `path`, parsed as ParseCsv does. Throws core::IoError if it cannot be read.
std::vector<CsvRecord> ReadCsvFile(const std::filesystem::path& path);

/// The cells of one record that holds no line break; nullopt when `line` is not one well-formed
/// record (an unclosed quote, text after a closing quote, a quote in an unquoted cell, a line
/// break). An empty line is one empty cell.
std::optional<std::vector<std::string>> SplitCsvRecord(std::string_view line);

/// A number cell: decimal or scientific text, or nan / inf / -inf (any case) as
/// io::FormatCsvNumber writes them; spaces around it and a leading '+' are allowed. nullopt for
/// anything else.
std::optional<double> ParseCsvNumber(std::string_view text);

}  // namespace retrace::io

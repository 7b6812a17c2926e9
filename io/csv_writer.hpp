#pragma once
// CSV tables (events.csv, sweep results): a header row, then rows of string and number cells,
// committed atomically. RFC 4180 quoting; numbers in shortest round-trip form; NaN and
// infinities as `nan`, `inf`, `-inf` (what pandas, numpy and R read back).

#include <concepts>
#include <filesystem>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "io/atomic_file.hpp"

namespace retrace::io {

/// One CSV cell, formatted on construction: text is quoted when it contains a comma, a
/// double quote, a line break or leading/trailing spaces; numbers are never quoted.
class CsvCell {
 public:
  // Implicit on purpose, so that rows read `csv.AddRow({t, "goal", count})`.
  // NOLINTBEGIN(google-explicit-constructor)
  CsvCell(std::string_view text);
  CsvCell(const char* text) : CsvCell(std::string_view(text)) {}
  CsvCell(const std::string& text) : CsvCell(std::string_view(text)) {}
  CsvCell(bool value) : text_(value ? "true" : "false") {}
  CsvCell(double value);
  CsvCell(float value) : CsvCell(static_cast<double>(value)) {}
  CsvCell(long long value);
  CsvCell(unsigned long long value);
  template <std::signed_integral T>
  CsvCell(T value) : CsvCell(static_cast<long long>(value)) {}
  template <std::unsigned_integral T>
    requires(!std::same_as<T, bool>)
  CsvCell(T value) : CsvCell(static_cast<unsigned long long>(value)) {}
  // NOLINTEND(google-explicit-constructor)

  /// The cell as it appears in the file (quoted if needed).
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

/// The shortest decimal text that reads back to `value`; `nan`, `inf`, `-inf` otherwise.
std::string FormatCsvNumber(double value);

/// Writes a CSV file row by row into a temporary file and publishes it on Commit(). Without
/// Commit() (for example when an exception unwinds) the target is left untouched.
class CsvWriter {
 public:
  /// Opens the temporary file and writes the header row. Throws core::IoError if the file
  /// cannot be created.
  CsvWriter(const std::filesystem::path& path, const std::vector<std::string>& header);

  /// Appends one row; it must have as many cells as the header (checked).
  void AddRow(std::initializer_list<CsvCell> cells) {
    AddRow(std::span(cells.begin(), cells.size()));
  }
  void AddRow(std::span<const CsvCell> cells);

  std::size_t columns() const { return columns_; }
  std::size_t rows() const { return rows_; }

  /// Publishes the file. Throws core::IoError if it cannot be written.
  void Commit() { file_.Commit(); }

 private:
  AtomicOutputFile file_;
  std::size_t columns_;
  std::size_t rows_ = 0;
};

}  // namespace retrace::io

#include "io/csv_writer.hpp"

#include <charconv>
#include <cmath>
#include <ostream>

#include "core/check.hpp"
#include "core/config.hpp"

namespace retrace::io {
namespace {

bool NeedsQuotes(std::string_view text) {
  if (text.empty()) return false;
  if (text.front() == ' ' || text.back() == ' ') return true;
  return text.find_first_of(",\"\r\n") != std::string_view::npos;
}

template <class T>
std::string ToChars(T value) {
  char buf[64];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), value);
  RETRACE_CHECK(ec == std::errc());
  return std::string(buf, ptr);
}

}  // namespace

std::string FormatCsvNumber(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return core::FormatNumber(value);
}

CsvCell::CsvCell(std::string_view text) {
  if (!NeedsQuotes(text)) {
    text_ = std::string(text);
    return;
  }
  text_.reserve(text.size() + 2);
  text_ += '"';
  for (char c : text) {
    if (c == '"') text_ += '"';  // RFC 4180: a quote inside a quoted field is doubled.
    text_ += c;
  }
  text_ += '"';
}

CsvCell::CsvCell(double value) : text_(FormatCsvNumber(value)) {}
CsvCell::CsvCell(long long value) : text_(ToChars(value)) {}
CsvCell::CsvCell(unsigned long long value) : text_(ToChars(value)) {}

CsvWriter::CsvWriter(const std::filesystem::path& path, const std::vector<std::string>& header)
    : file_(path), columns_(header.size()) {
  RETRACE_CHECK(!header.empty());
  std::vector<CsvCell> cells(header.begin(), header.end());
  AddRow(cells);
  rows_ = 0;  // the header is not a data row
}

void CsvWriter::AddRow(std::span<const CsvCell> cells) {
  RETRACE_CHECK(cells.size() == columns_);
  std::ostream& out = file_.stream();
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i > 0) out << ',';
    out << cells[i].text();
  }
  out << '\n';
  ++rows_;
}

}  // namespace retrace::io

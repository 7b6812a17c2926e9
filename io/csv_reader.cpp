#include "io/csv_reader.hpp"

#include <charconv>

#include "core/errors.hpp"
#include "io/read_file.hpp"

namespace retrace::io {
namespace {

struct CsvProblem {
  int line = 0;
  std::string what;
};

// The one parser behind ParseCsv and SplitCsvRecord: fills `records`, or says what is wrong.
std::optional<CsvProblem> Parse(std::string_view text, std::vector<CsvRecord>* records) {
  CsvRecord record;
  std::string cell;
  int line = 1;
  record.line = 1;
  bool quoted = false;      // inside a quoted cell
  bool was_quoted = false;  // the current cell was quoted and has closed
  bool any = false;         // the record has content (a blank line has none)
  auto end_cell = [&] {
    record.cells.push_back(std::move(cell));
    cell.clear();
    was_quoted = false;
  };
  auto end_record = [&] {
    if (any) {
      end_cell();
      records->push_back(std::move(record));
    }
    record = CsvRecord{};
    cell.clear();
    was_quoted = false;
    any = false;
    record.line = line;
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < text.size() && text[i + 1] == '"') {
          cell += '"';
          ++i;
        } else {
          quoted = false;
          was_quoted = true;
        }
      } else {
        if (c == '\n') ++line;
        cell += c;
      }
      continue;
    }
    if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') continue;
    if (c == '\n') {
      ++line;
      end_record();
      continue;
    }
    any = true;
    if (c == ',') {
      end_cell();
    } else if (c == '"') {
      if (was_quoted || !cell.empty()) {
        return CsvProblem{line, "a double quote inside a cell that is not quoted"};
      }
      quoted = true;
    } else if (was_quoted) {
      return CsvProblem{line, "text after the closing quote of a cell"};
    } else {
      cell += c;
    }
  }
  if (quoted) return CsvProblem{record.line, "a quoted cell is not closed before the end"};
  end_record();
  return std::nullopt;
}

}  // namespace

std::vector<CsvRecord> ParseCsv(std::string_view text, const std::string& source) {
  std::vector<CsvRecord> records;
  if (const std::optional<CsvProblem> problem = Parse(text, &records)) {
    throw core::IoError(source + ":" + std::to_string(problem->line) + ": " + problem->what);
  }
  return records;
}

std::vector<CsvRecord> ReadCsvFile(const std::filesystem::path& path) {
  return ParseCsv(ReadFileBytes(path), path.string());
}

std::optional<std::vector<std::string>> SplitCsvRecord(std::string_view line) {
  if (line.find_first_of("\r\n") != std::string_view::npos) return std::nullopt;
  if (line.empty()) return std::vector<std::string>(1);
  std::vector<CsvRecord> records;
  if (Parse(line, &records) || records.size() != 1) return std::nullopt;
  return std::move(records.front().cells);
}

std::optional<double> ParseCsvNumber(std::string_view text) {
  const std::size_t b = text.find_first_not_of(" \t");
  if (b == std::string_view::npos) return std::nullopt;
  const std::size_t e = text.find_last_not_of(" \t");
  std::string_view number = text.substr(b, e + 1 - b);
  if (number.front() == '+') {  // from_chars takes no '+', and "+-1" is no number
    number.remove_prefix(1);
    if (number.empty() || number.front() == '-') return std::nullopt;
  }
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
  if (ec != std::errc() || ptr != number.data() + number.size()) return std::nullopt;
  return value;
}

}  // namespace retrace::io

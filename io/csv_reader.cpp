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

// Where Parse stands: the record and the cell being read, the line (1-based) and the quoting.
struct CsvParseState {
  explicit CsvParseState(std::vector<CsvRecord>* out) : records(out) { record.line = 1; }

  std::vector<CsvRecord>* records;
  CsvRecord record;
  std::string cell;
  int line = 1;
  bool quoted = false;      // inside a quoted cell
  bool was_quoted = false;  // the current cell was quoted and has closed
  bool any = false;         // the record has content (a blank line has none)

  // Closes the current cell of the record.
  void EndCell() {
    record.cells.push_back(std::move(cell));
    cell.clear();
    was_quoted = false;
  }
  // Closes the record (kept only if it has content) and starts the next one on `line`.
  void EndRecord() {
    if (any) {
      EndCell();
      records->push_back(std::move(record));
    }
    record = CsvRecord{};
    cell.clear();
    was_quoted = false;
    any = false;
    record.line = line;
  }
};

// One character inside a quoted cell, text[*i]: a doubled quote is a quote (*i moves past the
// second), a single one closes the cell; anything else, line breaks too, belongs to the cell.
void ReadQuotedCsvChar(std::string_view text, std::size_t* i, CsvParseState* s) {
  const char c = text[*i];
  if (c == '"') {
    if (*i + 1 < text.size() && text[*i + 1] == '"') {
      s->cell += '"';
      ++*i;
    } else {
      s->quoted = false;
      s->was_quoted = true;
    }
  } else {
    if (c == '\n') ++s->line;
    s->cell += c;
  }
}

// One character of a record outside quotes (not a line break): a comma ends the cell, a quote
// opens a quoted cell; the problem when the character breaks the format.
std::optional<CsvProblem> ReadPlainCsvChar(char c, CsvParseState* s) {
  s->any = true;
  if (c == ',') {
    s->EndCell();
  } else if (c == '"') {
    if (s->was_quoted || !s->cell.empty()) {
      return CsvProblem{s->line, "a double quote inside a cell that is not quoted"};
    }
    s->quoted = true;
  } else if (s->was_quoted) {
    return CsvProblem{s->line, "text after the closing quote of a cell"};
  } else {
    s->cell += c;
  }
  return std::nullopt;
}

// The one parser behind ParseCsv and SplitCsvRecord: fills `records`, or says what is wrong.
std::optional<CsvProblem> Parse(std::string_view text, std::vector<CsvRecord>* records) {
  CsvParseState s(records);
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (s.quoted) {
      ReadQuotedCsvChar(text, &i, &s);
      continue;
    }
    if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') continue;
    if (c == '\n') {
      ++s.line;
      s.EndRecord();
      continue;
    }
    if (std::optional<CsvProblem> problem = ReadPlainCsvChar(c, &s)) return problem;
  }
  if (s.quoted) return CsvProblem{s.record.line, "a quoted cell is not closed before the end"};
  s.EndRecord();
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

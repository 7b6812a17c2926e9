#include "bench/sweep/sweep_results.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <set>

#include "core/check.hpp"
#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/csv_reader.hpp"
#include "io/read_file.hpp"

namespace retrace::bench {
namespace {

bool IsInteger(std::string_view text) {
  std::uint64_t v = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  return !text.empty() && ec == std::errc() && ptr == text.data() + text.size();
}

std::string HeaderLine(const SweepTableSchema& schema) {
  const std::vector<io::CsvCell> cells(schema.header.begin(), schema.header.end());
  return CsvLine(cells);
}

std::string Errno() { return std::strerror(errno); }

}  // namespace

SweepTableSchema ResultsSchema(const std::vector<std::string>& parameters,
                               const std::vector<std::string>& metrics) {
  SweepTableSchema s;
  s.header = {"case", "combo", "repeat", "seed"};
  s.kinds.assign(4, SweepColumn::kInteger);
  for (const std::string& p : parameters) {
    s.header.push_back(p);
    s.kinds.push_back(SweepColumn::kText);
  }
  for (const std::string& m : metrics) {
    s.header.push_back(m);
    s.kinds.push_back(SweepColumn::kNumber);
  }
  return s;
}

SweepTableSchema TimingsSchema(const std::vector<std::string>& timing_metrics) {
  SweepTableSchema s;
  s.header = {"case", "wall_time_s"};
  s.kinds = {SweepColumn::kInteger, SweepColumn::kNumber};
  for (const std::string& m : timing_metrics) {
    s.header.push_back(m);
    s.kinds.push_back(SweepColumn::kNumber);
  }
  return s;
}

std::string CsvLine(std::span<const io::CsvCell> cells) {
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i > 0) line += ',';
    line += cells[i].text();
  }
  return line;
}

std::optional<SweepRow> ParseSweepRow(std::string_view line, const SweepTableSchema& schema) {
  auto fields = io::SplitCsvRecord(line);
  if (!fields || fields->size() != schema.header.size()) return std::nullopt;
  for (std::size_t i = 0; i < fields->size(); ++i) {
    const std::string& f = (*fields)[i];
    if (schema.kinds[i] == SweepColumn::kInteger && !IsInteger(f)) return std::nullopt;
    if (schema.kinds[i] == SweepColumn::kNumber && !io::ParseCsvNumber(f)) return std::nullopt;
  }
  SweepRow row;
  std::from_chars(fields->front().data(), fields->front().data() + fields->front().size(),
                  row.case_id);
  row.fields = std::move(*fields);
  row.line = std::string(line);
  return row;
}

SweepTable ReadSweepTable(const std::filesystem::path& file, const SweepTableSchema& schema,
                          PartialRow partial) {
  SweepTable table;
  if (!std::filesystem::exists(file)) return table;
  table.exists = true;
  const std::string text = io::ReadFileBytes(file);
  table.file_size = text.size();
  const std::string header = HeaderLine(schema);
  const std::size_t header_end = text.find('\n');
  if (header_end == std::string::npos) {
    // Nothing but (a piece of) the header: a table interrupted while it was being created.
    if (header.compare(0, text.size(), text) != 0) {
      throw core::IoError(file.string() + ":1: not the header of this sweep's table");
    }
    if (partial == PartialRow::kReject && !text.empty())
      throw core::IoError(file.string() + ":1: the header is incomplete");
    table.dropped = text;
    return table;
  }
  if (text.compare(0, header_end, header) != 0) {
    throw core::IoError(file.string() + ":1: its columns are not this sweep's (" +
                        text.substr(0, std::min<std::size_t>(header_end, 80)) + "...)");
  }
  table.complete_size = header_end + 1;
  std::set<std::size_t> seen;
  std::size_t start = header_end + 1;
  int line_number = 1;
  while (start < text.size()) {
    ++line_number;
    const std::size_t end = text.find('\n', start);
    const bool terminated = end != std::string::npos;
    const std::string_view line(text.data() + start, (terminated ? end : text.size()) - start);
    const bool last = !terminated || end + 1 == text.size();
    std::optional<SweepRow> row = terminated ? ParseSweepRow(line, schema) : std::nullopt;
    if (!row) {
      const std::string where = file.string() + ":" + std::to_string(line_number) + ": ";
      if (!last) throw core::IoError(where + "not a row of this sweep's table");
      if (partial == PartialRow::kReject) {
        throw core::IoError(
            where + "the last row is incomplete (the sweep was interrupted while writing it)");
      }
      table.dropped = std::string(line);
      break;
    }
    if (!seen.insert(row->case_id).second) {
      throw core::IoError(file.string() + ":" + std::to_string(line_number) + ": case " +
                          std::to_string(row->case_id) + " appears a second time");
    }
    row->line_number = line_number;
    table.rows.push_back(std::move(*row));
    table.complete_size = end + 1;
    start = end + 1;
  }
  return table;
}

SweepTableAppender::SweepTableAppender(std::filesystem::path file, const SweepTableSchema& schema,
                                       std::uintmax_t complete_size)
    : file_(std::move(file)), columns_(schema.header.size()) {
  std::error_code ec;
  if (std::filesystem::exists(file_) && std::filesystem::file_size(file_) != complete_size) {
    std::filesystem::resize_file(file_, complete_size, ec);
    if (ec)
      throw core::IoError(file_.string() +
                          ": cannot cut off the partial last row: " + ec.message());
  }
  fd_ = ::open(file_.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw core::IoError(file_.string() + ": cannot open for appending: " + Errno());
  if (complete_size == 0) WriteLine(HeaderLine(schema));
}

SweepTableAppender::~SweepTableAppender() {
  if (fd_ >= 0) ::close(fd_);
}

void SweepTableAppender::Append(std::span<const io::CsvCell> cells) {
  RETRACE_CHECK(cells.size() == columns_);
  WriteLine(CsvLine(cells));
}

void SweepTableAppender::WriteLine(const std::string& line) {
  std::lock_guard lock(mutex_);
  const std::string text = line + '\n';
  // One write() of the whole line: with O_APPEND it lands at the end in one piece. A short
  // write (a full disk) is continued, and an error leaves at most a partial last line, which
  // the next start cuts off.
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd_, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw core::IoError(file_.string() + ": cannot write: " + Errno());
    done += static_cast<std::size_t>(n);
  }
  // On the disk before the next case starts: a finished case survives even a power cut.
  if (::fdatasync(fd_) != 0) throw core::IoError(file_.string() + ": cannot flush: " + Errno());
}

void WriteSortedSweepTable(const std::filesystem::path& file, const SweepTableSchema& schema,
                           std::vector<SweepRow> rows) {
  std::sort(rows.begin(), rows.end(),
            [](const SweepRow& a, const SweepRow& b) { return a.case_id < b.case_id; });
  std::string text = HeaderLine(schema) + "\n";
  for (const SweepRow& row : rows) text += row.line + "\n";
  io::WriteFileAtomic(file, text);
}

}  // namespace retrace::bench

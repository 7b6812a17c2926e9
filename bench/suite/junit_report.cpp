#include "bench/suite/junit_report.hpp"

#include <cmath>
#include <cstdio>
#include <string_view>
#include <utility>
#include <vector>

#include "bench/suite/suite_spec.hpp"
#include "bench/suite/tolerance.hpp"
#include "core/format.hpp"
#include "io/markup_escape.hpp"

namespace retrace::bench {
namespace {

constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD

// The length of the valid UTF-8 sequence at text[i]; 0 when there is none (a stray byte, an
// overlong form, a surrogate, a code point past U+10FFFF or a cut sequence).
std::size_t Utf8Length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char c = byte(i);
  if (c < 0x80) return 1;
  std::size_t n = 0;
  unsigned char lo = 0x80;
  unsigned char hi = 0xBF;
  if (c >= 0xC2 && c <= 0xDF) {
    n = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    n = 3;
    if (c == 0xE0) lo = 0xA0;
    if (c == 0xED) hi = 0x9F;
  } else if (c >= 0xF0 && c <= 0xF4) {
    n = 4;
    if (c == 0xF0) lo = 0x90;
    if (c == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (i + n > text.size() || byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k) {
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  }
  return n;
}

// Text as XML 1.0 allows it: markup characters escaped, invalid UTF-8 and the characters XML
// cannot hold (controls, U+FFFE, U+FFFF) replaced by U+FFFD. In an attribute, line breaks and
// tabs are escaped too, since a parser would read them as spaces.
std::string Escape(std::string_view text, bool attribute) {
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = Utf8Length(text, i);
    if (n != 1) {
      const std::string_view sequence = text.substr(i, n == 0 ? 1 : n);
      const bool banned = n == 0 || sequence == "\xEF\xBF\xBE" || sequence == "\xEF\xBF\xBF";
      out += banned ? kReplacement : sequence;
      i += sequence.size();
      continue;
    }
    const char c = text[i++];
    if (const char* entity = io::MarkupEntity(c)) {
      out += entity;
      continue;
    }
    switch (c) {
      case '\n':
        out += attribute ? "&#10;" : "\n";
        break;
      case '\r':
        out += "&#13;";
        break;
      case '\t':
        out += attribute ? "&#9;" : "\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          out += kReplacement;
        } else {
          out += c;
        }
    }
  }
  return out;
}

// ` name="value"`, escaped.
std::string Attribute(std::string_view name, std::string_view value) {
  // Appended piece by piece: GCC 12 warns (-Wstringop-overflow) on " " + std::string(name).
  std::string out = " ";
  out.append(name);
  out += "=\"";
  out += Escape(value, true);
  out += '"';
  return out;
}

// The rows `retrace bench` exits 1 for.
bool Fails(const SuiteReport& report, const ReportContext& context, const ReportRow& row) {
  return report.compared && !context.recording && IsFailure(row.check.verdict);
}

// One line: what the table shows for the row, and why it fails.
std::string FailureMessage(const ReportRow& row) {
  std::string message = "baseline " + FormatValue(row.baseline) + ", now " + FormatValue(row.now) +
                        ", delta " + FormatDelta(RowDelta(row)) + ", tolerance " +
                        DescribeTolerance(row.tolerance);
  if (!row.check.reason.empty()) message += ": " + row.check.reason;
  return message;
}

// The failure's text: the same, one item a line, with where the numbers come from.
std::string FailureDetails(const ReportRow& row, const ReportContext& context) {
  std::string text = row.name + " regressed";
  if (!row.check.reason.empty()) text += ": " + row.check.reason;
  text += "\nbaseline: " + FormatValue(row.baseline);
  if (context.baseline != nullptr) {
    text += " (" + context.baseline_file.string() + ", git " + context.baseline->git_revision +
            ", " + context.baseline->date + ")";
  }
  text += "\nnow: " + FormatValue(row.now) + " (mean over the seeds";
  if (std::isfinite(row.seed_sd)) text += "; seed sd " + FormatValue(row.seed_sd);
  text += ")";
  text += "\ndelta: " + FormatDelta(RowDelta(row));
  text += "\ntolerance: " + DescribeTolerance(row.tolerance) + " (rule \"" + row.pattern + "\")\n";
  return text;
}

// What produced the numbers, as <property> name-value pairs (set and only once per value).
std::vector<std::pair<std::string, std::string>> Properties(const SuiteReport& report,
                                                            const ReportContext& context) {
  std::vector<std::pair<std::string, std::string>> p = {{"retrace_version", context.version}};
  if (!context.git_revision.empty()) p.emplace_back("git_revision", context.git_revision);
  p.emplace_back("date", context.date);
  p.emplace_back("wall_time_s", core::FixedText(context.wall_time_s, 3));
  p.emplace_back("jobs", std::to_string(context.jobs));
  p.emplace_back("suite", report.suite);
  p.emplace_back("suite_file", context.suite_file.string());
  p.emplace_back("suite_digest", context.suite_digest);
  if (context.baseline != nullptr) {
    p.emplace_back("baseline_file", context.baseline_file.string());
    p.emplace_back("baseline_git_revision", context.baseline->git_revision);
    p.emplace_back("baseline_date", context.baseline->date);
  }
  if (context.recording) p.emplace_back("recording", "baseline recorded, nothing judged");
  for (const std::string& o : context.overrides) p.emplace_back("set", o);
  for (const std::string& o : context.only) p.emplace_back("only", o);
  return p;
}

// The gated rows of one entry and mode, in the report's order.
struct SuiteBlock {
  std::string name;  ///< "<entry>.<mode>"
  std::vector<const ReportRow*> rows;
  int failures = 0;
};

std::vector<SuiteBlock> Blocks(const SuiteReport& report, const ReportContext& context) {
  std::vector<SuiteBlock> blocks;
  for (const ReportRow& row : report.rows) {
    if (row.check.verdict == Verdict::kReport) continue;
    const SuiteMetricName parts = SplitSuiteMetricName(row.name);
    const std::string name = parts.entry + "." + parts.mode;
    SuiteBlock* block = nullptr;
    for (SuiteBlock& b : blocks) {
      if (b.name == name) block = &b;
    }
    if (block == nullptr) block = &blocks.emplace_back(SuiteBlock{name, {}, 0});
    block->rows.push_back(&row);
    if (Fails(report, context, row)) ++block->failures;
  }
  return blocks;
}

std::string TestSuiteXml(const SuiteBlock& block, const SuiteReport& report,
                         const ReportContext& context, const std::string& properties) {
  std::string xml = "  <testsuite" + Attribute("name", block.name) +
                    Attribute("tests", std::to_string(block.rows.size())) +
                    Attribute("failures", std::to_string(block.failures)) +
                    Attribute("errors", "0") + Attribute("skipped", "0") + Attribute("time", "0") +
                    Attribute("timestamp", context.date) + ">\n" + properties;
  for (const ReportRow* row : block.rows) {
    xml += "    <testcase" + Attribute("classname", block.name) + Attribute("name", row->name) +
           Attribute("time", "0");
    if (!Fails(report, context, *row)) {
      xml += "/>\n";
      continue;
    }
    xml += ">\n      <failure" + Attribute("type", "regression") +
           Attribute("message", FailureMessage(*row)) + ">" +
           Escape(FailureDetails(*row, context), false) + "</failure>\n    </testcase>\n";
  }
  return xml + "  </testsuite>\n";
}

}  // namespace

std::string JunitXml(const SuiteReport& report, const ReportContext& context) {
  const std::vector<SuiteBlock> blocks = Blocks(report, context);
  std::size_t tests = 0;
  int failures = 0;
  for (const SuiteBlock& block : blocks) {
    tests += block.rows.size();
    failures += block.failures;
  }
  std::string properties = "    <properties>\n";
  for (const auto& [name, value] : Properties(report, context))
    properties += "      <property" + Attribute("name", name) + Attribute("value", value) + "/>\n";
  properties += "    </properties>\n";

  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites" +
                    Attribute("name", report.suite) + Attribute("tests", std::to_string(tests)) +
                    Attribute("failures", std::to_string(failures)) + Attribute("errors", "0") +
                    Attribute("skipped", "0") +
                    Attribute("time", core::FixedText(context.wall_time_s, 3)) + ">\n";
  for (const SuiteBlock& block : blocks) xml += TestSuiteXml(block, report, context, properties);
  return xml + "</testsuites>\n";
}

}  // namespace retrace::bench

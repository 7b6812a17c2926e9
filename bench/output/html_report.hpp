#pragma once
// report.html: one self-contained page for a results folder (`retrace report <dir>`, and the end
// of `retrace run`, `playback`, `bench`, `sweep` and `compare`), read back from the files the
// folder holds, so that it works for any folder retrace writes and, listing what it found, for
// any folder at all:
//
//   summary      per metrics.json (a run's modes, a log-localize folder) the headline metrics
//                side by side, all of them folded away
//   suite        a bench report.json: the verdict, the regressions in red (baseline, now, delta,
//                tolerance), every gated row
//   comparison   comparison.md (compare, log-compare) with its confidence intervals
//   sweep        sweep.json and the first kReportTableRows rows of results.csv
//   figures      every PNG under the folder, grouped by subfolder, captioned
//   provenance   every manifest.yaml (command, seed, revision, build, wall time, config) and the
//                command and revision recorded in sweep.json, comparison.json and report.json
//   files        what the folder holds
//
// The page refers to nothing outside itself: images are `data:image/png;base64` URIs, the CSS
// and a small script inline, and a Content-Security-Policy forbids anything else. Every text
// taken from a file is HTML-escaped. The same folder gives the same bytes.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace retrace::bench {

/// The most rows of a table file (a sweep's results.csv) the page shows; it says when it cut.
inline constexpr std::size_t kReportTableRows = 200;

/// `text` safe as HTML element content and as a quoted attribute value: & < > " ' escaped.
std::string HtmlEscape(std::string_view text);

struct HtmlReport {
  std::string html;
  int images = 0;    ///< PNG files embedded
  std::string kind;  ///< what the folder looked like, e.g. "run", "bench", "folder"
};

/// The page of the folder `dir`. Throws core::IoError naming the path when `dir` does not exist
/// or is not a folder, or when a manifest.yaml, a JSON or a CSV file the page reads is unreadable
/// or malformed.
HtmlReport BuildHtmlReport(const std::filesystem::path& dir);

/// Builds the page and writes it to `<dir>/report.html` atomically (io/atomic_file.hpp); on any
/// error nothing is written. Throws like BuildHtmlReport, or core::IoError when the file cannot
/// be written.
HtmlReport WriteHtmlReport(const std::filesystem::path& dir);

}  // namespace retrace::bench

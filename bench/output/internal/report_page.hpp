#pragma once
// The pieces report.html (html_report.hpp) is made of, shared by the html_report*.cpp files only:
// what a results folder holds (html_report_folder.cpp), JSON values as table cells
// (html_report_cells.cpp), and the page's sections: the tables read from metrics, suite, compare
// and sweep files (html_report_tables.cpp), and the figures, provenance and file list
// (html_report_files.cpp).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace retrace::bench::report {

// Folders beyond this many entries are listed only in part; a results folder holds a few
// thousand files at most.
inline constexpr std::size_t kMaxWalkedFiles = 100000;
inline constexpr std::size_t kListedFiles = 500;
// A PNG larger than this is listed, not embedded: the page must stay loadable.
inline constexpr std::uintmax_t kMaxImageBytes = 64u << 20;

// --- What the folder holds ------------------------------------------------------------------

struct Folder {
  std::filesystem::path dir;
  std::vector<std::filesystem::path> files;  ///< relative, sorted
  bool truncated = false;
  bool Has(const std::filesystem::path& rel) const {
    return std::binary_search(files.begin(), files.end(), rel);
  }
  std::vector<std::filesystem::path> Named(const std::string& name) const {
    std::vector<std::filesystem::path> found;
    for (const std::filesystem::path& f : files)
      if (f.filename() == name) found.push_back(f);
    return found;
  }
};

/// Every regular file below `dir` (staging folders and the page itself left out), at most
/// kMaxWalkedFiles. Throws core::IoError when `dir` is missing, not a folder or unreadable.
Folder Walk(const std::filesystem::path& dir);

/// What kind of folder this is, from the files that identify each command's output: a short
/// name ("run", "bench", "sweep", ..., "folder") and a description.
std::pair<std::string, std::string> Kind(const Folder& folder);

// --- Cells ----------------------------------------------------------------------------------

std::string Number(double v);        ///< 4 significant digits, "n/a" when not finite
std::string SignedNumber(double v);  ///< the same with its sign
bool IsScalar(const nlohmann::json& v);
/// A JSON value as cell text (not yet escaped).
std::string Text(const nlohmann::json& v);
/// A JSON value as an escaped table cell, right-aligned when a number.
std::string Cell(const nlohmann::json& v);
/// Dotted names of every scalar (and short list of scalars) in `v`.
void Flatten(const nlohmann::json& v, const std::string& prefix,
             std::map<std::string, nlohmann::json>* out);
/// The value at a dotted path, or nullptr.
const nlohmann::json* Find(const nlohmann::json& root, std::string_view dotted);
std::string Generic(const std::filesystem::path& rel);
nlohmann::json ReadJson(const std::filesystem::path& dir, const std::filesystem::path& rel);
/// A two-column table of facts (already escaped values).
std::string FactsTable(const std::vector<std::pair<std::string, std::string>>& facts);

// --- The page's sections --------------------------------------------------------------------

struct Section {
  std::string id;
  std::string title;
  std::string html;
};

std::optional<Section> SummarySection(const Folder& folder);
std::optional<Section> SuiteSection(const Folder& folder);
std::optional<Section> ComparisonSection(const Folder& folder);
std::optional<Section> SweepSection(const Folder& folder);
/// Every PNG, embedded; counts them in `*images`.
Section FiguresSection(const Folder& folder, int* images);
std::optional<Section> ProvenanceSection(const Folder& folder);
Section FilesSection(const Folder& folder, bool open);

}  // namespace retrace::bench::report

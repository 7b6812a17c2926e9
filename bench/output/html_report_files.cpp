#include <yaml-cpp/yaml.h>

#include <cctype>
#include <system_error>

#include "bench/output/base64.hpp"
#include "bench/output/html_report.hpp"
#include "bench/output/internal/report_page.hpp"
#include "core/errors.hpp"
#include "io/read_file.hpp"

namespace retrace::bench::report {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// What a figure shows, by its file name (docs/FORMATS.md).
std::string Caption(const fs::path& rel) {
  const std::string name = rel.filename().string();
  static const std::vector<std::pair<std::string, std::string>> kKnown = {
      {"maps.png",
       "the taught route coloured per partial map with the switch points, then every partial "
       "map in its own frame (paper Fig. 1)"},
      {"maps_compare.png", "the consistent map next to the single odometry map (paper Fig. 6)"},
      {"odometry.png", "ground truth and wheel odometry of the teaching drive and run 0 (Fig. 8)"},
      {"likelihood.png",
       "the measurement likelihood around the true pose, without and with dynamic point "
       "rejection (Fig. 5)"},
      {"snapshot.png",
       "the update with the most pedestrian beams: particles, estimate, truth and the scan "
       "points rejected as dynamic (Fig. 4)"},
      {"errors.png", "tracking and localization error along the route, map switches marked"},
      {"comparison.png", "the modes' metrics side by side"},
      {"sweep.png", "each metric against each plotted parameter (mean over repeats, min–max)"},
      {"world.png", "the world and its route"},
  };
  for (const auto& [known, caption] : kKnown) {
    if (name == known) return caption;
  }
  if (name.starts_with("playback_"))
    return "the taught path and every run's trajectory, zoomed where the runs spread most (Fig. 7)";
  return "";
}

bool IsPng(const std::string& bytes) {
  return bytes.size() >= 8 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
}

}  // namespace

Section FiguresSection(const Folder& folder, int* images) {
  std::map<std::string, std::vector<fs::path>> groups;  // by subfolder; "" first
  for (const fs::path& rel : folder.files) {
    std::string ext = rel.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".png") groups[Generic(rel.parent_path())].push_back(rel);
  }
  Section s{"figures", "Figures", ""};
  if (groups.empty()) {
    s.html = "<p class=\"note\">No PNG figures in this folder.</p>\n";
    return s;
  }
  for (const auto& [group, files] : groups) {
    s.html += "<h3>" + HtmlEscape(group.empty() ? "top level" : group + "/") + "</h3>\n";
    for (const fs::path& rel : files) {
      const std::string where = "<code>" + HtmlEscape(Generic(rel)) + "</code>";
      std::error_code ec;
      const std::uintmax_t size = fs::file_size(folder.dir / rel, ec);
      if (ec || size > kMaxImageBytes) {
        s.html += "<p class=\"note\">" + where + ": not embedded (" +
                  (ec ? "cannot read it" : std::to_string(size >> 20) + " MB") + ").</p>\n";
        continue;
      }
      const std::string bytes = io::ReadFileBytes(folder.dir / rel);
      if (!IsPng(bytes)) {
        s.html += "<p class=\"note\">" + where + ": not a PNG image, not embedded.</p>\n";
        continue;
      }
      const std::string caption = Caption(rel);
      s.html += "<figure><img alt=\"" + HtmlEscape(Generic(rel)) +
                "\" src=\"data:image/png;base64," + Base64Encode(bytes) + "\"><figcaption>" +
                where + (caption.empty() ? "" : ": " + HtmlEscape(caption)) +
                "</figcaption></figure>\n";
      ++*images;
    }
  }
  return s;
}

namespace {

std::string YamlText(const YAML::Node& node) {
  YAML::Emitter out;
  out << node;
  return out.c_str();
}

// One manifest.yaml: its scalar keys as a table, its maps and lists folded away.
std::string ManifestHtml(const fs::path& dir, const fs::path& rel) {
  YAML::Node root;
  try {
    root = YAML::LoadFile((dir / rel).string());
  } catch (const YAML::Exception& e) {
    throw core::IoError((dir / rel).string() + ": cannot read the manifest: " + e.what());
  }
  if (!root.IsMap()) {
    throw core::IoError((dir / rel).string() +
                        ": cannot read the manifest: not a map of keys and values");
  }
  std::vector<std::pair<std::string, std::string>> facts;
  std::string folded;
  for (const auto& entry : root) {
    const std::string key = entry.first.Scalar();
    const YAML::Node& value = entry.second;
    if (value.IsScalar() || value.IsNull()) {
      facts.emplace_back(key, HtmlEscape(value.IsNull() ? "" : value.Scalar()));
    } else if (value.IsSequence() && value.size() == 0) {
      facts.emplace_back(key, "none");
    } else {
      folded += "<details><summary>" + HtmlEscape(key) + "</summary><pre>" +
                HtmlEscape(YamlText(value)) + "</pre></details>\n";
    }
  }
  return "<h3><code>" + HtmlEscape(Generic(rel)) + "</code></h3>\n" + FactsTable(facts) + folded;
}

// The command, revision and timing that sweep.json, a compare's comparison.json and a suite's
// report.json record (their folders have no manifest.yaml).
std::string RecordHtml(const Folder& folder, const fs::path& rel) {
  const json j = ReadJson(folder.dir, rel);
  if (!j.is_object()) return "";
  std::vector<std::pair<std::string, std::string>> facts;
  for (const char* key : {"command", "scenario", "scenario_file", "suite", "suite_file",
                          "sweep_file", "seeds", "repeats", "reference", "git_revision",
                          "build_type", "date", "jobs", "wall_time_s", "set", "only"}) {
    if (j.contains(key) && !(j[key].is_array() && j[key].empty()) && !j[key].is_object())
      facts.emplace_back(key, HtmlEscape(Text(j[key])));
  }
  if (facts.empty()) return "";
  return "<h3><code>" + HtmlEscape(Generic(rel)) + "</code></h3>\n" + FactsTable(facts);
}

}  // namespace

std::optional<Section> ProvenanceSection(const Folder& folder) {
  std::string html;
  for (const fs::path& rel : folder.Named("manifest.yaml")) html += ManifestHtml(folder.dir, rel);
  for (const char* record : {"sweep.json", "comparison.json", "report.json"}) {
    if (folder.Has(record)) html += RecordHtml(folder, record);
  }
  if (html.empty()) return std::nullopt;
  return Section{"provenance", "Provenance", html};
}

Section FilesSection(const Folder& folder, bool open) {
  std::map<std::string, int> by_extension;
  for (const fs::path& rel : folder.files) {
    const std::string ext = rel.extension().string();
    ++by_extension[ext.empty() ? "(none)" : ext];
  }
  std::string counts;
  for (const auto& [ext, n] : by_extension)
    counts += (counts.empty() ? "" : ", ") + std::to_string(n) + " " + HtmlEscape(ext);
  Section s{"files", "Files", ""};
  s.html = "<p>" + std::to_string(folder.files.size()) + (folder.truncated ? "+" : "") +
           (folder.files.size() == 1 ? " file" : " files") +
           (counts.empty() ? "" : " (" + counts + ")") + ".</p>\n";
  if (folder.files.empty()) return s;
  s.html +=
      std::string("<details") + (open ? " open" : "") + "><summary>List" +
      (folder.files.size() > kListedFiles ? " (the first " + std::to_string(kListedFiles) + ")"
                                          : std::string()) +
      "</summary>\n<pre>";
  for (std::size_t i = 0; i < folder.files.size() && i < kListedFiles; ++i) {
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(folder.dir / folder.files[i], ec);
    s.html += HtmlEscape(Generic(folder.files[i])) +
              (ec ? std::string() : "  (" + std::to_string(size) + " bytes)") + "\n";
  }
  s.html += "</pre></details>\n";
  return s;
}

}  // namespace retrace::bench::report

#include <system_error>

#include "bench/output/internal/report_page.hpp"
#include "core/errors.hpp"

namespace retrace::bench::report {

namespace fs = std::filesystem;
using nlohmann::json;

Folder Walk(const fs::path& dir) {
  std::error_code ec;
  const fs::file_status status = fs::status(dir, ec);
  if (!fs::exists(status)) throw core::IoError(dir.string() + ": no such folder");
  if (!fs::is_directory(status)) throw core::IoError(dir.string() + ": not a folder");
  Folder folder;
  folder.dir = dir;
  fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
  if (ec) throw core::IoError(dir.string() + ": cannot read the folder: " + ec.message());
  for (; it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) break;
    const fs::path name = it->path().filename();
    const std::string ext = name.extension().string();
    if (it->is_directory(ec)) {
      // Staging folders of a command still writing (or killed): not results.
      if (ext == ".tmp" || ext == ".old") it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file(ec)) continue;
    // The page itself: a report made again must not list its previous version.
    if (it.depth() == 0 && name == "report.html") continue;
    if (folder.files.size() == kMaxWalkedFiles) {
      folder.truncated = true;
      break;
    }
    folder.files.push_back(it->path().lexically_relative(dir));
  }
  std::sort(folder.files.begin(), folder.files.end());
  return folder;
}

// What kind of folder this is, from the files that identify each command's output.
std::pair<std::string, std::string> Kind(const Folder& folder) {
  bool modes = false, manifests = false;
  for (const fs::path& rel : folder.Named("metrics.json"))
    modes = modes || !rel.parent_path().empty();
  for (const fs::path& rel : folder.Named("manifest.yaml"))
    manifests = manifests || !rel.parent_path().empty();
  if (folder.Has("report.json") || folder.Has("report.md"))
    return {"bench", "a regression suite's report (retrace bench)"};
  if (folder.Has("sweep.json")) return {"sweep", "a parameter sweep (retrace sweep / merge)"};
  if (folder.Has("metrics.json") && folder.Has("manifest.yaml"))
    return {"log-localize", "a recorded log localized in a teach folder (retrace log-localize)"};
  if (modes) return {"run", "the results of retrace run / playback, one folder per map mode"};
  if (folder.Has("comparison.json"))
    return {"compare", "a map-mode comparison over seeds (retrace compare)"};
  if (folder.Has("comparison.md"))
    return {"log-compare", "log-localize runs side by side (retrace log-compare)"};
  if (manifests) return {"teach", "teach folders (retrace teach / log-teach)"};
  return {"folder", "a folder retrace does not recognise: the page lists what it found"};
}

}  // namespace retrace::bench::report

#include "python/created_folders.hpp"

#include <algorithm>
#include <system_error>

namespace retrace::python {
namespace fs = std::filesystem;

CreatedFolders::CreatedFolders(const std::vector<fs::path>& targets) {
  std::error_code ec;
  for (const fs::path& target : targets) {
    if (target.empty()) continue;
    fs::path p = fs::absolute(target, ec).lexically_normal();
    if (ec) continue;
    if (!p.has_filename()) p = p.parent_path();  // "out/" names the folder out
    while (!p.empty() && p != p.root_path() && !fs::exists(p, ec)) {
      missing_.push_back(p);
      p = p.parent_path();
    }
  }
  // Deepest first: a folder is empty only once its new subfolders are gone.
  std::sort(missing_.begin(), missing_.end(), [](const fs::path& a, const fs::path& b) {
    return std::distance(a.begin(), a.end()) > std::distance(b.begin(), b.end());
  });
}

void CreatedFolders::RemoveEmpty() const {
  std::error_code ec;
  for (const fs::path& folder : missing_) {
    if (fs::is_directory(folder, ec) && fs::is_empty(folder, ec)) fs::remove(folder, ec);
  }
}

}  // namespace retrace::python

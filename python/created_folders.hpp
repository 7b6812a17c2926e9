#pragma once
// The folders a library call may create on its way to its outputs, removed again when the call
// fails or is interrupted and they are empty: the staged results folders clean up after
// themselves (bench/output/staged_folder.hpp), but not the parent folders they were made in, so
// `retrace.run(..., out="results/new")` interrupted would leave an empty results/new behind.

#include <filesystem>
#include <vector>

namespace retrace::python {

class CreatedFolders {
 public:
  /// Notes the ancestors of each target (a target included) that do not exist yet; empty targets
  /// are skipped.
  explicit CreatedFolders(const std::vector<std::filesystem::path>& targets);
  /// Removes those of them that are now empty folders, deepest first.
  void RemoveEmpty() const;

 private:
  std::vector<std::filesystem::path> missing_;
};

}  // namespace retrace::python

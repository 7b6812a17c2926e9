#include "bench/calibration/log_compare_run.hpp"

#include "bench/output/staged_folder.hpp"
#include "core/errors.hpp"
#include "viz/render_error.hpp"

namespace retrace::bench {

LogComparison CompareLogs(const LogCompareRequest& request) {
  if (request.runs.size() < 2)
    throw core::ConfigError("runs", "a comparison needs at least two log-localize folders");
  return {request, ReadLoggedRuns(request.runs, request.labels)};
}

std::vector<std::string> WriteLogCompareFolder(const LogComparison& compared) {
  StagedFolder folder(compared.request.out);
  std::vector<std::string> notes;
  try {
    WriteLogComparison(folder.path(), compared.runs);
  } catch (const viz::RenderError& e) {
    notes.push_back(std::string("no figure: ") + e.what());
  }
  folder.Commit();
  return notes;
}

std::string LogCompareSummary(const LogComparison& compared,
                              const std::vector<std::string>& notes) {
  std::string text = LoggedRunsTable(compared.runs);
  for (const std::string& note : notes) text += note + "\n";
  return text + "results: " + compared.request.out.string();
}

}  // namespace retrace::bench

#include "bench/metrics/flat_metrics.hpp"

#include <limits>

#include "bench/metrics/metrics_json.hpp"

namespace retrace::bench {
namespace {

void Flatten(const nlohmann::json& node, const std::string& prefix,
             std::map<std::string, double>& out) {
  if (node.is_object()) {
    for (const auto& [key, value] : node.items())
      Flatten(value, prefix.empty() ? key : prefix + "." + key, out);
  } else if (node.is_number()) {
    out[prefix] = node.get<double>();
  } else if (node.is_null()) {
    out[prefix] = std::numeric_limits<double>::quiet_NaN();
  } else if (node.is_boolean()) {
    out[prefix] = node.get<bool>() ? 1.0 : 0.0;
  }
  // arrays and strings carry no single number
}

}  // namespace

std::map<std::string, double> FlatMetrics(const AggregateMetrics& aggregate) {
  std::map<std::string, double> out;
  Flatten(ToJson(aggregate), "", out);
  return out;
}

bool IsTimingMetric(const std::string& name) { return name.rfind("cpu.", 0) == 0; }

}  // namespace retrace::bench

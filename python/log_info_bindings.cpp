// retrace.log_info: `retrace log-info` as a value (logs/sensor_log.hpp's IndexLog,
// bench/replay/log_description.hpp): what a recorded log holds and what the log commands would
// take from it.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <string>
#include <vector>

#include "bench/replay/log_description.hpp"
#include "logs/sensor_log.hpp"
#include "python/bindings.hpp"
#include "python/interruptible.hpp"
#include "python/log_arguments.hpp"
#include "python/pose_arrays.hpp"

namespace retrace::python {
namespace py = pybind11;
namespace {

/// What retrace.log_info returns.
struct LogInfo {
  std::string text;  ///< what `retrace log-info` prints
  std::string name, format;
  double duration_s = 0.0;
  py::list topics;  ///< [{topic, type, messages, first_s, last_s}]
  std::string scan_topic;
  py::dict scan;  ///< the scan topic's geometry
  std::string odometry_source, odometry_missing, reference_topic, reference_source;
  py::array_t<double> odometry, reference;  ///< (N, 4) [t, x, y, yaw]
  py::tuple mount;                          ///< X_RL (x, y, yaw)
  std::string mount_source;
  std::vector<std::string> notes;
  std::string problem;  ///< why the other log commands would refuse it ("": they would not)
  bool needs_choice = false;
};

py::dict ScanDict(const logs::ScanGeometry& g) {
  py::dict scan;
  scan["scans"] = g.scans;
  scan["beams"] = g.beams;
  scan["angle_min"] = g.angle_min;
  scan["angle_increment"] = g.angle_increment;
  scan["range_min"] = g.range_min;
  scan["range_max"] = g.range_max;
  scan["first_stamp"] = g.first_stamp;
  scan["last_stamp"] = g.last_stamp;
  return scan;
}

LogInfo ToLogInfo(const logs::LogIndex& index) {
  LogInfo info;
  info.text = bench::DescribeLog(index);
  info.name = index.name;
  info.format = std::string(logs::LogFormatName(index.format));
  info.duration_s = index.duration_s();
  for (const logs::LogTopic& t : index.topics) {
    info.topics.append(py::dict(py::arg("topic") = t.topic, py::arg("type") = t.type,
                                py::arg("messages") = t.messages, py::arg("first_s") = t.first_s,
                                py::arg("last_s") = t.last_s));
  }
  info.scan_topic = index.scan_topic;
  info.scan = ScanDict(index.scan);
  info.odometry_source = index.odometry_source;
  info.odometry_missing = index.odometry_missing;
  info.reference_topic = index.reference_topic;
  info.reference_source = index.reference_source;
  info.odometry = PoseArray(index.odometry);
  info.reference = PoseArray(index.reference);
  info.mount = py::make_tuple(index.X_RL.x, index.X_RL.y, index.X_RL.theta);
  info.mount_source = index.mount_source;
  info.notes = index.notes;
  info.problem = index.problem;
  info.needs_choice = index.needs_choice;
  return info;
}

LogInfo ReadLogInfo(const std::filesystem::path& log, const StreamArguments& streams) {
  PythonProgress progress(py::bool_(false));
  const logs::StreamChoice choice = StreamChoiceOf(streams);
  const logs::LogIndex index =
      CallInterruptibly(progress, CreatedFolders({}), [&] { return logs::IndexLog(log, choice); });
  return ToLogInfo(index);
}

void BindLogInfoType(py::module_& m) {
  py::class_<LogInfo>(m, "LogInfo", "What a recorded log holds (retrace log-info).")
      .def_readonly("text", &LogInfo::text, "what `retrace log-info` prints")
      .def_readonly("name", &LogInfo::name, "the log's path")
      .def_readonly("format", &LogInfo::format, "'CARMEN log', 'MCAP file', 'ROS 1 bag', ...")
      .def_readonly("duration_s", &LogInfo::duration_s, "from the first message to the last (s)")
      .def_readonly("topics", &LogInfo::topics, "[{topic, type, messages, first_s, last_s}]")
      .def_readonly("scan_topic", &LogInfo::scan_topic, "the scans' topic")
      .def_readonly("scan", &LogInfo::scan, "the scans' count and geometry (rad, m) and stamps (s)")
      .def_readonly("odometry_source", &LogInfo::odometry_source, "what the odometry comes from")
      .def_readonly("odometry_missing", &LogInfo::odometry_missing,
                    "why there is no odometry ('': there is)")
      .def_readonly("odometry", &LogInfo::odometry, "(N, 4) [t, x, y, yaw]: X_OR by stamp")
      .def_readonly("reference_topic", &LogInfo::reference_topic,
                    "the reference's topic ('': none)")
      .def_readonly("reference_source", &LogInfo::reference_source,
                    "what the reference comes from ('': none)")
      .def_readonly("reference", &LogInfo::reference, "(N, 4) [t, x, y, yaw]: X_WR by stamp")
      .def_readonly("mount", &LogInfo::mount, "the LiDAR mount X_RL (x, y, yaw)")
      .def_readonly("mount_source", &LogInfo::mount_source, "what the mount comes from")
      .def_readonly("notes", &LogInfo::notes, "what the user should know about the log")
      .def_readonly("problem", &LogInfo::problem,
                    "why log_teach and log_localize would refuse the log ('': none)")
      .def_readonly("needs_choice", &LogInfo::needs_choice,
                    "the problem is only a choice of topics to make")
      .def("__repr__", [](const LogInfo& i) { return "LogInfo('" + i.name + "')"; })
      .def("__str__", [](const LogInfo& i) { return i.text; });
}

}  // namespace

void BindLogInfo(py::module_& m) {
  BindLogInfoType(m);
  m.def(
      "log_info",
      [](const std::filesystem::path& log, std::string scan_topic, std::string odometry_topic,
         std::string reference_topic, std::string odom_frame, std::string base_frame) {
        return ReadLogInfo(log,
                           {scan_topic, odometry_topic, reference_topic, odom_frame, base_frame});
      },
      py::arg("log"), py::kw_only(), py::arg("scan_topic") = "", py::arg("odometry_topic") = "",
      py::arg("reference_topic") = "", py::arg("odom_frame") = "odom", py::arg("base_frame") = "",
      "`retrace log-info`: what a recorded log (CARMEN, MCAP, rosbag2, ROS 1 bag) holds. Unlike "
      "the command line it returns a log that the other commands would refuse, with the reason "
      "in `problem`; a log it cannot read at all raises. Returns a LogInfo.");
}

}  // namespace retrace::python

// The readers of the files retrace writes (docs/FORMATS.md), for retrace.load_results
// (python/retrace/results.py) and anyone: JSON as dict, TUM trajectories and AutoNavi paths as
// arrays, CSV tables as columns, ROS maps as uint8 images; and `retrace render` and `report`.
// Each reads with the library's own reader, so a malformed file raises the command line's line.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/output/html_report.hpp"
#include "bench/output/render_results.hpp"
#include "core/errors.hpp"
#include "core/occupancy_grid.hpp"
#include "io/csv_reader.hpp"
#include "io/json_writer.hpp"
#include "io/ros_map.hpp"
#include "io/route_file.hpp"
#include "python/bindings.hpp"
#include "python/json_to_python.hpp"
#include "python/numpy_arrays.hpp"
#include "python/pose_arrays.hpp"
#include "python/table_columns.hpp"

namespace retrace::python {
namespace py = pybind11;
using Path = std::filesystem::path;
namespace {

py::dict ReadCsvColumns(const Path& path) {
  const std::vector<io::CsvRecord> records = io::ReadCsvFile(path);
  if (records.empty()) throw core::IoError(path.string() + ": empty table (no header row)");
  const std::vector<std::string>& header = records.front().cells;
  std::vector<std::vector<std::string>> rows;
  for (std::size_t i = 1; i < records.size(); ++i) {
    if (records[i].cells.size() != header.size()) {
      throw core::IoError(path.string() + ":" + std::to_string(records[i].line) + ": " +
                          std::to_string(records[i].cells.size()) + " cells, the header has " +
                          std::to_string(header.size()));
    }
    rows.push_back(records[i].cells);
  }
  return TableColumns(header, rows);
}

// The map as map_saver's trinary image: 0 occupied, 254 free, 205 unknown, by the YAML's
// thresholds; row 0 is the lowest y (the grid's order: imshow(origin="lower")).
py::dict ReadMapImage(const Path& yaml) {
  const io::RosMapMetadata metadata = io::ReadRosMapMetadata(yaml);
  const core::OccupancyGrid grid = io::ReadRosMap(yaml);
  std::vector<std::uint8_t> pixels;
  pixels.reserve(grid.log_odds().size());
  for (const float l : grid.log_odds()) {
    const double p = core::InverseLogit(l);
    pixels.push_back(p > metadata.occupied_thresh ? 0 : p < metadata.free_thresh ? 254 : 205);
  }
  py::dict map;
  map["image"] = OwningArray(std::move(pixels), {grid.height(), grid.width()});
  map["resolution"] = grid.resolution();
  map["origin"] = py::make_tuple(grid.origin().x(), grid.origin().y());
  return map;
}

}  // namespace

void BindResults(py::module_& m) {
  m.def(
      "read_json", [](const Path& path) { return JsonToPython(io::ReadJsonFile(path)); },
      py::arg("path"), "A JSON file (metrics.json, comparison.json, ...) as dicts and lists.");
  m.def(
      "read_tum", [](const Path& path) { return PoseArray(io::ReadTum(path)); }, py::arg("path"),
      "A TUM trajectory (est.tum, gt.tum, ...) as an (N, 4) float64 array [t, x, y, yaw] (s, m, "
      "m, rad).");
  m.def(
      "read_path", [](const Path& path) { return PathArray(io::ReadPathFile(path)); },
      py::arg("path"),
      "An AutoNavi path file (a teach folder's paths/path_<k>.txt) as an (N, 3) float64 array "
      "[x, y, yaw] in its map's frame.");
  m.def("read_csv", &ReadCsvColumns, py::arg("path"),
        "A CSV table (errors.csv, est_map.csv, results.csv, ...) as {column: float64 array} "
        "(columns of text: lists of str).");
  m.def("read_map", &ReadMapImage, py::arg("yaml"),
        "A ROS map (a teach folder's maps/ogm_<k>.yaml) as {'image': (H, W) uint8, 0 occupied, "
        "254 free, 205 unknown, row 0 the lowest y; 'resolution': m per cell; 'origin': (x, y) "
        "of the lower-left corner}.");
  m.def(
      "render", [](const Path& folder) { return bench::RenderResults(folder); }, py::arg("folder"),
      py::call_guard<py::gil_scoped_release>(),
      "`retrace render`: render the figures of a results folder again. Returns the files.");
  m.def(
      "report",
      [](const Path& folder) {
        bench::WriteHtmlReport(folder);
        return folder / "report.html";
      },
      py::arg("folder"), py::call_guard<py::gil_scoped_release>(),
      "`retrace report`: write <folder>/report.html, the folder's page. Returns its path.");
}

}  // namespace retrace::python

#include "python/table_columns.hpp"

#include <optional>

#include "io/csv_reader.hpp"
#include "python/numpy_arrays.hpp"

namespace retrace::python {
namespace py = pybind11;
namespace {

// Column j as numbers, or nullopt when a cell is not one.
std::optional<std::vector<double>> NumberColumn(const std::vector<std::vector<std::string>>& rows,
                                                std::size_t j) {
  std::vector<double> numbers;
  numbers.reserve(rows.size());
  for (const std::vector<std::string>& row : rows) {
    const std::optional<double> v = io::ParseCsvNumber(row[j]);
    if (!v) return std::nullopt;
    numbers.push_back(*v);
  }
  return numbers;
}

}  // namespace

py::dict TableColumns(const std::vector<std::string>& header,
                      const std::vector<std::vector<std::string>>& rows) {
  py::dict columns;
  for (std::size_t j = 0; j < header.size(); ++j) {
    std::optional<std::vector<double>> numbers = NumberColumn(rows, j);
    if (numbers) {
      const auto n = static_cast<py::ssize_t>(numbers->size());
      columns[py::str(header[j])] = OwningArray(std::move(*numbers), {n});
      continue;
    }
    py::list text;
    for (const std::vector<std::string>& row : rows) text.append(py::str(row[j]));
    columns[py::str(header[j])] = text;
  }
  return columns;
}

}  // namespace retrace::python

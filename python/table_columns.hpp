#pragma once
// A table (a CSV file's rows, a sweep's results) as a dict of columns: a column whose every cell
// is a number (nan, inf and -inf included) is a float64 NumPy array, any other a list of str.

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

namespace retrace::python {

/// rows[i][j] is column j of row i; every row has header.size() cells.
pybind11::dict TableColumns(const std::vector<std::string>& header,
                            const std::vector<std::vector<std::string>>& rows);

}  // namespace retrace::python

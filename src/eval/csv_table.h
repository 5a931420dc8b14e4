#pragma once
// A CSV file of numbers with a header row (the soak's samples, eval's
// tables): one column per header name. An empty cell, "nan" or "-" is NaN.
#include <string>
#include <vector>

namespace dv {

struct CsvTable {
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;  // columns[i] belongs to names[i]
  // The index of the column called `name`, or -1.
  int find(const std::string& name) const;
};

// Throws InputError naming the file, line and column for a cell that is
// not a number or a row with the wrong number of cells.
CsvTable readCsvTable(const std::string& path);

}  // namespace dv

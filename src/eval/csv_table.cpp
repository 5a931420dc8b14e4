#include "eval/csv_table.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "core/error.h"

namespace dv {
namespace {

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == ',') {
      out.emplace_back();
    } else if (c != '\r') {
      out.back() += c;
    }
  }
  for (auto& cell : out) {  // trim spaces
    const size_t a = cell.find_first_not_of(" \t"), b = cell.find_last_not_of(" \t");
    cell = a == std::string::npos ? "" : cell.substr(a, b - a + 1);
  }
  return out;
}

}  // namespace

int CsvTable::find(const std::string& name) const {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return int(i);
  return -1;
}

CsvTable readCsvTable(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  CsvTable table;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto row = cells(line);
    if (table.names.empty()) {
      table.names = row;
      table.columns.resize(row.size());
      continue;
    }
    if (row.size() != table.names.size()) {
      throw InputError(path, "line " + std::to_string(line_no) + ": " + std::to_string(row.size()) +
                                 " cells, the header has " + std::to_string(table.names.size()));
    }
    for (size_t i = 0; i < row.size(); ++i) {
      const std::string& cell = row[i];
      double v = std::nan("");
      if (!cell.empty() && cell != "-" && cell != "nan") {
        char* end = nullptr;
        v = std::strtod(cell.c_str(), &end);
        if (end == cell.c_str() || *end != '\0') {
          throw InputError(path, "line " + std::to_string(line_no) + ", column " + std::to_string(i + 1) + " (" +
                                     table.names[i] + "): \"" + cell + "\" is not a number");
        }
      }
      table.columns[i].push_back(v);
    }
  }
  if (table.names.empty()) throw InputError(path, "empty file: no header row");
  return table;
}

}  // namespace dv

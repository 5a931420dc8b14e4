// `dotvision plot CSV OUT.png`: the CSV's columns as lines against its first
// column (the soak's samples against time), or one column's histogram.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "app/commands.h"
#include "core/error.h"
#include "eval/chart.h"
#include "eval/csv_table.h"

namespace dv::app {

namespace {

struct PlotArgs {
  std::string csv, out, columns, title, ylabel, histogram;
  int bins = 30;
  int width = 960, height = 540;
};

std::vector<std::string> splitList(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

int columnOrThrow(const CsvTable& t, const std::string& name, const std::string& path) {
  const int i = t.find(name);
  if (i < 0) throw InputError(path, "no column \"" + name + "\" (the header names the columns)");
  return i;
}

}  // namespace

CommandFn addPlotCommand(CLI::App& root) {
  auto a = std::make_shared<PlotArgs>();
  CLI::App* cmd = root.add_subcommand("plot", "Chart a CSV file of numbers as a PNG: its columns against the first");
  cmd->add_option("csv", a->csv, "CSV file with a header row")->required();
  cmd->add_option("out", a->out, "image to write (.png)")->required();
  cmd->add_option("--columns", a->columns, "comma-separated columns to draw (default: all but the first)");
  cmd->add_option("--title", a->title, "chart title (default: the CSV's file name)");
  cmd->add_option("--ylabel", a->ylabel, "label of the y axis");
  cmd->add_option("--histogram", a->histogram, "draw this column's histogram instead");
  cmd->add_option("--bins", a->bins, "histogram bins")->default_str("30")->check(CLI::Range(1, 1000));
  cmd->add_option("--width", a->width, "image width in pixels")->default_str("960")->check(CLI::Range(200, 8000));
  cmd->add_option("--height", a->height, "image height in pixels")->default_str("540")->check(CLI::Range(150, 8000));

  return [a] {
    const CsvTable table = readCsvTable(a->csv);
    const std::string title = a->title.empty() ? std::filesystem::path(a->csv).filename().string() : a->title;
    const ChartStyle style{a->width, a->height};
    std::string why;
    bool ok = false;
    if (!a->histogram.empty()) {
      const int c = columnOrThrow(table, a->histogram, a->csv);
      ok = writeHistogram(a->out, title, a->histogram, table.columns[size_t(c)], a->bins, &why, style);
    } else {
      std::vector<int> chosen;
      if (a->columns.empty()) {
        for (int i = 1; i < int(table.names.size()); ++i) chosen.push_back(i);
      } else {
        for (const auto& name : splitList(a->columns)) chosen.push_back(columnOrThrow(table, name, a->csv));
      }
      if (chosen.empty()) throw InputError(a->csv, "only one column: nothing to draw against it");
      std::vector<Series> series;
      for (int c : chosen) series.push_back({table.names[size_t(c)], table.columns[0], table.columns[size_t(c)]});
      ok = writeLineChart(a->out, title, table.names[0], a->ylabel, series, &why, style);
    }
    if (!ok) {
      std::fprintf(stderr, "plot: %s\n", why.c_str());
      return kExitFailure;
    }
    std::printf("plot: wrote %s\n", a->out.c_str());
    return kExitOk;
  };
}

}  // namespace dv::app

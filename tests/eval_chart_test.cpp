// Charts: a PNG of the requested size with the axes, each series and the
// bars drawn in their colors; nothing to draw or nowhere to write is a
// reason, not a crash. The CSV reader names bad cells. `dotvision plot`.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "core/error.h"
#include "eval/chart.h"
#include "eval/csv_table.h"
#include "temp_dir.h"

namespace dv {
namespace {

// Pixels within a few levels of `bgr` (antialiased lines blend at edges).
int pixelsOfColor(const cv::Mat& img, cv::Vec3b bgr) {
  int n = 0;
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x) {
      const cv::Vec3b p = img.at<cv::Vec3b>(y, x);
      if (std::abs(p[0] - bgr[0]) + std::abs(p[1] - bgr[1]) + std::abs(p[2] - bgr[2]) < 12) ++n;
    }
  return n;
}

const cv::Vec3b kFirst(180, 119, 31), kSecond(14, 127, 255);

TEST(Chart, LineChartDrawsEverySeriesAtTheRequestedSize) {
  TempDir dir("dv_chart");
  Series rising{"rss_mb", {}, {}}, wave{"fds", {}, {}};
  for (int i = 0; i < 60; ++i) {
    rising.xs.push_back(i * 10);
    rising.ys.push_back(100 + i);
    wave.xs.push_back(i * 10);
    wave.ys.push_back(i == 30 ? std::nan("") : 130 + 20 * std::sin(i / 5.0));  // a gap in the line
  }
  std::string why;
  ASSERT_TRUE(writeLineChart(dir.file("c.png"), "soak", "t (s)", "MB", {rising, wave}, &why, {640, 400})) << why;
  const cv::Mat img = cv::imread(dir.file("c.png"), cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, 640);
  EXPECT_EQ(img.rows, 400);
  EXPECT_GT(pixelsOfColor(img, kFirst), 300);   // a line across the chart, 2 px wide, and its legend
  EXPECT_GT(pixelsOfColor(img, kSecond), 300);
  EXPECT_GT(pixelsOfColor(img, {40, 40, 40}), 200);  // axes, ticks and labels
  // Where the first series is drawn, it rises: its pixels' mean row on the
  // left half lies below (larger y than) the right half's.
  double left = 0, right = 0;
  int nl = 0, nr = 0;
  for (int y = 60; y < img.rows - 60; ++y)
    for (int x = 200; x < img.cols - 30; ++x) {
      const cv::Vec3b p = img.at<cv::Vec3b>(y, x);
      if (std::abs(p[0] - kFirst[0]) + std::abs(p[1] - kFirst[1]) + std::abs(p[2] - kFirst[2]) >= 12) continue;
      (x < img.cols / 2 ? left : right) += y;
      ++(x < img.cols / 2 ? nl : nr);
    }
  ASSERT_GT(nl, 0);
  ASSERT_GT(nr, 0);
  EXPECT_GT(left / nl, right / nr);
}

TEST(Chart, HistogramDrawsBars) {
  TempDir dir("dv_chart");
  std::vector<double> values;
  for (int i = 0; i < 1000; ++i) values.push_back(std::fmod(i * 0.618, 1.0) * 20 + (i % 3));
  values.push_back(std::nan(""));
  std::string why;
  ASSERT_TRUE(writeHistogram(dir.file("h.png"), "p99", "ms", values, 20, &why)) << why;
  const cv::Mat img = cv::imread(dir.file("h.png"), cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, 960);
  EXPECT_EQ(img.rows, 540);
  EXPECT_GT(pixelsOfColor(img, kFirst), 960 * 540 / 10);  // filled bars
}

TEST(Chart, NothingToDrawOrNowhereToWriteIsAReason) {
  TempDir dir("dv_chart");
  std::string why;
  EXPECT_FALSE(writeLineChart(dir.file("e.png"), "t", "x", "y", {{"a", {1, 2}, {std::nan(""), INFINITY}}}, &why));
  EXPECT_NE(why.find("no finite values"), std::string::npos) << why;
  EXPECT_FALSE(writeHistogram(dir.file("e.png"), "t", "x", {}, 10, &why));
  EXPECT_FALSE(writeHistogram(dir.file("e.png"), "t", "x", {1, 2}, 0, &why));
  const std::string nowhere = dir.file("missing/dir/c.png");
  EXPECT_FALSE(writeLineChart(nowhere, "t", "x", "y", {{"a", {1, 2}, {3, 4}}}, &why));
  EXPECT_NE(why.find(nowhere), std::string::npos) << why;
  // One point or a flat line still makes a chart.
  EXPECT_TRUE(writeLineChart(dir.file("flat.png"), "t", "x", "y", {{"a", {5}, {7}}}, &why)) << why;
}

TEST(CsvTable, ReadsColumnsAndNamesBadCells) {
  TempDir dir("dv_csv");
  std::ofstream(dir.file("ok.csv")) << "t_s,rss_mb, fds\n0,100.5,12\n10,,13\r\n\n20,101,-\n";
  const CsvTable t = readCsvTable(dir.file("ok.csv"));
  ASSERT_EQ(t.names, (std::vector<std::string>{"t_s", "rss_mb", "fds"}));
  EXPECT_EQ(t.columns[0], (std::vector<double>{0, 10, 20}));
  EXPECT_TRUE(std::isnan(t.columns[1][1]));
  EXPECT_TRUE(std::isnan(t.columns[2][2]));
  EXPECT_EQ(t.find("fds"), 2);
  EXPECT_EQ(t.find("nope"), -1);

  std::ofstream(dir.file("bad.csv")) << "t,a\n0,1\n1,x2\n";
  try {
    readCsvTable(dir.file("bad.csv"));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("line 3, column 2 (a): \"x2\" is not a number"), std::string::npos) << e.what();
  }
  std::ofstream(dir.file("short.csv")) << "t,a\n0\n";
  EXPECT_THROW(readCsvTable(dir.file("short.csv")), InputError);
}

int run(const std::string& args) {
  const int status = std::system((std::string(DV_CLI_PATH) + " " + args + " >/dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(PlotCli, WritesTheChartOfACsvFile) {
  TempDir dir("dv_plot");
  std::ofstream(dir.file("s.csv")) << "t_s,rss_mb,fds\n0,100,12\n10,101,12\n20,101.5,13\n";
  EXPECT_EQ(run("plot " + dir.file("s.csv") + " " + dir.file("s.png") + " --width 500 --height 300"), 0);
  const cv::Mat img = cv::imread(dir.file("s.png"));
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, 500);
  EXPECT_EQ(img.rows, 300);
  EXPECT_EQ(run("plot " + dir.file("s.csv") + " " + dir.file("h.png") + " --histogram rss_mb --bins 5"), 0);
  EXPECT_FALSE(cv::imread(dir.file("h.png")).empty());
  EXPECT_EQ(run("plot " + dir.file("s.csv") + " " + dir.file("x.png") + " --columns nope"), 2);
  EXPECT_EQ(run("plot " + dir.file("missing.csv") + " " + dir.file("x.png")), 2);
}

}  // namespace
}  // namespace dv

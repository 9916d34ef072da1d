// HTML report and SVG plots: well-formed, escaped, NaN gaps, long series reduced.
#include "evaluation/html_report.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace slipgraph {
namespace {

size_t Count(const std::string& text, const std::string& what) {
  size_t count = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++count;
  }
  return count;
}

TEST(HtmlReport, EscapesTextAndWrapsAPage) {
  HtmlReport report("a < b & c");
  report.Table({"x"}, {{"<script>"}});
  const std::string html = report.Html();
  EXPECT_NE(html.find("<!DOCTYPE html>"), std::string::npos);
  EXPECT_NE(html.find("a &lt; b &amp; c"), std::string::npos);
  EXPECT_EQ(html.find("<script>"), std::string::npos);
  EXPECT_NE(html.find("&lt;script&gt;"), std::string::npos);
}

TEST(RenderSvg, DrawsEachSeriesWithALegendAndBreaksAtNaN) {
  Plot plot{"v", "m/s", {}, {{1.0, 2.0}}};
  PlotSeries a{"truth", {0, 1, 2, 3}, {0, 1, std::nan(""), 3}};
  PlotSeries b{"smoother", {0, 1, 2, 3}, {0, 1, 2, 3}, "#ff0000", true, {0.1, 0.1, 0.1, 0.1}};
  plot.series = {a, b};
  const std::string svg = RenderSvg(plot);
  EXPECT_EQ(Count(svg, "<svg"), 1u);
  EXPECT_EQ(Count(svg, "</svg>"), 1u);
  EXPECT_EQ(Count(svg, "<path"), 2u);
  EXPECT_EQ(Count(svg, "<polygon"), 1u);  // the +-2 sd band
  EXPECT_NE(svg.find("truth"), std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
  EXPECT_NE(svg.find("<rect x="), std::string::npos);  // the shaded interval
  // The NaN splits the truth line into two subpaths ("M" twice).
  const size_t path = svg.find("<path d=\"");
  const std::string d = svg.substr(path, svg.find('"', path + 9) - path);
  EXPECT_EQ(Count(d, "M"), 2u);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
}

TEST(RenderSvg, ReducesLongSeriesButKeepsTheirExtremes) {
  PlotSeries s{"long", {}, {}};
  for (int i = 0; i < 200000; ++i) {
    s.t.push_back(i * 0.01);
    s.y.push_back(i == 123456 ? 50.0 : std::sin(i * 0.001));
  }
  const std::string svg = RenderSvg(Plot{"long", "-", {s}, {}});
  EXPECT_LT(svg.size(), 200000u);                  // a few points per pixel column, not 200 k
  EXPECT_NE(svg.find(">40<"), std::string::npos);  // the spike sets the axis
  // and is drawn: the line reaches the top of the plot (y pixel near the top margin).
  const size_t path = svg.find("<path d=\"");
  std::istringstream d(svg.substr(path + 9, svg.find('"', path + 9) - path - 9));
  std::string command;
  double x = 0.0, y = 0.0, top = 1e9;
  while (d >> command >> y) {
    x = std::stod(command.substr(1));
    top = std::min(top, y);
  }
  EXPECT_GT(x, 0.0);
  EXPECT_LT(top, 45.0);
}

TEST(RenderSvg, SaysNoDataForAnEmptyPlot) {
  EXPECT_NE(RenderSvg(Plot{"empty", "-", {}, {}}).find("no data"), std::string::npos);
}

}  // namespace
}  // namespace slipgraph

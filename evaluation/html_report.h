// Self-contained HTML reports with inline SVG plots: no scripts, no external files, so a report
// opens anywhere and can be attached to an issue. Used by `compare` (and the later workbench
// reports). Long series are reduced per pixel column to their minimum and maximum, so spikes
// survive and a 35-minute log still makes a small page.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace slipgraph {

struct PlotSeries {
  std::string label;
  std::vector<double> t, y;  // NaN values break the line
  std::string color = "#1f77b4";
  bool dashed = false;
  std::vector<double> sd;  // optional: a +-2 sd band around y, same length
  bool points = false;     // a scatter of dots instead of a line (at most ~2000 drawn)
};

// An empty series with its label and style, to fill with t and y.
inline PlotSeries NewSeries(const std::string& label, const std::string& color,
                            bool dashed = false) {
  PlotSeries s;
  s.label = label, s.color = color, s.dashed = dashed;
  return s;
}

struct Plot {
  std::string title;
  std::string y_label;
  std::vector<PlotSeries> series;
  std::vector<std::pair<double, double>> shaded;  // time intervals to shade (e.g. events)
  std::string x_label = "t (s)";
  bool equal_axes = false;  // same scale on x and y (scatter of 2-D errors)
};

// One plot as an <svg> element (width x height pixels).
std::string RenderSvg(const Plot& plot, int width = 960, int height = 260);

std::string HtmlEscape(const std::string& text);

class HtmlReport {
 public:
  explicit HtmlReport(std::string title);
  void Heading(const std::string& text, int level = 2);
  void Paragraph(const std::string& text);
  void Preformatted(const std::string& text);
  void Table(const std::vector<std::string>& header,
             const std::vector<std::vector<std::string>>& rows);
  void Figure(const Plot& plot);
  // Appends another report's body (not its title).
  void Append(const HtmlReport& other) { body_ += other.body_; }
  std::string Html() const;
  // Throws InputError (a std::runtime_error) naming the path when it cannot be written.
  void Write(const std::string& path) const;

 private:
  std::string title_;
  std::string body_;
};

}  // namespace slipgraph

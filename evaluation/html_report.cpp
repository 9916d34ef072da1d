#include "evaluation/html_report.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "io/text_file.h"

namespace slipgraph {
namespace {

constexpr int kLeft = 70, kRight = 170, kTop = 28, kBottom = 34;  // margins, px

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void Add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool Valid() const { return lo <= hi; }
};

// A "nice" tick step for a span, about `count` ticks.
double TickStep(double span, int count) {
  const double raw = span / count;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * magnitude >= raw) return m * magnitude;
  }
  return 10.0 * magnitude;
}

std::string Number(double v) {
  std::ostringstream out;
  out.precision(4);
  out << (std::abs(v) < 1e-12 ? 0.0 : v);
  return out.str();
}

// Per pixel column: the first, minimum, maximum and last finite points, in time order; a NaN
// breaks the line (returned as a NaN point).
std::vector<std::pair<double, double>> Reduce(const std::vector<double>& t,
                                              const std::vector<double>& y, double t0, double t1,
                                              int columns) {
  std::vector<std::pair<double, double>> out;
  const size_t n = std::min(t.size(), y.size());
  if (n <= static_cast<size_t>(4 * columns)) {
    for (size_t i = 0; i < n; ++i) out.emplace_back(t[i], y[i]);
    return out;
  }
  size_t i = 0;
  while (i < n) {
    const int column = static_cast<int>((t[i] - t0) / (t1 - t0) * columns);
    size_t end = i;
    size_t first = n, last = n, lo = n, hi = n;
    bool gap = false;
    while (end < n && static_cast<int>((t[end] - t0) / (t1 - t0) * columns) == column) {
      if (!std::isfinite(y[end])) {
        gap = true;
      } else {
        if (first == n) first = end;
        last = end;
        if (lo == n || y[end] < y[lo]) lo = end;
        if (hi == n || y[end] > y[hi]) hi = end;
      }
      ++end;
    }
    if (end == i) ++end;  // a time outside [t0, t1]: skip it
    std::vector<size_t> keep = {first, lo, hi, last};
    keep.erase(std::remove(keep.begin(), keep.end(), n), keep.end());
    std::sort(keep.begin(), keep.end());
    keep.erase(std::unique(keep.begin(), keep.end()), keep.end());
    for (size_t k : keep) out.emplace_back(t[k], y[k]);
    if (gap) out.emplace_back(t[end - 1], std::nan(""));
    i = end;
  }
  return out;
}

}  // namespace

std::string HtmlEscape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string RenderSvg(const Plot& plot, int width, int height) {
  Range tr, yr;
  for (const PlotSeries& s : plot.series) {
    for (size_t i = 0; i < s.t.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.y[i])) continue;
      tr.Add(s.t[i]);
      if (s.sd.size() == s.y.size() && std::isfinite(s.sd[i])) {
        yr.Add(s.y[i] - 2.0 * s.sd[i]);
        yr.Add(s.y[i] + 2.0 * s.sd[i]);
      } else {
        yr.Add(s.y[i]);
      }
    }
  }
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << width << " " << height << "\" font-family=\"sans-serif\" "
      << "font-size=\"11\">\n";
  svg << "<text x=\"" << kLeft << "\" y=\"16\" font-size=\"13\" font-weight=\"bold\">"
      << HtmlEscape(plot.title) << "</text>\n";
  if (!tr.Valid() || !yr.Valid()) {
    svg << "<text x=\"" << kLeft << "\" y=\"" << height / 2 << "\">no data</text>\n</svg>\n";
    return svg.str();
  }
  if (tr.hi <= tr.lo) tr.hi = tr.lo + 1.0;
  if (yr.hi <= yr.lo) {
    yr.lo -= 0.5;
    yr.hi += 0.5;
  }
  const double pad = 0.05 * (yr.hi - yr.lo);
  yr.lo -= pad;
  yr.hi += pad;
  const int pw = width - kLeft - kRight, ph = height - kTop - kBottom;
  if (plot.equal_axes) {  // widen the tighter axis so one unit is as long on both
    const double per_px = std::max((tr.hi - tr.lo) / pw, (yr.hi - yr.lo) / ph);
    const double tc = 0.5 * (tr.lo + tr.hi), yc = 0.5 * (yr.lo + yr.hi);
    tr.lo = tc - 0.5 * per_px * pw;
    tr.hi = tc + 0.5 * per_px * pw;
    yr.lo = yc - 0.5 * per_px * ph;
    yr.hi = yc + 0.5 * per_px * ph;
  }
  const auto X = [&](double t) { return kLeft + (t - tr.lo) / (tr.hi - tr.lo) * pw; };
  const auto Y = [&](double y) { return kTop + (yr.hi - y) / (yr.hi - yr.lo) * ph; };
  for (const auto& [a, b] : plot.shaded) {
    const double x0 = X(std::max(a, tr.lo)), x1 = X(std::min(b, tr.hi));
    if (x1 > x0) {
      svg << "<rect x=\"" << x0 << "\" y=\"" << kTop << "\" width=\"" << x1 - x0 << "\" height=\""
          << ph << "\" fill=\"#f4d03f\" fill-opacity=\"0.25\"/>\n";
    }
  }
  // Axes, grid and ticks.
  svg << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << pw << "\" height=\"" << ph
      << "\" fill=\"none\" stroke=\"#444\"/>\n";
  const double ty = TickStep(yr.hi - yr.lo, 5);
  for (double v = std::ceil(yr.lo / ty) * ty; v <= yr.hi; v += ty) {
    svg << "<line x1=\"" << kLeft << "\" x2=\"" << kLeft + pw << "\" y1=\"" << Y(v) << "\" y2=\""
        << Y(v) << "\" stroke=\"#ddd\"/><text x=\"" << kLeft - 6 << "\" y=\"" << Y(v) + 4
        << "\" text-anchor=\"end\">" << Number(v) << "</text>\n";
  }
  const double tx = TickStep(tr.hi - tr.lo, 10);
  for (double v = std::ceil(tr.lo / tx) * tx; v <= tr.hi; v += tx) {
    svg << "<line x1=\"" << X(v) << "\" x2=\"" << X(v) << "\" y1=\"" << kTop << "\" y2=\""
        << kTop + ph << "\" stroke=\"#eee\"/><text x=\"" << X(v) << "\" y=\"" << kTop + ph + 14
        << "\" text-anchor=\"middle\">" << Number(v) << "</text>\n";
  }
  svg << "<text x=\"" << kLeft + pw / 2 << "\" y=\"" << height - 4 << "\" text-anchor=\"middle\">"
      << HtmlEscape(plot.x_label) << "</text>\n";
  svg << "<text transform=\"translate(14," << kTop + ph / 2
      << ") rotate(-90)\" text-anchor=\"middle\">" << HtmlEscape(plot.y_label) << "</text>\n";
  // Series: bands first, then lines, then the legend.
  for (const PlotSeries& s : plot.series) {
    if (s.sd.size() != s.y.size()) continue;
    std::vector<double> upper(s.y.size()), lower(s.y.size());
    for (size_t i = 0; i < s.y.size(); ++i) {
      upper[i] = s.y[i] + 2.0 * s.sd[i];
      lower[i] = s.y[i] - 2.0 * s.sd[i];
    }
    const auto up = Reduce(s.t, upper, tr.lo, tr.hi, pw);
    const auto down = Reduce(s.t, lower, tr.lo, tr.hi, pw);
    std::ostringstream points;
    for (const auto& [t, y] : up) {
      if (std::isfinite(y)) points << X(t) << "," << Y(y) << " ";
    }
    for (auto it = down.rbegin(); it != down.rend(); ++it) {
      if (std::isfinite(it->second)) points << X(it->first) << "," << Y(it->second) << " ";
    }
    svg << "<polygon points=\"" << points.str() << "\" fill=\"" << s.color
        << "\" fill-opacity=\"0.15\" stroke=\"none\"/>\n";
  }
  for (const PlotSeries& s : plot.series) {
    if (s.points) {
      const size_t n = std::min(s.t.size(), s.y.size());
      const size_t stride = std::max<size_t>(1, n / 2000);
      for (size_t i = 0; i < n; i += stride) {
        if (!std::isfinite(s.t[i]) || !std::isfinite(s.y[i])) continue;
        svg << "<circle cx=\"" << X(s.t[i]) << "\" cy=\"" << Y(s.y[i]) << "\" r=\"1.5\" fill=\""
            << s.color << "\" fill-opacity=\"0.6\"/>";
      }
      svg << "\n";
      continue;
    }
    std::ostringstream path;
    bool pen_down = false;
    for (const auto& [t, y] : Reduce(s.t, s.y, tr.lo, tr.hi, pw)) {
      if (!std::isfinite(y)) {
        pen_down = false;
        continue;
      }
      path << (pen_down ? "L" : "M") << X(t) << " " << Y(y) << " ";
      pen_down = true;
    }
    svg << "<path d=\"" << path.str() << "\" fill=\"none\" stroke=\"" << s.color
        << "\" stroke-width=\"1.3\"" << (s.dashed ? " stroke-dasharray=\"5,3\"" : "") << "/>\n";
  }
  int row = 0;
  for (const PlotSeries& s : plot.series) {
    const int y = kTop + 10 + 16 * row++;
    svg << "<line x1=\"" << kLeft + pw + 10 << "\" x2=\"" << kLeft + pw + 30 << "\" y1=\"" << y
        << "\" y2=\"" << y << "\" stroke=\"" << s.color << "\" stroke-width=\"2\""
        << (s.dashed ? " stroke-dasharray=\"5,3\"" : "") << "/><text x=\"" << kLeft + pw + 34
        << "\" y=\"" << y + 4 << "\">" << HtmlEscape(s.label)
        << (s.sd.size() == s.y.size() ? " (&#177;2&#963;)" : "") << "</text>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

HtmlReport::HtmlReport(std::string title) : title_(std::move(title)) {}

void HtmlReport::Heading(const std::string& text, int level) {
  level = std::clamp(level, 1, 4);
  body_ +=
      "<h" + std::to_string(level) + ">" + HtmlEscape(text) + "</h" + std::to_string(level) + ">\n";
}

void HtmlReport::Paragraph(const std::string& text) {
  body_ += "<p>" + HtmlEscape(text) + "</p>\n";
}

void HtmlReport::Preformatted(const std::string& text) {
  body_ += "<pre>" + HtmlEscape(text) + "</pre>\n";
}

void HtmlReport::Table(const std::vector<std::string>& header,
                       const std::vector<std::vector<std::string>>& rows) {
  body_ += "<table>\n<tr>";
  for (const std::string& h : header) body_ += "<th>" + HtmlEscape(h) + "</th>";
  body_ += "</tr>\n";
  for (const auto& row : rows) {
    body_ += "<tr>";
    for (const std::string& cell : row) body_ += "<td>" + HtmlEscape(cell) + "</td>";
    body_ += "</tr>\n";
  }
  body_ += "</table>\n";
}

void HtmlReport::Figure(const Plot& plot) { body_ += "<div>" + RenderSvg(plot) + "</div>\n"; }

std::string HtmlReport::Html() const {
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
         HtmlEscape(title_) +
         "</title>\n<style>body{font-family:sans-serif;margin:24px;max-width:1000px}"
         "table{border-collapse:collapse;margin:8px 0}td,th{border:1px solid #bbb;"
         "padding:3px 8px;text-align:right}th{background:#eee}pre{background:#f6f6f6;"
         "padding:8px;overflow-x:auto}</style>\n</head>\n<body>\n<h1>" +
         HtmlEscape(title_) + "</h1>\n" + body_ + "</body>\n</html>\n";
}

void HtmlReport::Write(const std::string& path) const { WriteTextFile(path, Html()); }

}  // namespace slipgraph

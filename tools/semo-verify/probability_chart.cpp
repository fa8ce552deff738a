#include "probability_chart.hpp"
#include "svg_text.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace semo::cli {
namespace {

constexpr double kPlotWidth = 450, kHeight = 420, kLeft = 70, kTop = 40, kBottom = 50;
constexpr const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2"};


}  // namespace

std::string probabilityChartSvg(const std::vector<ChartSeries>& series, const std::string& title, const std::string& unit) {
  std::size_t horizon = 1;
  for (const ChartSeries& s : series) horizon = std::max(horizon, s.values.empty() ? std::size_t{1} : s.values.size() - 1);
  // The legend's column is as wide as its longest name (about 7 px a character at 12 px).
  std::size_t longest = 0;
  for (const ChartSeries& s : series) longest = std::max(longest, s.name.size());
  const double kRight = 60 + 7.0 * static_cast<double>(longest), kWidth = kLeft + kPlotWidth + kRight;
  const double plotWidth = kPlotWidth, plotHeight = kHeight - kTop - kBottom;
  auto x = [&](std::size_t t) { return kLeft + plotWidth * static_cast<double>(t) / static_cast<double>(horizon); };
  auto y = [&](double p) { return kTop + plotHeight * (1.0 - std::clamp(p, 0.0, 1.0)); };
  std::string out = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" font-family=\"sans-serif\" "
      "font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
      kWidth, kHeight);
  out += fmt::format("<text class=\"title\" x=\"{}\" y=\"22\" font-size=\"14\">{}</text>\n", kLeft, svgEscaped(title));
  // Grid and axes: probability 0 .. 1 by quarters, time in about ten ticks.
  for (int q = 0; q <= 4; ++q) {
    const double p = q / 4.0;
    out += fmt::format("<line class=\"grid\" x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#dddddd\"/>\n", kLeft, y(p),
                       kLeft + plotWidth, y(p));
    out += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"end\">{:.2f}</text>\n", kLeft - 6, y(p) + 4, p);
  }
  const std::size_t step = std::max<std::size_t>(1, (horizon + 9) / 10);
  for (std::size_t t = 0; t <= horizon; t += step) {
    out += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>\n", x(t), kTop + plotHeight + 18, t);
  }
  out += fmt::format("<line class=\"axis\" x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" stroke=\"black\"/>\n", kLeft, kTop,
                     kTop + plotHeight);
  out += fmt::format("<line class=\"axis\" x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"black\"/>\n", kLeft,
                     kTop + plotHeight, kLeft + plotWidth, kTop + plotHeight);
  out += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>\n", kLeft + plotWidth / 2, kHeight - 10, svgEscaped(unit));
  out += fmt::format("<text x=\"16\" y=\"{:.1f}\" text-anchor=\"middle\" transform=\"rotate(-90 16 {:.1f})\">probability</text>\n",
                     kTop + plotHeight / 2, kTop + plotHeight / 2);
  // One line per series (a dashed one for a minimum over schedulers), and its legend entry.
  for (std::size_t i = 0; i < series.size(); ++i) {
    const ChartSeries& s = series[i];
    const char* colour = kColours[i % std::size(kColours)];
    std::string points;
    for (std::size_t t = 0; t < s.values.size(); ++t) points += fmt::format("{}{:.1f},{:.1f}", t == 0 ? "" : " ", x(t), y(s.values[t]));
    out += fmt::format("<polyline class=\"series\" fill=\"none\" stroke=\"{}\" stroke-width=\"2\"{} points=\"{}\"><title>{}</title></polyline>\n",
                       colour, s.dashed ? " stroke-dasharray=\"6 4\"" : "", points, svgEscaped(s.name));
    const double ly = kTop + 10 + 18.0 * static_cast<double>(i);
    out += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" stroke=\"{3}\" stroke-width=\"2\"{4}/>\n",
                       kWidth - kRight + 12, ly, kWidth - kRight + 36, colour, s.dashed ? " stroke-dasharray=\"6 4\"" : "");
    out += fmt::format("<text class=\"legend\" x=\"{:.1f}\" y=\"{:.1f}\">{}</text>\n", kWidth - kRight + 42, ly + 4, svgEscaped(s.name));
  }
  return out + "</svg>\n";
}

}  // namespace semo::cli

#pragma once
// A chart of probabilities against steps or rounds, as SVG: one line per series, a legend, the
// axes from 0 to 1 and from 0 to the horizon. The same numbers give the same bytes.
#include <string>
#include <vector>

namespace semo::cli {

struct ChartSeries {
  std::string name;
  std::vector<double> values;  // at t = 0, 1, ...
  bool dashed = false;         // a minimum over schedulers, drawn under its maximum
};

std::string probabilityChartSvg(const std::vector<ChartSeries>& series, const std::string& title, const std::string& unit);

}  // namespace semo::cli

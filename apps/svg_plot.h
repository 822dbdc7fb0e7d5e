// Line charts written as SVG by the benchmark programs themselves: one or more panels side by side,
// each with log or linear axes, labelled ticks, and one polyline with markers per series.
#pragma once

#include <string>
#include <vector>

namespace mfx::app {

struct PlotSeries {
    std::string label;
    std::string colour; // any SVG colour, e.g. "#d62728"
    std::vector<double> x, y;
};

struct PlotPanel {
    std::string title;
    std::string xLabel, yLabel;
    bool logX = false, logY = false;
    std::vector<PlotSeries> series;
};

// The SVG text of `panels` side by side under `title`.
std::string svgPlot(const std::string& title, const std::vector<PlotPanel>& panels);

} // namespace mfx::app

#include "apps/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace mfx::app {

namespace {

constexpr double kPanelWidth = 420, kPanelHeight = 320;
constexpr double kLeft = 70, kRight = 20, kTop = 50, kBottom = 55;

std::string number(double v) {
    char text[32];
    if (v != 0.0 && (std::abs(v) >= 1e5 || std::abs(v) < 1e-2))
        std::snprintf(text, sizeof text, "%.0e", v);
    else
        std::snprintf(text, sizeof text, "%g", v);
    return text;
}

std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else if (c == '&')
            out += "&amp;";
        else
            out += c;
    }
    return out;
}

struct Axis {
    bool log = false;
    double low = 0, high = 1;
    double map(double v, double from, double to) const {
        const double a = log ? std::log10(low) : low, b = log ? std::log10(high) : high;
        const double t = ((log ? std::log10(v) : v) - a) / (b - a);
        return from + t * (to - from);
    }
    std::vector<double> ticks() const {
        std::vector<double> out;
        if (log) {
            for (double d = std::pow(10.0, std::floor(std::log10(low))); d <= high * 1.0001;
                 d *= 10)
                if (d >= low * 0.9999) out.push_back(d);
            if (out.size() < 2) out = {low, high};
        } else {
            const double span = high - low;
            const double step = std::pow(10.0, std::floor(std::log10(span / 4)));
            const double nice = span / step > 20 ? step * 5 : span / step > 8 ? step * 2 : step;
            for (double v = std::ceil(low / nice) * nice; v <= high + 1e-9 * span; v += nice)
                out.push_back(v);
        }
        return out;
    }
};

Axis fit(const std::vector<PlotSeries>& series, bool x, bool log) {
    double low = std::numeric_limits<double>::max(), high = std::numeric_limits<double>::lowest();
    for (const PlotSeries& s : series)
        for (double v : x ? s.x : s.y)
            if (std::isfinite(v) && (!log || v > 0)) {
                low = std::min(low, v);
                high = std::max(high, v);
            }
    if (low > high) return {log, 1, 10};
    if (log) {
        low = std::pow(10.0, std::floor(std::log10(low)));
        high = std::pow(10.0, std::ceil(std::log10(high)));
        if (low == high) high *= 10;
    } else {
        if (!x) low = std::min(low, 0.0);
        if (low == high) high = low + 1;
        high += 0.05 * (high - low);
    }
    return {log, low, high};
}

} // namespace

std::string svgPlot(const std::string& title, const std::vector<PlotPanel>& panels) {
    const double width = kPanelWidth * double(std::max<size_t>(panels.size(), 1));
    const double height = kPanelHeight + 30;
    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
        << "\" font-family=\"sans-serif\" font-size=\"11\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
        << "<text x=\"" << width / 2 << "\" y=\"20\" text-anchor=\"middle\" font-size=\"14\">"
        << escape(title) << "</text>\n";
    for (size_t p = 0; p < panels.size(); ++p) {
        const PlotPanel& panel = panels[p];
        const double x0 = double(p) * kPanelWidth + kLeft,
                     x1 = double(p + 1) * kPanelWidth - kRight;
        const double y0 = 30 + kTop, y1 = 30 + kPanelHeight - kBottom;
        const Axis ax = fit(panel.series, true, panel.logX),
                   ay = fit(panel.series, false, panel.logY);
        svg << "<text x=\"" << (x0 + x1) / 2 << "\" y=\"" << y0 - 12
            << "\" text-anchor=\"middle\" font-size=\"12\">" << escape(panel.title) << "</text>\n";
        svg << "<rect x=\"" << x0 << "\" y=\"" << y0 << "\" width=\"" << x1 - x0 << "\" height=\""
            << y1 - y0 << "\" fill=\"none\" stroke=\"#444\"/>\n";
        for (double t : ax.ticks()) {
            const double x = ax.map(t, x0, x1);
            svg << "<line x1=\"" << x << "\" y1=\"" << y0 << "\" x2=\"" << x << "\" y2=\"" << y1
                << "\" stroke=\"#ddd\"/><text x=\"" << x << "\" y=\"" << y1 + 14
                << "\" text-anchor=\"middle\">" << number(t) << "</text>\n";
        }
        for (double t : ay.ticks()) {
            const double y = ay.map(t, y1, y0);
            svg << "<line x1=\"" << x0 << "\" y1=\"" << y << "\" x2=\"" << x1 << "\" y2=\"" << y
                << "\" stroke=\"#ddd\"/><text x=\"" << x0 - 5 << "\" y=\"" << y + 4
                << "\" text-anchor=\"end\">" << number(t) << "</text>\n";
        }
        svg << "<text x=\"" << (x0 + x1) / 2 << "\" y=\"" << y1 + 32 << "\" text-anchor=\"middle\">"
            << escape(panel.xLabel) << "</text>\n"
            << "<text transform=\"translate(" << x0 - 50 << "," << (y0 + y1) / 2
            << ") rotate(-90)\" text-anchor=\"middle\">" << escape(panel.yLabel) << "</text>\n";
        for (size_t s = 0; s < panel.series.size(); ++s) {
            const PlotSeries& series = panel.series[s];
            std::ostringstream points;
            for (size_t i = 0; i < series.x.size() && i < series.y.size(); ++i) {
                if (!std::isfinite(series.x[i]) || !std::isfinite(series.y[i])) continue;
                if ((panel.logX && series.x[i] <= 0) || (panel.logY && series.y[i] <= 0)) continue;
                const double x = ax.map(series.x[i], x0, x1), y = ay.map(series.y[i], y1, y0);
                points << x << "," << y << " ";
                svg << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"3\" fill=\""
                    << series.colour << "\"/>\n";
            }
            svg << "<polyline fill=\"none\" stroke-width=\"2\" stroke=\"" << series.colour
                << "\" points=\"" << points.str() << "\"/>\n";
            const double ly = y0 + 14 + 16 * double(s);
            svg << "<line x1=\"" << x0 + 10 << "\" y1=\"" << ly - 4 << "\" x2=\"" << x0 + 30
                << "\" y2=\"" << ly - 4 << "\" stroke=\"" << series.colour
                << "\" stroke-width=\"2\"/><text x=\"" << x0 + 35 << "\" y=\"" << ly << "\">"
                << escape(series.label) << "</text>\n";
        }
    }
    svg << "</svg>\n";
    return svg.str();
}

} // namespace mfx::app

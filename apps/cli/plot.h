// nephele CLI — a small, dependency-free line-chart plotter for the benchmark's charts.
//
// Renders straight into an 8-bit sRGB RGBA buffer (no tone mapping): white background, a
// framed plot area with light grid lines, ~5-8 nicely rounded ticks per axis, title, axis
// labels, one antialiased line with point markers per series (distinct colour and marker
// shape each), and a legend placed in the corner of the plot that covers the least data.
// Text uses stb_easy_font scaled by 2 (ASCII only; other characters are drawn as '?').
#pragma once

#include <string>
#include <vector>

namespace nephele::cli {

// One line with point markers. Points are joined in the order given; x and y must have the
// same length. A point with a non-finite coordinate (or y <= 0 on a log axis, x <= 0 on a
// log x axis) is not drawn and breaks the line there.
struct PlotSeries {
  std::string label;  // legend entry; a series with an empty label gets none
  std::vector<double> x, y;
};

struct PlotSpec {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
  bool log_y = false;             // logarithmic y axis (values must be > 0)
  bool log_x = false;             // logarithmic x axis (values must be > 0)
  int width = 900, height = 600;  // pixels, each in [64, 8192]
};

// Renders the chart into an RGBA8 buffer, row-major, row 0 at the top, alpha 255:
// width * height * 4 bytes. Empty series, a single point and all-equal values are fine.
// Throws InputError for a size out of range or a series whose x and y differ in length.
std::vector<unsigned char> render_plot(const PlotSpec& spec);

// render_plot, then writes a PNG (via a temporary file beside `path`, renamed over it, so a
// failure leaves nothing behind). Throws RuntimeError naming the path on I/O failure,
// InputError as render_plot does.
void write_plot_png(const PlotSpec& spec, const std::string& path);

// Several charts in one PNG: a grid with `columns` columns (clamped to the number of charts),
// filled row by row; each cell is as large as the largest chart, a smaller chart is centred
// in its cell. Throws InputError for no charts, columns < 1 or a grid over 16384 pixels a
// side; RuntimeError on I/O failure.
void write_plot_grid_png(const std::vector<PlotSpec>& specs, int columns, const std::string& path);

}  // namespace nephele::cli

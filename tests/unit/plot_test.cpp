// Tests of the benchmark's line-chart plotter (apps/cli/plot.h).
#include "plot.h"

#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "nephele/error.h"

namespace nephele::cli {
namespace {

namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Rgb {
  int r, g, b;
};

// The plotter's first three series colours (Tableau 10).
constexpr Rgb kBlue{31, 119, 180};
constexpr Rgb kOrange{255, 127, 14};
constexpr Rgb kGreen{44, 160, 44};

Rgb pixel(const std::vector<unsigned char>& rgba, int width, int x, int y) {
  const size_t i = (size_t(y) * size_t(width) + size_t(x)) * 4;
  return {rgba[i], rgba[i + 1], rgba[i + 2]};
}

bool near(Rgb a, Rgb b, int tolerance = 2) {
  return std::abs(a.r - b.r) <= tolerance && std::abs(a.g - b.g) <= tolerance &&
         std::abs(a.b - b.b) <= tolerance;
}

struct Centroid {
  double x, y;
  int count;
};

// Centroid of the pixels of (nearly) exactly `colour`, if there are any.
std::optional<Centroid> centroid(const std::vector<unsigned char>& rgba, int width, int height,
                                 Rgb colour) {
  double sx = 0.0, sy = 0.0;
  int n = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (near(pixel(rgba, width, x, y), colour)) {
        sx += x;
        sy += y;
        ++n;
      }
    }
  }
  if (n == 0) return std::nullopt;
  return Centroid{sx / n, sy / n, n};
}

int count_colour(const std::vector<unsigned char>& rgba, int width, int height, Rgb colour) {
  const auto c = centroid(rgba, width, height, colour);
  return c ? c->count : 0;
}

// A chart of single, unlabelled points (no legend), one series each: blue, orange, green.
PlotSpec three_points(double y0, double y1, double y2, bool log_y) {
  PlotSpec spec;
  spec.title = "three points";
  spec.x_label = "x";
  spec.y_label = "y";
  spec.log_y = log_y;
  spec.series = {{"", {0.0}, {y0}}, {"", {1.0}, {y1}}, {"", {2.0}, {y2}}};
  return spec;
}

TEST(Plot, BufferIsWidthTimesHeightRgbaOpaque) {
  PlotSpec spec;
  spec.width = 321;
  spec.height = 234;
  spec.series = {{"a", {1, 2, 3}, {3, 1, 2}}};
  const std::vector<unsigned char> rgba = render_plot(spec);
  ASSERT_EQ(rgba.size(), size_t(321) * 234 * 4);
  for (size_t i = 3; i < rgba.size(); i += 4) ASSERT_EQ(rgba[i], 255) << "pixel " << i / 4;
}

TEST(Plot, BackgroundIsWhiteInTheCorners) {
  PlotSpec spec;
  spec.title = "fps vs density";
  spec.series = {{"gpu", {0.5, 1.0, 2.0}, {120, 80, 41}}};
  const std::vector<unsigned char> rgba = render_plot(spec);
  const int w = spec.width, h = spec.height;
  for (auto [x, y] : {std::pair{1, 1}, {w - 2, 1}, {1, h - 2}, {w - 2, h - 2}}) {
    EXPECT_TRUE(near(pixel(rgba, w, x, y), {255, 255, 255}, 0)) << x << ", " << y;
  }
}

TEST(Plot, PointsAreDrawnWhereTheirValuesSay) {
  // Low y on the left, high y on the right: blue sits left and low, green right and high.
  const PlotSpec spec = three_points(0.0, 5.0, 10.0, false);
  const std::vector<unsigned char> rgba = render_plot(spec);
  const auto blue = centroid(rgba, spec.width, spec.height, kBlue);
  const auto orange = centroid(rgba, spec.width, spec.height, kOrange);
  const auto green = centroid(rgba, spec.width, spec.height, kGreen);
  ASSERT_TRUE(blue && orange && green);
  EXPECT_LT(blue->x, spec.width / 3.0);
  EXPECT_GT(blue->y, spec.height / 2.0);
  EXPECT_GT(green->x, spec.width * 2.0 / 3.0);
  EXPECT_LT(green->y, spec.height / 2.0);
  // Linear axes: the middle point lies halfway between the others.
  EXPECT_NEAR(orange->x, 0.5 * (blue->x + green->x), 1.5);
  EXPECT_NEAR(orange->y, 0.5 * (blue->y + green->y), 1.5);
  // A marker is a few pixels across, not a speck and not a blob.
  EXPECT_GE(blue->count, 20);
  EXPECT_LE(blue->count, 150);
}

TEST(Plot, LogAxisSpacesDecadesEvenly) {
  // 1, 10, 100 on a log axis: the middle is halfway; on a linear axis it is near the bottom.
  PlotSpec spec = three_points(1.0, 10.0, 100.0, true);
  std::vector<unsigned char> rgba = render_plot(spec);
  auto blue = centroid(rgba, spec.width, spec.height, kBlue);
  auto orange = centroid(rgba, spec.width, spec.height, kOrange);
  auto green = centroid(rgba, spec.width, spec.height, kGreen);
  ASSERT_TRUE(blue && orange && green);
  EXPECT_NEAR(orange->y, 0.5 * (blue->y + green->y), 1.5);

  spec.log_y = false;
  rgba = render_plot(spec);
  blue = centroid(rgba, spec.width, spec.height, kBlue);
  orange = centroid(rgba, spec.width, spec.height, kOrange);
  green = centroid(rgba, spec.width, spec.height, kGreen);
  ASSERT_TRUE(blue && orange && green);
  EXPECT_GT(orange->y, blue->y - 0.2 * (blue->y - green->y));
}

TEST(Plot, LineIsDrawnBetweenPoints) {
  PlotSpec spec;
  spec.series = {{"", {0.0, 10.0}, {0.0, 10.0}}};
  const std::vector<unsigned char> rgba = render_plot(spec);
  const auto blue = centroid(rgba, spec.width, spec.height, kBlue);
  ASSERT_TRUE(blue);
  // A diagonal across the plot: far more pixels than two markers, centred in the middle.
  EXPECT_GT(blue->count, 600);
  // Walk across: at each column in the middle third there is a run of at least 2 px of the
  // line colour or of its antialiased edge.
  int columns_with_line = 0;
  for (int x = spec.width / 3; x < 2 * spec.width / 3; ++x) {
    int strong = 0;
    for (int y = 0; y < spec.height; ++y) {
      const Rgb p = pixel(rgba, spec.width, x, y);
      if (p.b > p.r + 60) ++strong;  // bluish: the line, not grey grid or text
    }
    if (strong >= 2) ++columns_with_line;
  }
  EXPECT_EQ(columns_with_line, spec.width / 3);
}

TEST(Plot, SeriesGetDistinctColours) {
  PlotSpec spec;
  spec.series = {
      {"a", {0, 1, 2}, {1, 2, 3}}, {"b", {0, 1, 2}, {3, 2, 1}}, {"c", {0, 1, 2}, {2, 2.5, 2}}};
  const std::vector<unsigned char> rgba = render_plot(spec);
  EXPECT_GT(count_colour(rgba, spec.width, spec.height, kBlue), 100);
  EXPECT_GT(count_colour(rgba, spec.width, spec.height, kOrange), 100);
  EXPECT_GT(count_colour(rgba, spec.width, spec.height, kGreen), 100);
}

TEST(Plot, TextIsDrawn) {
  PlotSpec plain;
  plain.series = {{"", {0, 1}, {0, 1}}};
  PlotSpec titled = plain;
  titled.title = "FPS VS COVERAGE";
  const std::vector<unsigned char> a = render_plot(plain), b = render_plot(titled);
  // The title adds dark pixels in the top band, above where the frame of an untitled chart is.
  auto dark_on_top = [&](const std::vector<unsigned char>& rgba) {
    int n = 0;
    for (int y = 0; y < 20; ++y) {
      for (int x = 0; x < plain.width; ++x) n += pixel(rgba, plain.width, x, y).r < 100;
    }
    return n;
  };
  EXPECT_EQ(dark_on_top(a), 0);
  EXPECT_GT(dark_on_top(b), 100);
}

TEST(Plot, DegenerateInputsRender) {
  std::vector<PlotSpec> specs(10);
  specs[0].series = {};                                              // no series at all
  specs[1].series = {{"empty", {}, {}}};                             // an empty series
  specs[2].series = {{"one", {3.0}, {7.0}}};                         // a single point
  specs[3].series = {{"flat", {1, 2, 3}, {5, 5, 5}}};                // all-equal y
  specs[4].series = {{"zeros", {0, 0, 0}, {0, 0, 0}}};               // one point, three times
  specs[5].series = {{"bad", {kNaN, 1, 2, kInf}, {1, kNaN, 2, 3}}};  // non-finite values
  specs[6].log_y = true;                                             // <= 0 on a log axis
  specs[6].series = {{"log", {1, 2, 3, 4}, {0.0, -1.0, 5.0, 50.0}}};
  specs[7].log_y = true;
  specs[7].series = {{"all bad", {1, 2}, {0.0, -3.0}}};
  specs[8].title = "\x01\t\xff caf\xc3\xa9 \xce\xbcs \xe2\x80\x94 \xf0\x9f\x98\x80";  // not ASCII
  specs[8].x_label = std::string(400, 'x');  // wider than the chart
  specs[8].series = {{"huge", {-1.7e308, 1.7e308}, {1e-320, 1.7e308}}};
  specs[9].log_y = true;
  specs[9].series = {{"tiny", {1, 2}, {5e-324, 1e-310}}};  // subnormal
  for (size_t i = 0; i < specs.size(); ++i) {
    std::vector<unsigned char> rgba;
    ASSERT_NO_THROW(rgba = render_plot(specs[i])) << "spec " << i;
    EXPECT_EQ(rgba.size(), size_t(specs[i].width) * specs[i].height * 4) << "spec " << i;
  }
  // The single point and the flat line are visible.
  for (int i : {2, 3, 4}) {
    const std::vector<unsigned char> rgba = render_plot(specs[size_t(i)]);
    EXPECT_GT(count_colour(rgba, specs[size_t(i)].width, specs[size_t(i)].height, kBlue), 20)
        << "spec " << i;
  }
}

TEST(Plot, RejectsInvalidSpecs) {
  PlotSpec mismatched;
  mismatched.series = {{"s", {1, 2, 3}, {1, 2}}};
  EXPECT_THROW(render_plot(mismatched), InputError);
  for (auto [w, h] : {std::pair{0, 600}, {900, -1}, {10, 10}, {100000, 600}}) {
    PlotSpec spec;
    spec.width = w;
    spec.height = h;
    EXPECT_THROW(render_plot(spec), InputError) << w << "x" << h;
  }
}

// --- files ----------------------------------------------------------------------------------

class PlotFiles : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("nephele-plot-test-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  size_t entries() const {
    size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++n;
    return n;
  }

  struct Png {
    int width = 0, height = 0;
    std::vector<unsigned char> rgba;
  };
  static Png read_png(const std::string& file) {
    Png png;
    int channels = 0;
    std::unique_ptr<unsigned char, void (*)(void*)> data(
        stbi_load(file.c_str(), &png.width, &png.height, &channels, 4), stbi_image_free);
    if (data) png.rgba.assign(data.get(), data.get() + size_t(png.width) * png.height * 4);
    return png;
  }

  fs::path dir_;
};

PlotSpec sample(const std::string& title, int width, int height) {
  PlotSpec spec;
  spec.title = title;
  spec.x_label = "coverage";
  spec.y_label = "fps";
  spec.width = width;
  spec.height = height;
  spec.series = {{"gpu", {0.1, 0.5, 0.9}, {90, 70, 55}}, {"cpu", {0.1, 0.5, 0.9}, {9, 7, 5.5}}};
  return spec;
}

TEST_F(PlotFiles, PngHoldsTheRenderedBytes) {
  const PlotSpec spec = sample("fps vs coverage", 400, 300);
  write_plot_png(spec, path("chart.png"));
  const Png png = read_png(path("chart.png"));
  ASSERT_EQ(png.width, 400);
  ASSERT_EQ(png.height, 300);
  EXPECT_EQ(png.rgba, render_plot(spec));
  EXPECT_EQ(entries(), 1u);  // no temporary file left
}

TEST_F(PlotFiles, UnwritablePathThrowsRuntimeErrorAndLeavesNothing) {
  const PlotSpec spec = sample("x", 200, 150);
  EXPECT_THROW(write_plot_png(spec, path("missing-dir/chart.png")), RuntimeError);
  fs::create_directories(path("a-directory"));
  EXPECT_THROW(write_plot_png(spec, path("a-directory")), RuntimeError);
  EXPECT_EQ(entries(), 1u);  // just the directory made above
}

TEST_F(PlotFiles, GridPlacesChartsInColumns) {
  const std::vector<PlotSpec> specs = {sample("fps vs density", 300, 200),
                                       sample("fps vs coverage", 300, 200),
                                       sample("fps vs resolution", 300, 200)};
  write_plot_grid_png(specs, 2, path("grid.png"));
  const Png png = read_png(path("grid.png"));
  ASSERT_EQ(png.width, 600);
  ASSERT_EQ(png.height, 400);
  // Each cell holds its chart exactly; the empty fourth cell is white.
  for (size_t i = 0; i < specs.size(); ++i) {
    const std::vector<unsigned char> chart = render_plot(specs[i]);
    const int ox = int(i % 2) * 300, oy = int(i / 2) * 200;
    bool same = true;
    for (int y = 0; y < 200 && same; ++y) {
      for (int x = 0; x < 300 && same; ++x) {
        const Rgb a = pixel(png.rgba, 600, ox + x, oy + y), b = pixel(chart, 300, x, y);
        same = a.r == b.r && a.g == b.g && a.b == b.b;
      }
    }
    EXPECT_TRUE(same) << "chart " << i;
  }
  EXPECT_TRUE(near(pixel(png.rgba, 600, 450, 300), {255, 255, 255}, 0));
  // More columns than charts: one row.
  write_plot_grid_png(specs, 8, path("row.png"));
  const Png row = read_png(path("row.png"));
  EXPECT_EQ(row.width, 900);
  EXPECT_EQ(row.height, 200);
}

TEST_F(PlotFiles, GridRejectsBadArguments) {
  EXPECT_THROW(write_plot_grid_png({}, 2, path("grid.png")), InputError);
  EXPECT_THROW(write_plot_grid_png({sample("a", 300, 200)}, 0, path("grid.png")), InputError);
  EXPECT_EQ(entries(), 0u);
}

}  // namespace
}  // namespace nephele::cli

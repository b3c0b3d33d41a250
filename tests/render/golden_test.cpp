// Golden-image regression (Filament renderdiff style): each tests/golden/<case>.toml is rendered
// and its tone-mapped PNG compared with <case>.png under the tolerances in <case>.json (maximum
// per-pixel difference, maximum fraction of pixels over a threshold). A failing case writes the
// image, the reference and a difference image to build/test-output/golden/.
// NEPHELE_UPDATE_GOLDEN=1 rewrites the references instead (look at them before committing).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "nephele/exposure.h"
#include "nephele/image_compare.h"
#include "nephele/scene_io.h"
#include "render_fixture.h"

namespace fs = std::filesystem;

namespace {

const fs::path kGoldenDir = fs::path(NEPHELE_SOURCE_DIR) / "tests" / "golden";

std::vector<std::string> golden_cases() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kGoldenDir))
    if (entry.path().extension() == ".toml") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

class GoldenTest : public RenderTest, public ::testing::WithParamInterface<std::string> {};

}  // namespace

TEST_P(GoldenTest, MatchesReference) {
  const std::string name = GetParam();
  const nephele::Scene scene = nephele::load_scene_file((kGoldenDir / (name + ".toml")).string());
  const nephele::Frame frame = render(scene);
  const fs::path out_dir = fs::path(NEPHELE_TEST_OUTPUT_DIR) / "golden";
  fs::create_directories(out_dir);
  const fs::path actual_png = out_dir / (name + ".png");
  nephele::write_image(frame.color, actual_png.string(),
                       nephele::still_exposure(scene.output, frame.color));

  const fs::path reference_png = kGoldenDir / (name + ".png");
  const char* update = std::getenv("NEPHELE_UPDATE_GOLDEN");
  if (update && std::string(update) == "1") {
    fs::copy_file(actual_png, reference_png, fs::copy_options::overwrite_existing);
    GTEST_SKIP() << "reference rewritten: " << reference_png;
  }
  ASSERT_TRUE(fs::exists(reference_png)) << "no reference " << reference_png
                                         << " (NEPHELE_UPDATE_GOLDEN=1 writes it)";
  const nephele::CompareResult result = nephele::compare_images(
      nephele::read_image(actual_png.string()), nephele::read_image(reference_png.string()),
      nephele::load_tolerance_json((kGoldenDir / (name + ".json")).string()));
  if (!result.pass) {
    fs::copy_file(reference_png, out_dir / (name + ".reference.png"),
                  fs::copy_options::overwrite_existing);
    nephele::write_image(result.diff, (out_dir / (name + ".diff.png")).string(), 1.0f);
  } else {
    fs::remove(actual_png);
  }
  EXPECT_TRUE(result.pass) << name << ": " << result.summary << " (images in " << out_dir << ")";
}

INSTANTIATE_TEST_SUITE_P(Cases, GoldenTest, ::testing::ValuesIn(golden_cases()),
                         [](const auto& info) {
                           std::string n = info.param;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

// The scene reference and the field table it comes from: each key's range is declared once and
// validation, the CLI's help and docs/scene-reference.md all follow it.
#include "scene_reference.h"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <fstream>
#include <sstream>

#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "scene_flags.h"

namespace nephele {
namespace {

std::string validation_error(const Scene& scene) {
  try {
    validate_scene(scene);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A TOML literal of the parameter's kind holding `value` (every component of a vector).
std::string literal(const SceneParameter& p, double value) {
  std::ostringstream text;
  text.precision(17);
  if (p.kind == SceneValueKind::kInt) {
    text << static_cast<long long>(value);
    return text.str();
  }
  text << std::showpoint << value;
  if (p.kind == SceneValueKind::kFloat) return text.str();
  const std::string one = text.str();
  return p.kind == SceneValueKind::kVec2 ? "[" + one + ", " + one + "]"
                                         : "[" + one + ", " + one + ", " + one + "]";
}

TEST(SceneReference, DocsPageIsUpToDate) {
  std::ifstream in(std::string(NEPHELE_SOURCE_DIR) + "/docs/scene-reference.md");
  ASSERT_TRUE(in)
      << "docs/scene-reference.md is missing: run ./build/nephele keys > docs/scene-reference.md";
  std::stringstream page;
  page << in.rdbuf();
  const std::string expected = cli::scene_reference_markdown();
  if (page.str() == expected) return;
  // Name the first line that differs.
  std::istringstream a(page.str()), b(expected);
  std::string line_a, line_b;
  int line = 1;
  while (std::getline(a, line_a) && std::getline(b, line_b) && line_a == line_b) ++line;
  FAIL() << "docs/scene-reference.md is out of date (line " << line << ": '" << line_a
         << "', the table gives '" << line_b
         << "'): run ./build/nephele keys > docs/scene-reference.md";
}

TEST(SceneReference, EveryKeyIsListedWithItsDefault) {
  const std::string page = cli::scene_reference_markdown();
  const Scene defaults{};
  for (const SceneParameter& p : scene_parameters()) {
    if (p.key.starts_with("conditions.bad.") ||
        (p.key.starts_with("conditions.good.") && !p.key.starts_with("conditions.good.night.")))
      continue;  // the keyframes' keys are listed once
    const std::string name =
        p.key.substr(p.key.rfind('.') == std::string::npos ? 0 : p.key.rfind('.') + 1);
    EXPECT_NE(page.find("| `" + name + "` | " + p.unit + " |"), std::string::npos) << p.key;
    EXPECT_EQ(p.default_value, get_scene_value(defaults, p.key)) << p.key;
  }
  // Units come from the names' suffixes.
  const auto unit = [](const char* key) {
    for (const SceneParameter& p : scene_parameters())
      if (p.key == key) return p.unit;
    return std::string("?");
  };
  EXPECT_EQ(unit("clouds.bottom_altitude_m"), "m");
  EXPECT_EQ(unit("clouds.wind_mps"), "m/s");
  EXPECT_EQ(unit("camera.fov_deg"), "deg");
  EXPECT_EQ(unit("atmosphere.mie_scattering_per_m"), "1/m");
  EXPECT_EQ(unit("output.adaptation_ev_per_s"), "EV/s");
  EXPECT_EQ(unit("clouds.coverage"), "");
}

// Each declared range is what validation enforces: a value past either end (or on an open end)
// is refused with the range in the message, and the "off" value is accepted.
TEST(SceneReference, EveryDeclaredRangeIsEnforced) {
  const Scene base{};
  ASSERT_EQ(validation_error(base), "");
  int checked = 0;
  for (const SceneParameter& p : scene_parameters()) {
    if (std::isnan(p.min)) continue;
    ++checked;
    const std::string interval = p.allowed_values.substr(p.allowed_values.find_first_of("[("));
    const std::string bounds = interval.substr(0, interval.find_first_of(")]") + 1);
    const double span = std::max(1.0, p.max - p.min);
    for (double bad : {p.max + span, p.min - span}) {
      Scene scene = base;
      set_scene_value(scene, p.key, literal(p, bad));
      const std::string error = validation_error(scene);
      EXPECT_NE(error.find(p.key), std::string::npos) << p.key << " = " << bad << ": " << error;
      EXPECT_NE(error.find(bounds), std::string::npos) << p.key << " = " << bad << ": " << error;
    }
    for (auto [open, end] : {std::pair{p.min_open, p.min}, std::pair{p.max_open, p.max}}) {
      if (!open) continue;
      Scene scene = base;
      set_scene_value(scene, p.key, literal(p, end));
      EXPECT_NE(validation_error(scene).find(p.key), std::string::npos) << p.key << " = " << end;
    }
    if (p.off) {
      Scene scene = base;
      set_scene_value(scene, p.key, literal(p, *p.off));
      const std::string error = validation_error(scene);
      EXPECT_EQ(error.find(p.key + " ="), std::string::npos)
          << p.key << " = " << *p.off << ": " << error;
    }
  }
  EXPECT_GT(checked, 140);
}

TEST(SceneReference, ChoicesAreEnforcedAndListed) {
  Scene scene{};
  scene.quality.light_shafts = "beams";
  EXPECT_EQ(validation_error(scene),
            "quality.light_shafts = \"beams\": must be \"volumetric\", \"screen\" or \"off\"");
  scene = Scene{};
  scene.terrain.method = "splat";
  EXPECT_EQ(validation_error(scene),
            "terrain.method = \"splat\": must be \"raycast\" or \"raster\"");
  scene = Scene{};
  scene.particle_clouds.atlas_tile = 24;
  EXPECT_EQ(validation_error(scene), "particle_clouds.atlas_tile = 24: must be 16 or 32");
}

TEST(SceneReference, FlagHelpGivesTheDeclaredRange) {
  CLI::App app;
  cli::SceneFlags flags;
  cli::add_scene_flags(app, flags);
  const std::string help = app.help();
  EXPECT_NE(help.find("cloud coverage; allowed: [0, 1]"), std::string::npos) << help;
  EXPECT_NE(help.find("forward phase lobe asymmetry; allowed: [0, 1)"), std::string::npos);
  EXPECT_NE(help.find("0 or [1, 1e+07]"), std::string::npos);  // --weather-evolution-s
}

}  // namespace
}  // namespace nephele

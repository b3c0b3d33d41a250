// nephele-view's logic without a window: scripts, the scene editor, the panel's groups and
// value texts, dynamic resolution, the camera and its place on the planet, recording and flying
// camera paths.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <limits>
#include <numbers>
#include <set>

#include "camera_control.h"
#include "dynamic_resolution.h"
#include "nephele/camera_path.h"
#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "path_control.h"
#include "scene_editor.h"
#include "script.h"

namespace nephele::view {
namespace {

std::string input_error(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

TEST(ViewerScript, ReadsCommandsInFrameOrder) {
  const Script s = parse_script(
      "# a comment\n"
      "\n"
      "frame 40 screenshot out.png\n"
      "frame 10 set clouds.coverage 0.9\n"
      "  frame 10   set camera.position_m [1, 2, 3]  \n"
      "frame 12 preset overcast\n"
      "frame 13 window-screenshot win.png\n"
      "frame 50 quit\n"
      "frame 45 resize 640x400\n",
      "s.txt");
  ASSERT_EQ(s.commands.size(), 7u);
  EXPECT_EQ(s.commands[5].action, ScriptAction::kResize);
  EXPECT_EQ(s.commands[5].width, 640);
  EXPECT_EQ(s.commands[5].height, 400);
  EXPECT_EQ(s.commands[0].frame, 10);
  EXPECT_EQ(s.commands[0].line, 4);
  EXPECT_EQ(s.commands[0].action, ScriptAction::kSet);
  EXPECT_EQ(s.commands[0].key, "clouds.coverage");
  EXPECT_EQ(s.commands[0].argument, "0.9");
  EXPECT_EQ(s.commands[1].key, "camera.position_m");
  EXPECT_EQ(s.commands[1].argument, "[1, 2, 3]");
  EXPECT_EQ(s.commands[2].action, ScriptAction::kPreset);
  EXPECT_EQ(s.commands[2].argument, "overcast");
  EXPECT_EQ(s.commands[3].action, ScriptAction::kWindowScreenshot);
  EXPECT_EQ(s.commands[4].action, ScriptAction::kScreenshot);
  EXPECT_EQ(s.commands[4].argument, "out.png");
  EXPECT_EQ(s.commands[6].action, ScriptAction::kQuit);
}

TEST(ViewerScript, BadLinesAreOneLineWithTheLineNumber) {
  const auto error = [](const std::string& text) {
    return input_error([&] { parse_script(text, "s.txt"); });
  };
  EXPECT_EQ(error("set clouds.coverage 1\n"),
            "s.txt:1: 'set clouds.coverage 1': expected 'frame N COMMAND ...'");
  EXPECT_EQ(error("\nframe -1 quit\n"), "s.txt:2: frame '-1': expected an integer in [0, 16000000]");
  EXPECT_EQ(error("frame 1x quit\n"), "s.txt:1: frame '1x': expected an integer in [0, 16000000]");
  EXPECT_EQ(error("frame 1\n"),
            "s.txt:1: unknown command '' (allowed: set, preset, load, camera-path, record-start, "
            "record-stop, print-camera, screenshot, window-screenshot, resize, quit)");
  EXPECT_EQ(error("frame 1 resize 640\n"), "s.txt:1: resize '640': expected WxH, each in [1, 16384]");
  EXPECT_EQ(error("frame 1 resize 640x0\n"),
            "s.txt:1: resize '640x0': expected WxH, each in [1, 16384]");
  EXPECT_EQ(error("frame 1 set clouds.coverage\n"),
            "s.txt:1: set: expected 'set KEY VALUE', e.g. 'set clouds.coverage 0.9'");
  EXPECT_EQ(error("frame 1 set clouds.cover 1\n").rfind(
                "s.txt:1: set: unknown scene key 'clouds.cover' (allowed in [clouds]:", 0),
            0u);
  EXPECT_EQ(error("frame 1 screenshot out.jpg\n"),
            "s.txt:1: screenshot 'out.jpg': unsupported image format (allowed: .png, .exr)");
  EXPECT_EQ(error("frame 1 window-screenshot out.exr\n"),
            "s.txt:1: window-screenshot 'out.exr': unsupported image format (allowed: .png)");
  EXPECT_EQ(error("frame 1 screenshot\n"), "s.txt:1: screenshot: expected a file name");
  EXPECT_EQ(error("frame 1 quit now\n"), "s.txt:1: quit: takes nothing, got 'now'");
  EXPECT_EQ(error("frame 1 preset fog\n").rfind(
                "s.txt:1: preset 'fog': unknown preset (available: above-clouds, ", 0),
            0u);
  EXPECT_EQ(error("frame 1 camera-path\n"),
            "s.txt:1: camera-path: expected a path file, e.g. 'camera-path flight.toml'");
  EXPECT_EQ(error("frame 1 record-start now\n"), "s.txt:1: record-start: takes nothing, got 'now'");
  EXPECT_EQ(error("frame 1 print-camera x\n"), "s.txt:1: print-camera: takes nothing, got 'x'");
  EXPECT_EQ(error("frame 1 record-stop /no/such/folder/p.toml\n")
                .rfind("s.txt:1: record-stop '/no/such/folder/p.toml': ", 0),
            0u);
}

TEST(ViewerScript, ReadsCameraPathCommands) {
  const Script s = parse_script(
      "frame 30 record-stop flight.toml\n"
      "frame 20 camera-path missing-until-it-runs.toml\n"
      "frame 10 record-start\n"
      "frame 31 record-stop\n"
      "frame 32 print-camera\n",
      "s.txt");
  ASSERT_EQ(s.commands.size(), 5u);
  EXPECT_EQ(s.commands[0].action, ScriptAction::kRecordStart);
  EXPECT_EQ(s.commands[1].action, ScriptAction::kCameraPath);
  EXPECT_EQ(s.commands[1].argument, "missing-until-it-runs.toml");  // read when it runs
  EXPECT_EQ(s.commands[2].action, ScriptAction::kRecordStop);
  EXPECT_EQ(s.commands[2].argument, "flight.toml");
  EXPECT_EQ(s.commands[3].action, ScriptAction::kRecordStop);
  EXPECT_EQ(s.commands[3].argument, "");
  EXPECT_EQ(s.commands[4].action, ScriptAction::kPrintCamera);
}

TEST(ViewerSceneEditor, AcceptsValidEditsAndKeepsTheLastValidScene) {
  SceneEditor editor{Scene{}};
  const long start = editor.revision();
  EXPECT_EQ(editor.set("clouds.coverage", "0.9"), "");
  EXPECT_EQ(editor.scene().clouds.coverage, 0.9f);
  EXPECT_EQ(editor.revision(), start + 1);

  EXPECT_EQ(editor.set("clouds.coverage", "1.5"), "clouds.coverage = 1.5: must be in [0, 1]");
  EXPECT_EQ(editor.error_key(), "clouds.coverage");
  EXPECT_EQ(editor.scene().clouds.coverage, 0.9f);  // still rendering the last valid one
  EXPECT_EQ(editor.revision(), start + 1);

  EXPECT_EQ(editor.set("clouds.density", "\"thick\""),
            "clouds.density = \"thick\": expected a number");
  EXPECT_EQ(editor.set("clouds.cover", "1").rfind("unknown scene key 'clouds.cover'", 0), 0u);

  // A value valid alone is judged with the rest of the scene, as in a file.
  // (the message names the other end: "clouds.bottom_altitude_m = 1500: must be below ...").
  EXPECT_NE(editor.set("clouds.top_altitude_m", "100").find("clouds.top_altitude_m"),
            std::string::npos);
  EXPECT_EQ(editor.error_key(), "clouds.top_altitude_m");
  EXPECT_EQ(editor.scene().clouds.top_altitude_m, 4000.0f);

  EXPECT_EQ(editor.set("clouds.density", "0.25"), "");
  EXPECT_EQ(editor.error(), "");
  EXPECT_EQ(editor.scene().clouds.density, 0.25f);

  Scene bad;
  bad.output.width = 0;
  EXPECT_EQ(editor.replace(bad, "scene.toml"), "scene.toml: output.width = 0: must be in [1, 16384]");
  EXPECT_EQ(editor.error_key(), "");
  EXPECT_EQ(editor.scene().output.width, 900);
  EXPECT_EQ(editor.change([](Scene& s) { s.time_s = 2e6f; }).find("time_s = 2e+06"), 0u);
  EXPECT_EQ(editor.change([](Scene& s) { s.time_s = 5.0f; }), "");
  EXPECT_EQ(editor.scene().time_s, 5.0f);
}

// A report pasted into the panel's weather.metar sets the sky as a scene file's would: its
// groups become layers; a report that cannot be read is one line naming the group, and the
// last valid scene stays.
TEST(ViewerSceneEditor, APastedReportSetsTheSky) {
  SceneEditor editor{Scene{}};
  EXPECT_EQ(
      editor.set("weather.metar", "\"EDDF 271150Z 24015KT 9999 FEW025 SCT040 BKN080 12/06 Q1008\""),
      "");
  const Scene& s = editor.scene();
  EXPECT_EQ(s.clouds.type, 0.75f);       // FEW025 SCT040: cumulus
  ASSERT_EQ(s.cloud_layers.size(), 1u);  // BKN080: altocumulus
  EXPECT_EQ(s.cloud_layers[0].genus, "altocumulus");
  EXPECT_NEAR(s.cloud_layers[0].base_m, 8000 * 0.3048f, 0.5f);
  // The wind from 240 deg: towards the east-north-east.
  EXPECT_NEAR(std::atan2(s.clouds.wind_mps.x, s.clouds.wind_mps.y), glm::radians(60.0f), 1e-3f);
  const long revision = editor.revision();
  const std::string error =
      editor.set("weather.metar", "\"EDDF 271150Z 24015KT 9999 BKN0X0 12/06 Q1008\"");
  EXPECT_NE(error.find("weather.metar"), std::string::npos) << error;
  EXPECT_NE(error.find("BKN0X0"), std::string::npos) << error;
  EXPECT_EQ(editor.revision(), revision);
  EXPECT_EQ(editor.scene().cloud_layers.size(), 1u);
}

TEST(ViewerPanel, EveryParameterIsInExactlyOneGroupInTheFilesOrder) {
  std::multiset<std::string> shown;
  std::vector<std::string> titles;
  for (const ParameterGroup& g : parameter_groups()) {
    titles.push_back(g.title);
    shown.insert(g.keys.begin(), g.keys.end());
  }
  EXPECT_EQ(titles,
            (std::vector<std::string>{"Location and time", "Camera", "Sun and moon",
                                      "Atmosphere and sky model", "Clouds", "High clouds", "Cirrus",
                                      "Weather", "Particle clouds", "Classical cloud models",
                                      "Terrain", "Conditions", "Quality", "Output", "Lab"}));
  EXPECT_EQ(parameter_groups()[7].keys.front(), "weather.metar");
  EXPECT_EQ(shown.size(), scene_parameters().size());
  for (const SceneParameter& p : scene_parameters()) EXPECT_EQ(shown.count(p.key), 1u) << p.key;
  EXPECT_EQ(parameter_groups()[0].keys,
            (std::vector<std::string>{"time", "time_s", "location.lat_deg", "location.lon_deg",
                                      "location.altitude_m"}));
  EXPECT_EQ(parameter_groups()[4].keys.front(), "clouds.model");
  EXPECT_EQ(parameter_groups()[4].keys.back(), "noise_seed");
}

TEST(ViewerPanel, WidgetTextsAreSceneLiterals) {
  EXPECT_EQ(float_literal(0.45f), "0.45");
  EXPECT_EQ(float_literal(1e6f), "1e+06");
  EXPECT_EQ(float_literal(-INFINITY), "-inf");
  const float v[3] = {1.0f, -2.5f, 5.8e-6f};
  EXPECT_EQ(vector_literal(v, 3), "[1, -2.5, 5.8e-06]");
  Scene scene;
  set_scene_value(scene, "atmosphere.rayleigh_scattering_per_m", vector_literal(v, 3));
  EXPECT_EQ(scene.atmosphere.rayleigh_scattering_per_m, glm::vec3(1.0f, -2.5f, 5.8e-6f));
  EXPECT_EQ(parse_numbers("[8.0, 2.0]"), (std::vector<double>{8.0, 2.0}));
  EXPECT_EQ(parse_numbers("1_000.5"), (std::vector<double>{1000.5}));
  EXPECT_TRUE(std::isnan(parse_numbers("nan")[0]));
  const std::string odd = "maps/a \"b\" \\ c\td.png";
  EXPECT_EQ(unquote_string(quote_string(odd)), odd);
  set_scene_value(scene, "clouds.weather_map", quote_string(odd));
  EXPECT_EQ(scene.clouds.weather_map, odd);
  EXPECT_EQ(unquote_string(get_scene_value(scene, "clouds.weather_map")), odd);
  EXPECT_EQ(unquote_string("\"hillaire\""), "hillaire");
}

TEST(ViewerDynamicResolution, StepsDownWhenSlowAtMostOnceASecond) {
  DynamicResolution d;
  d.set_target_ms(33.0);
  double t = 0.0;
  EXPECT_FALSE(d.update(t, 1000.0, false));  // the first frame is ignored
  int changes = 0;
  for (int i = 0; i < 8; ++i) changes += d.update(t += 0.125, 100.0, false);  // 1 s of 100 ms
  EXPECT_EQ(changes, 1);
  // 100 ms against 33: sqrt(0.33) = 0.57 of the size, in steps of 1/8 below it.
  EXPECT_FLOAT_EQ(d.scale(), 0.5f);
  EXPECT_EQ(d.scaled(160), 80);
  for (int i = 0; i < 24; ++i) d.update(t += 0.125, 100.0, false);
  EXPECT_FLOAT_EQ(d.scale(), DynamicResolution::kMinScale);
  EXPECT_EQ(d.scaled(2), 1);  // never 0
}

TEST(ViewerDynamicResolution, StepsUpOneStepWhenThereIsRoomAndHoldsNearTheTarget) {
  DynamicResolution d;
  double t = 0.0;
  d.update(t, 0.0, false);
  for (int i = 0; i < 32; ++i) d.update(t += 0.125, 200.0, false);
  ASSERT_FLOAT_EQ(d.scale(), 0.25f);
  // 10 ms frames at 0.25: 0.375 is predicted at 22.5 ms, under 0.85 x 33 ms.
  for (int i = 0; i < 8; ++i) d.update(t += 0.125, 10.0, false);
  EXPECT_FLOAT_EQ(d.scale(), 0.375f);
  // 30 ms frames: within 10% of the target, and larger would be too slow: it holds.
  for (int i = 0; i < 40; ++i) d.update(t += 0.125, 30.0, false);
  EXPECT_FLOAT_EQ(d.scale(), 0.375f);
}

TEST(ViewerDynamicResolution, StillViewConvergesToFullSizeAfterASecond) {
  DynamicResolution d;
  double t = 0.0;
  d.update(t, 0.0, false);
  for (int i = 0; i < 32; ++i) d.update(t += 0.125, 200.0, false);
  ASSERT_LT(d.scale(), 1.0f);
  for (int i = 0; i < 8; ++i) d.update(t += 0.125, 200.0, true);  // still for 7/8 s
  EXPECT_LT(d.scale(), 1.0f);
  d.update(t += 0.125, 200.0, true);
  EXPECT_FLOAT_EQ(d.scale(), 1.0f);
  d.set_enabled(false);
  EXPECT_FALSE(d.update(t += 5.0, 1000.0, false));
  EXPECT_FLOAT_EQ(d.scale(), 1.0f);
}

TEST(ViewerCamera, TakesAndGivesTheScenesPose) {
  CameraParams camera;
  camera.position_m = {10.0f, 20.0f, 300.0f};
  camera.view_dir = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f));
  CameraControl c;
  c.sync_from(camera);
  EXPECT_NEAR(c.yaw_deg(), 45.0f, 1e-4f);
  EXPECT_NEAR(c.pitch_deg(), 0.0f, 1e-4f);
  CameraParams out;
  c.apply_to(out);
  EXPECT_EQ(out.position_m, camera.position_m);
  EXPECT_NEAR(glm::length(out.view_dir - camera.view_dir), 0.0f, 1e-6f);
}

TEST(ViewerCamera, FliesAtItsSpeedAndLooksWithTheMouse) {
  CameraControl c;
  CameraParams camera;
  camera.position_m = {0.0f, 0.0f, 100.0f};
  camera.view_dir = {0.0f, 1.0f, 0.0f};
  c.sync_from(camera);
  c.set_speed_mps(20.0f);
  c.update(CameraInput{.forward = 1.0f}, 0.5f);  // north at 20 m/s for 0.5 s
  EXPECT_NEAR(c.position_m().y, 10.0f, 1e-4f);
  c.update(CameraInput{.right = 1.0f, .up = -1.0f}, 0.25f);  // east and down
  EXPECT_NEAR(c.position_m().x, 5.0f, 1e-4f);
  EXPECT_NEAR(c.position_m().z, 95.0f, 1e-4f);
  c.update(CameraInput{.up = -1.0f}, 1.0f);
  c.update(CameraInput{.up = -1.0f}, 1.0f);
  c.update(CameraInput{.up = -1.0f}, 1.0f);
  c.update(CameraInput{.up = -1.0f}, 1.0f);
  c.update(CameraInput{.up = -1.0f}, 1.0f);
  EXPECT_EQ(c.position_m().z, 0.0f);  // never below the ground
  c.update(CameraInput{.look_dx_px = 100.0f, .look_dy_px = -1000.0f}, 0.1f);
  EXPECT_NEAR(c.yaw_deg(), 100.0f * CameraControl::kLookDegPerPx, 1e-4f);
  EXPECT_LT(c.pitch_deg(), 90.0f);  // never straight up
  EXPECT_GT(c.view_dir().z, 0.99f);
  c.scale_speed(1.0f);
  EXPECT_FLOAT_EQ(c.speed_mps(), 25.0f);
  c.scale_speed(-1000.0f);
  EXPECT_FLOAT_EQ(c.speed_mps(), CameraControl::kMinSpeedMps);
  c.update(CameraInput{.roll = 1.0f}, 1.0f);
  EXPECT_FLOAT_EQ(c.roll_deg(), CameraControl::kRollDegPerS);
}

// The viewer's roll is the scene's camera.roll_deg, with its sign: the library reads the same
// roll back from the applied camera (key_from_camera), and its rolled right wing points down.
TEST(ViewerCamera, AppliesItsRollAsTheScenesRoll) {
  CameraParams camera;
  camera.position_m = {0.0f, 0.0f, 500.0f};
  camera.view_dir = glm::normalize(glm::vec3(1.0f, 1.0f, 0.2f));
  camera.roll_deg = 30.0f;
  CameraControl c;
  c.sync_from(camera);
  EXPECT_FLOAT_EQ(c.roll_deg(), 30.0f);
  CameraParams out;
  c.apply_to(out);
  EXPECT_FLOAT_EQ(out.roll_deg, 30.0f);
  EXPECT_NEAR(key_from_camera(0.0, out).roll_deg, 30.0, 1e-3);

  c.update(CameraInput{.roll = 1.0f}, 1.0f);  // C for a second
  c.apply_to(out);
  EXPECT_FLOAT_EQ(out.roll_deg, 30.0f + CameraControl::kRollDegPerS);
  const CameraKey key = key_from_camera(0.0, out);
  EXPECT_NEAR(key.roll_deg, 75.0, 1e-3);
  const glm::dvec3 right =
      orientation_from_angles(key.heading_deg, key.pitch_deg, key.roll_deg) * glm::dvec3(1, 0, 0);
  EXPECT_LT(right.z, -0.9);  // 75 deg: the right wing well down

  // Past 180 the roll wraps, staying in the scene's [-180, 180].
  c.set_roll_deg(170.0f);
  c.update(CameraInput{.roll = 1.0f}, 0.5f);  // +22.5
  c.apply_to(out);
  EXPECT_NEAR(out.roll_deg, -167.5f, 1e-3f);
  c.set_roll_deg(-180.0f);
  c.apply_to(out);
  EXPECT_GE(out.roll_deg, -180.0f);
  EXPECT_LE(out.roll_deg, 180.0f);
  c.set_roll_deg(std::numeric_limits<float>::quiet_NaN());  // ignored
  c.apply_to(out);
  EXPECT_TRUE(std::isfinite(out.roll_deg));
}

// W flies along the view direction whatever the roll; A/D and Q/E along the rolled image's right
// and up (exactly, at pitch 0); the mouse turns the view towards the image's right and up.
TEST(ViewerCamera, FliesAndLooksRelativeToTheRolledCamera) {
  for (const float roll_deg : {0.0f, 35.0f, 90.0f, -120.0f}) {
    SCOPED_TRACE(roll_deg);
    CameraParams camera;
    camera.position_m = {0.0f, 0.0f, 1000.0f};
    camera.view_dir = glm::normalize(glm::vec3(0.3f, 1.0f, 0.0f));
    camera.roll_deg = roll_deg;
    CameraControl c;
    c.sync_from(camera);
    c.set_speed_mps(10.0f);
    const CameraKey key = key_from_camera(0.0, camera);
    const glm::dquat q = orientation_from_angles(key.heading_deg, key.pitch_deg, key.roll_deg);
    const glm::vec3 image_right(q * glm::dvec3(1, 0, 0)), image_up(q * glm::dvec3(0, 0, 1));
    EXPECT_NEAR(glm::length(c.strafe_right() - image_right), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(c.strafe_up() - image_up), 0.0f, 1e-5f);

    c.update(CameraInput{.forward = 1.0f}, 1.0f);
    EXPECT_NEAR(glm::length(c.position_m() - (camera.position_m + camera.view_dir * 10.0f)), 0.0f,
                1e-3f);
    const glm::vec3 before = c.position_m();
    c.update(CameraInput{.right = 1.0f}, 1.0f);
    EXPECT_NEAR(glm::length(c.position_m() - (before + image_right * 10.0f)), 0.0f, 1e-3f);
    c.update(CameraInput{.up = 1.0f}, 1.0f);
    EXPECT_NEAR(glm::length(c.position_m() - (before + (image_right + image_up) * 10.0f)), 0.0f,
                1e-3f);

    // A small drag right turns the view towards the image's right, a drag down towards its down;
    // the roll stays.
    const glm::vec3 view = c.view_dir();
    c.update(CameraInput{.look_dx_px = 4.0f}, 0.01f);
    const glm::vec3 turned_right = glm::normalize(c.view_dir() - view);
    EXPECT_GT(glm::dot(turned_right, image_right), 0.999f);
    const glm::vec3 view2 = c.view_dir();
    c.update(CameraInput{.look_dy_px = 4.0f}, 0.01f);
    const glm::vec3 turned_down = glm::normalize(c.view_dir() - view2);
    EXPECT_GT(glm::dot(turned_down, -image_up), 0.99f);
    EXPECT_FLOAT_EQ(c.roll_deg(), roll_deg);
  }
  // Pitched, unrolled: Q/E stay vertical and A/D level, as before roll was rendered.
  CameraParams pitched;
  pitched.view_dir = glm::normalize(glm::vec3(0.0f, 1.0f, 1.0f));
  CameraControl c;
  c.sync_from(pitched);
  EXPECT_NEAR(glm::length(c.strafe_up() - glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(c.strafe_right() - glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
}

CameraParams camera_at(glm::vec3 position_m, float roll_deg = 0.0f) {
  CameraParams camera;
  camera.position_m = position_m;
  camera.view_dir = {0.0f, 1.0f, 0.0f};
  camera.roll_deg = roll_deg;
  return camera;
}

// A key every half second of scene time while the camera moves; a pause is two keys at one
// place; the keys are the cameras as they were and read back from the file exactly.
TEST(ViewerPathRecorder, KeysEveryIntervalWhileMovingAndHoldsPauses) {
  PathRecorder r;
  const glm::vec3 a(0.0f, 0.0f, 100.0f);
  r.start(100.0, camera_at(a));  // scene time 100 is path time 0
  EXPECT_TRUE(r.recording());
  // Moving, one sample a frame of 0.1 s: a key at 0.5, 1.0, 1.5 (path time).
  for (int frame = 1; frame <= 15; ++frame)
    r.sample(100.0 + 0.1 * frame, camera_at(a + glm::vec3(0.0f, float(frame), 0.0f)));
  EXPECT_EQ(r.key_count(), 4u);
  // Still from 1.5 to 3.0, then moving again at 3.5.
  const glm::vec3 b = a + glm::vec3(0.0f, 15.0f, 0.0f);
  for (int frame = 16; frame <= 30; ++frame) r.sample(100.0 + 0.1 * frame, camera_at(b));
  EXPECT_EQ(r.key_count(), 4u);  // nothing moved: nothing kept
  r.sample(103.5, camera_at(b + glm::vec3(5.0f, 0.0f, 0.0f), 10.0f));
  EXPECT_EQ(r.key_count(), 6u);  // the pause's end (3.0, at b) and the new pose
  r.sample(103.2, camera_at(a));  // the clock went back: skipped
  EXPECT_EQ(r.key_count(), 6u);
  const CameraPath path = r.stop(103.7, camera_at(b + glm::vec3(6.0f, 0.0f, 0.0f), 10.0f));
  EXPECT_FALSE(r.recording());
  ASSERT_EQ(path.keys().size(), 7u);  // and the camera when it stopped
  const std::vector<double> times = {0.0, 0.5, 1.0, 1.5, 3.0, 3.5, 3.7};
  for (size_t i = 0; i < times.size(); ++i) EXPECT_NEAR(path.keys()[i].time_s, times[i], 1e-9);
  EXPECT_EQ(path.keys()[3].position_m, glm::dvec3(b));
  EXPECT_EQ(path.keys()[4].position_m, glm::dvec3(b));  // held
  EXPECT_NEAR(path.keys()[5].roll_deg, 10.0, 1e-4);
  // The path holds still between the pause's keys.
  EXPECT_EQ(path.at(2.2).position_m, b);

  // Written and read back, the same keys.
  const Scene scene;
  const CameraPath back = parse_camera_path(camera_path_to_toml(path), "rec.toml", scene);
  EXPECT_EQ(back.keys(), path.keys());
}

TEST(ViewerPathRecorder, AlwaysTwoKeys) {
  PathRecorder r;
  const glm::vec3 a(10.0f, 20.0f, 30.0f);
  r.start(5.0, camera_at(a));
  CameraPath path = r.stop(5.0, camera_at(a));  // no time passed
  ASSERT_EQ(path.keys().size(), 2u);
  EXPECT_EQ(path.keys()[0].position_m, glm::dvec3(a));
  EXPECT_EQ(path.keys()[1].position_m, glm::dvec3(a));
  EXPECT_DOUBLE_EQ(path.duration_s(), PathRecorder::kSampleIntervalS);

  r.start(5.0, camera_at(a));
  r.sample(6.0, camera_at(a));  // still
  path = r.stop(7.0, camera_at(a));
  ASSERT_EQ(path.keys().size(), 2u);  // still all along: the start and the end
  EXPECT_DOUBLE_EQ(path.duration_s(), 2.0);
}

TEST(ViewerPathPlayback, FliesThePathInSceneTimeFromWhenItStarted) {
  const Scene scene;
  const CameraPath path = parse_camera_path(
      "[[key]]\ntime_s = 2\nposition_m = [0, 0, 100]\nheading_deg = 0\npitch_deg = 0\n"
      "[[key]]\ntime_s = 6\nposition_m = [400, 0, 300]\nheading_deg = 90\npitch_deg = 10\n"
      "roll_deg = 20\n",
      "p.toml", scene);
  PathPlayback p;
  EXPECT_FALSE(p.camera_at(0.0));  // nothing loaded
  p.load(path, "p.toml");
  EXPECT_FALSE(p.playing());
  EXPECT_FALSE(p.camera_at(0.0));
  p.play(50.0);  // scene time 50 is path time 2
  ASSERT_TRUE(p.playing());
  for (const double t : {50.0, 51.0, 53.5}) {
    const std::optional<CameraParams> camera = p.camera_at(t);
    ASSERT_TRUE(camera);
    EXPECT_TRUE(same_view(*camera, path.at(t - 48.0))) << t;
  }
  EXPECT_TRUE(p.playing());
  const std::optional<CameraParams> last = p.camera_at(54.5);  // past the last key
  ASSERT_TRUE(last);
  EXPECT_TRUE(same_view(*last, path.at(6.0)));
  EXPECT_FLOAT_EQ(last->roll_deg, path.at(6.0).roll_deg);
  EXPECT_FALSE(p.playing());  // the flight is over
  EXPECT_FALSE(p.camera_at(55.0));
}

TEST(ViewerCamera, OrbitsAroundAPointAtItsDistance) {
  CameraControl c;
  CameraParams camera;
  camera.position_m = {0.0f, 0.0f, 1000.0f};
  camera.view_dir = {0.0f, 1.0f, 0.0f};
  c.sync_from(camera);
  c.set_orbit_distance_m(500.0f);
  c.set_mode(CameraMode::kOrbit);
  const glm::vec3 target = c.orbit_target_m();
  EXPECT_NEAR(glm::length(target - glm::vec3(0.0f, 500.0f, 1000.0f)), 0.0f, 1e-3f);
  c.update(CameraInput{.look_dx_px = 600.0f}, 0.1f);  // 90 deg around
  EXPECT_NEAR(glm::length(c.position_m() - target), 500.0f, 1e-2f);
  EXPECT_NEAR(c.position_m().x, -500.0f, 1e-2f);
  c.set_orbit_distance_m(100.0f);
  EXPECT_NEAR(glm::length(c.position_m() - target), 100.0f, 1e-2f);
}

TEST(ViewerCamera, PlaceOnThePlanetAndGoToAltitude) {
  LocationParams here;
  here.lat_deg = 45.0f;
  here.lon_deg = 7.0f;
  here.altitude_m = 300.0f;
  const float radius_km = 6360.0f;
  Geodetic g = geodetic_from_enu({0.0f, 0.0f, 0.0f}, here, radius_km);
  EXPECT_NEAR(g.lat_deg, 45.0, 1e-9);
  EXPECT_NEAR(g.lon_deg, 7.0, 1e-9);
  EXPECT_NEAR(g.altitude_m, 300.0, 1e-6);
  // One degree of arc north at 1 km up: latitude 46, the same height.
  const double r = radius_km * 1000.0 + 1000.0, a = std::numbers::pi / 180.0;
  g = geodetic_from_enu({0.0f, float(r * std::sin(a)), float(r * std::cos(a) - radius_km * 1000.0)},
                        here, radius_km);
  EXPECT_NEAR(g.lat_deg, 46.0, 1e-4);
  EXPECT_NEAR(g.lon_deg, 7.0, 1e-4);
  EXPECT_NEAR(g.altitude_m, 1300.0, 0.5);
  // 10 km east on the equator: 10 / 6360 rad of longitude.
  LocationParams equator;
  g = geodetic_from_enu({10000.0f, 0.0f, 0.0f}, equator, radius_km);
  EXPECT_NEAR(g.lon_deg, std::atan(10.0 / 6360.0) * 180.0 / std::numbers::pi, 1e-6);
  EXPECT_NEAR(g.lat_deg, 0.0, 1e-9);

  CameraControl c;
  CameraParams camera;
  camera.position_m = {50000.0f, 0.0f, 2.0f};
  c.sync_from(camera);
  c.go_to_altitude(3000.0f, radius_km);
  g = geodetic_from_enu(c.position_m(), equator, radius_km);
  EXPECT_NEAR(g.altitude_m, 3000.0, 0.5);
  EXPECT_GT(c.position_m().x, 50000.0f);  // straight up from where it was
  EXPECT_EQ(c.position_m().y, 0.0f);
}

}  // namespace
}  // namespace nephele::view

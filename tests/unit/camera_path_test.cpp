// Camera paths: the spline passes through its keys at their times with a continuous velocity,
// has no loop on a tight turn, orientations and fields of view interpolate, look_at and lat/lon
// keys land where they say, the file round-trips, and every malformed path gets its one line.
#include "nephele/camera_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/geometric.hpp>
#include <numbers>

#include "nephele/error.h"
#include "render/frame_params.h"

namespace nephele {
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

CameraKey key(double time_s, glm::dvec3 position_m, double heading_deg, double pitch_deg,
              double roll_deg = 0.0, double fov_deg = 60.0) {
  return {time_s, position_m, heading_deg, pitch_deg, roll_deg, fov_deg};
}

// Keys unevenly spaced in time and in distance, turning, climbing, rolling and zooming.
CameraPath uneven_path() {
  return CameraPath({key(0.0, {0, 0, 100}, 0, 0, 0, 60), key(1.0, {0, 300, 150}, 30, 5, 10, 50),
                     key(4.0, {500, 600, 120}, 80, -5, -15, 70),
                     key(4.5, {560, 640, 125}, 100, 0, 0, 65),
                     key(9.0, {900, 200, 400}, 170, 10, 20, 40)});
}

void expect_near(const glm::dvec3& a, const glm::dvec3& b, double tolerance) {
  EXPECT_LE(glm::distance(a, b), tolerance) << "(" << a.x << ", " << a.y << ", " << a.z << ") vs ("
                                            << b.x << ", " << b.y << ", " << b.z << ")";
}

// The difference of two angles in degrees, wrapped to (-180, 180].
double angle_difference(double a, double b) {
  double d = std::fmod(a - b, 360.0);
  if (d > 180.0) d -= 360.0;
  if (d <= -180.0) d += 360.0;
  return d;
}

// ------------------------------------------------------------------ interpolation

TEST(CameraPath, PassesThroughItsKeysAtTheirTimes) {
  const CameraPath path = uneven_path();
  EXPECT_EQ(path.start_s(), 0.0);
  EXPECT_EQ(path.end_s(), 9.0);
  EXPECT_EQ(path.duration_s(), 9.0);
  for (const CameraKey& k : path.keys()) {
    SCOPED_TRACE(k.time_s);
    const CameraPose pose = path.pose_at(k.time_s);
    EXPECT_EQ(pose.position_m, k.position_m);
    EXPECT_EQ(pose.fov_deg, k.fov_deg);
    const CameraAngles angles = angles_from_basis(pose.forward(), pose.up());
    EXPECT_NEAR(angle_difference(angles.heading_deg, k.heading_deg), 0.0, 1e-9);
    EXPECT_NEAR(angles.pitch_deg, k.pitch_deg, 1e-9);
    EXPECT_NEAR(angles.roll_deg, k.roll_deg, 1e-9);
    // The scene's camera: the same, in float.
    const CameraParams camera = path.at(k.time_s);
    EXPECT_EQ(camera.position_m, glm::vec3(k.position_m));
    EXPECT_EQ(camera.fov_deg, float(k.fov_deg));
    EXPECT_NEAR(camera.roll_deg, k.roll_deg, 1e-4);
    expect_near(glm::dvec3(camera.view_dir), pose.forward(), 1e-6);
  }
  // Held at the ends.
  EXPECT_EQ(path.pose_at(-5.0).position_m, path.keys().front().position_m);
  EXPECT_EQ(path.pose_at(100.0).position_m, path.keys().back().position_m);
}

// One-sided differences just before and just after each inner key agree: no kink in time,
// though the keys' spacings in time and distance differ by 10x.
TEST(CameraPath, VelocityIsContinuousAcrossKeys) {
  const CameraPath path = uneven_path();
  const double dt = 1e-5;
  for (size_t i = 1; i + 1 < path.keys().size(); ++i) {
    const double t = path.keys()[i].time_s;
    SCOPED_TRACE(t);
    const glm::dvec3 p = path.pose_at(t).position_m;
    const glm::dvec3 before = (p - path.pose_at(t - dt).position_m) / dt;
    const glm::dvec3 after = (path.pose_at(t + dt).position_m - p) / dt;
    EXPECT_GT(glm::length(before), 1.0);
    EXPECT_LT(glm::distance(before, after), 1e-3 * glm::length(before));
  }
  // A key where the camera stops (the same position twice): still continuous, at rest.
  const CameraPath hover({key(0, {0, 0, 10}, 0, 0), key(2, {0, 100, 10}, 0, 0),
                          key(3, {0, 100, 10}, 90, 0), key(5, {100, 100, 10}, 90, 0)});
  for (double t : {2.0, 3.0}) {
    const glm::dvec3 p = hover.pose_at(t).position_m;
    EXPECT_LT(glm::length(p - hover.pose_at(t - dt).position_m) / dt, 1e-2) << t;
    EXPECT_LT(glm::length(hover.pose_at(t + dt).position_m - p) / dt, 1e-2) << t;
  }
  EXPECT_EQ(hover.pose_at(2.5).position_m, glm::dvec3(0, 100, 10));
}

// A tight turn between far keys: a 1 m step between two 100 m legs. Uniform Catmull-Rom (the
// tangent at a key half the chord between its neighbours) swings 12.5 m past the turn and its
// segment loops; the centripetal spline (Yuksel et al. 2011: no cusps or self-intersections in a
// segment) stays within the step's length of the keys, and keeps moving.
TEST(CameraPath, CentripetalSplineTurnsTightlyWithoutLoopOrCusp) {
  const glm::dvec3 a(0, 0, 100), b(100, 0, 100), c(100, 1, 100), d(0, 1, 100);
  const CameraPath path({key(0, a, 90, 0), key(1, b, 0, 0), key(2, c, 270, 0), key(3, d, 270, 0)});
  // The uniform spline's segment from b to c, as a Hermite cubic, for comparison.
  const auto uniform = [&](double s) {
    const glm::dvec3 mb = 0.5 * (c - a), mc = 0.5 * (d - b);
    const double s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * b + (s3 - 2 * s2 + s) * mb + (-2 * s3 + 3 * s2) * c +
           (s3 - s2) * mc;
  };
  constexpr int kSamples = 400;
  std::vector<glm::dvec3> points;
  double overshoot = 0.0, uniform_overshoot = 0.0, min_speed = 1e30;
  for (int i = 0; i <= kSamples; ++i) {
    const double s = double(i) / kSamples;
    const glm::dvec3 p = path.pose_at(1.0 + s).position_m;
    points.push_back(p);
    overshoot = std::max(overshoot, p.x - 100.0);
    uniform_overshoot = std::max(uniform_overshoot, uniform(s).x - 100.0);
    if (i > 0) min_speed = std::min(min_speed, glm::distance(p, points[i - 1]) * kSamples);
    EXPECT_NEAR(p.z, 100.0, 1e-9);
  }
  EXPECT_GT(uniform_overshoot, 10.0) << "the case is a tight one";
  EXPECT_LT(overshoot, 1.0);
  EXPECT_GT(min_speed, 0.05) << "a cusp stops the camera";
  // No two non-adjacent pieces of the sampled segment cross (in the plane z = 100).
  const auto cross = [](glm::dvec2 o, glm::dvec2 p, glm::dvec2 q) {
    return (p.x - o.x) * (q.y - o.y) - (p.y - o.y) * (q.x - o.x);
  };
  int crossings = 0;
  for (size_t i = 0; i + 1 < points.size(); ++i)
    for (size_t j = i + 2; j + 1 < points.size(); ++j) {
      const glm::dvec2 p1(points[i]), p2(points[i + 1]), q1(points[j]), q2(points[j + 1]);
      if (cross(p1, p2, q1) * cross(p1, p2, q2) < 0 && cross(q1, q2, p1) * cross(q1, q2, p2) < 0)
        ++crossings;
    }
  EXPECT_EQ(crossings, 0);
}

TEST(CameraPath, RollFovAndOrientationInterpolate) {
  const CameraPath roll({key(0, {0, 0, 10}, 45, 10, 0, 30), key(2, {0, 50, 10}, 45, 10, 60, 90)});
  for (double t : {0.5, 1.0, 1.5}) {
    const CameraPose pose = roll.pose_at(t);
    const CameraAngles angles = angles_from_basis(pose.forward(), pose.up());
    EXPECT_NEAR(angles.roll_deg, 30.0 * t, 1e-9) << t;
    EXPECT_NEAR(angles.heading_deg, 45.0, 1e-9) << t;
    EXPECT_NEAR(angles.pitch_deg, 10.0, 1e-9) << t;
    EXPECT_NEAR(pose.fov_deg, 30.0 + 30.0 * t, 1e-12) << t;
    EXPECT_NEAR(roll.at(t).roll_deg, 30.0 * t, 1e-4) << t;
  }
  // Heading 350 to 10 turns through north (the shorter arc), not through south.
  const CameraPath turn({key(0, {0, 0, 10}, 350, 0), key(1, {0, 10, 10}, 10, 0)});
  const CameraAngles middle =
      angles_from_basis(turn.pose_at(0.5).forward(), turn.pose_at(0.5).up());
  EXPECT_NEAR(angle_difference(middle.heading_deg, 0.0), 0.0, 1e-9);
  // The turn's rate is uniform: a quarter of the way, a quarter of the angle.
  const CameraAngles quarter =
      angles_from_basis(turn.pose_at(0.25).forward(), turn.pose_at(0.25).up());
  EXPECT_NEAR(angle_difference(quarter.heading_deg, 355.0), 0.0, 1e-9);
}

TEST(CameraPath, OrientationConventions) {
  // Heading 90 looks east, pitch 90 up; roll 30 turns the right side down.
  expect_near(orientation_from_angles(90, 0, 0) * glm::dvec3(0, 1, 0), {1, 0, 0}, 1e-15);
  expect_near(orientation_from_angles(0, 90, 0) * glm::dvec3(0, 1, 0), {0, 0, 1}, 1e-15);
  const glm::dvec3 right = orientation_from_angles(0, 0, 30) * glm::dvec3(1, 0, 0);
  expect_near(right, {std::cos(std::numbers::pi / 6), 0, -0.5}, 1e-15);
  // The renderer's camera basis agrees: camera.roll_deg has the same sense.
  CameraParams camera;
  camera.view_dir = {0.0f, 1.0f, 0.0f};
  camera.roll_deg = 30.0f;
  const CameraBasis basis = camera_basis(camera);
  expect_near(glm::dvec3(basis.right), right, 1e-6);
}

TEST(CameraPath, KeyFromCameraGivesTheCameraBack) {
  CameraParams camera;
  camera.position_m = {120.0f, -40.0f, 900.0f};
  camera.view_dir = {0.3f, -0.8f, 0.25f};
  camera.roll_deg = -33.0f;
  camera.fov_deg = 48.0f;
  CameraParams later = camera;
  later.position_m.x += 50.0f;
  later.view_dir = {0.0f, 0.0f, 1.0f};  // straight up: the renderer's up is north there
  later.roll_deg = 120.0f;
  const CameraPath path({key_from_camera(1.0, camera), key_from_camera(2.0, later)});
  for (const auto& [t, expected] : {std::pair{1.0, camera}, {2.0, later}}) {
    const CameraParams back = path.at(t);
    EXPECT_EQ(back.position_m, expected.position_m);
    expect_near(glm::dvec3(back.view_dir), glm::dvec3(glm::normalize(expected.view_dir)), 1e-6);
    EXPECT_NEAR(angle_difference(back.roll_deg, expected.roll_deg), 0.0, 1e-3);
    EXPECT_EQ(back.fov_deg, expected.fov_deg);
  }
}

// ------------------------------------------------------------------ the file

std::string two_keys(const std::string& first, const std::string& second = "") {
  return "[[key]]\n" + first + "\n[[key]]\n" +
         (second.empty() ? "time_s = 10\nposition_m = [0, 100, 10]\nheading_deg = 0\npitch_deg = 0"
                         : second) +
         "\n";
}

TEST(CameraPathFile, LookAtPointsAtTheTarget) {
  Scene scene;
  const CameraPath path = parse_camera_path(
      two_keys("time_s = 0\nposition_m = [10, 20, 30]\nlook_at_m = [110, 20, 130]\nroll_deg = 5"),
      "path.toml", scene);
  const CameraPose pose = path.pose_at(0.0);
  expect_near(pose.forward(), glm::normalize(glm::dvec3(100, 0, 100)), 1e-12);
  EXPECT_NEAR(path.keys()[0].heading_deg, 90.0, 1e-12);
  EXPECT_NEAR(path.keys()[0].pitch_deg, 45.0, 1e-12);
  EXPECT_EQ(path.keys()[0].roll_deg, 5.0);
}

TEST(CameraPathFile, LatLonKeysLandAtTheirPointsOfTheScenesFrame) {
  Scene scene;
  scene.location.lat_deg = 45.0f;
  scene.location.lon_deg = 7.0f;
  const double r = 6360e3, h = 300.0;
  // At the scene's location: straight above the origin.
  expect_near(enu_from_lat_lon(scene, 45.0, 7.0, h), {0, 0, h}, 1e-6);
  // 0.01 deg north along the meridian: north by (R + h) sin, down by the sphere's curve.
  const double a = 0.01 * std::numbers::pi / 180.0;
  expect_near(enu_from_lat_lon(scene, 45.01, 7.0, h),
              {0, (r + h) * std::sin(a), (r + h) * std::cos(a) - r}, 1e-6);
  // East: at latitude 45 a degree of longitude is cos 45 as long; the point stays on the
  // parallel, which curves north of the east axis.
  const glm::dvec3 east = enu_from_lat_lon(scene, 45.0, 7.01, h);
  EXPECT_NEAR(east.x, (r + h) * std::cos(std::numbers::pi / 4) * std::sin(a), 1e-6);
  EXPECT_GT(east.y, 0.0);
  // Every point keeps its altitude above the sphere in the renderer's frame (planet_from_enu).
  for (const auto& [p, altitude_m] :
       {std::pair{east, h}, {enu_from_lat_lon(scene, 44.2, 8.1, 5000.0), 5000.0}})
    EXPECT_NEAR(glm::length(glm::dvec3(p.x, p.y, r + p.z)) - r, altitude_m, 1e-6);
  // In a file: the key's position is that point.
  const CameraPath path = parse_camera_path(
      two_keys("time_s = 0\nlat_deg = 45.01\nlon_deg = 7\naltitude_m = 300\nheading_deg = 0\n"
               "pitch_deg = 0"),
      "path.toml", scene);
  EXPECT_EQ(path.keys()[0].position_m, enu_from_lat_lon(scene, 45.01, 7.0, 300.0));
}

TEST(CameraPathFile, FovDefaultsToTheScenes) {
  Scene scene;
  scene.camera.fov_deg = 42.5f;
  const CameraPath path = parse_camera_path(
      two_keys("time_s = 0\nposition_m = [0, 0, 2]\nheading_deg = 0\npitch_deg = 0\nfov_deg = 20"),
      "path.toml", scene);
  EXPECT_EQ(path.keys()[0].fov_deg, 20.0);
  EXPECT_EQ(path.keys()[1].fov_deg, 42.5);
  EXPECT_EQ(path.pose_at(5.0).fov_deg, 31.25);
}

TEST(CameraPathFile, WriterReadsBackExactly) {
  const CameraPath path({key(0.1, {1.0 / 3.0, -2e8, 0.0}, 359.999, -89.5, -179.25, 0.01),
                         key(2, {5.802e-6, 1e9, 1e9}, -360, 90, 180, 179.999),
                         key(1e6, {0, 0, 2}, 0, 0, 0, 70)});
  const std::string text = camera_path_to_toml(path);
  SCOPED_TRACE(text);
  Scene scene;
  const CameraPath back = parse_camera_path(text, "recorded.toml", scene);
  EXPECT_EQ(back.keys(), path.keys());
  EXPECT_NE(text.find("[[key]]\ntime_s = 2.0\n"), std::string::npos);
}

TEST(CameraPathFile, LoadReadsAFileAndNamesIt) {
  const std::filesystem::path dir =
      std::filesystem::path(NEPHELE_TEST_OUTPUT_DIR) / "camera_path_test";
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "flight.toml").string();
  std::ofstream(file) << two_keys(
      "time_s = 0\nposition_m = [0, 0, 2]\nheading_deg = 0\npitch_deg = 0");
  Scene scene;
  EXPECT_EQ(load_camera_path(file, scene).keys().size(), 2u);
  std::ofstream(file) << "[[key]]\ntime_s = 0\n";
  EXPECT_EQ(input_error([&] { load_camera_path(file, scene); }),
            file +
                ": key[0]: no position: give position_m = [east, north, up] or lat_deg, "
                "lon_deg and altitude_m");
  const std::string missing = (dir / "missing.toml").string();
  EXPECT_EQ(input_error([&] { load_camera_path(missing, scene); }),
            missing + ": cannot read the camera path: No such file or directory");
  EXPECT_EQ(input_error([&] { load_camera_path(dir.string(), scene); }),
            dir.string() + ": cannot read the camera path: it is a directory");
}

struct BadPath {
  const char* name;
  std::string toml;
  std::string message;  // the whole message, or its start when `whole` is false
  bool whole = true;
};

const std::string kKey0 = "time_s = 0\nposition_m = [0, 0, 2]\nheading_deg = 0\npitch_deg = 0";

const BadPath kBadPaths[] = {
    {"Empty", "", "path.toml: 0 keys: a camera path needs at least 2 keys ([[key]] tables)"},
    {"OneKey", "[[key]]\n" + kKey0 + "\n",
     "path.toml: 1 key: a camera path needs at least 2 keys ([[key]] tables)"},
    {"TimesNotIncreasing",
     two_keys("time_s = 5\nposition_m = [0, 0, 2]\nheading_deg = 0\npitch_deg = 0",
              "time_s = 2\nposition_m = [0, 9, 2]\nheading_deg = 0\npitch_deg = 0"),
     "path.toml: key[1].time_s = 2: must be greater than key[0].time_s = 5"},
    {"TimeMissing", two_keys("position_m = [0, 0, 2]\nheading_deg = 0\npitch_deg = 0"),
     "path.toml: key[0]: time_s is missing"},
    {"PositionMissing", two_keys("time_s = 0\nheading_deg = 0\npitch_deg = 0"),
     "path.toml: key[0]: no position: give position_m = [east, north, up] or lat_deg, lon_deg and "
     "altitude_m"},
    {"BothPositions",
     two_keys("time_s = 0\nposition_m = [0, 0, 2]\nlat_deg = 0\nheading_deg = 0\npitch_deg = 0"),
     "path.toml: key[0]: position_m and lat_deg/lon_deg/altitude_m are both given; give one form"},
    {"LatWithoutLon",
     two_keys("time_s = 0\nlat_deg = 0\naltitude_m = 5\nheading_deg = 0\npitch_deg = 0"),
     "path.toml: key[0]: lon_deg is missing (lat_deg, lon_deg and altitude_m go together)"},
    {"OrientationMissing", two_keys("time_s = 0\nposition_m = [0, 0, 2]"),
     "path.toml: key[0]: no orientation: give heading_deg and pitch_deg, or look_at_m"},
    {"HeadingWithoutPitch", two_keys("time_s = 0\nposition_m = [0, 0, 2]\nheading_deg = 0"),
     "path.toml: key[0]: pitch_deg is missing (heading_deg and pitch_deg go together; or give "
     "look_at_m)"},
    {"BothOrientations",
     two_keys("time_s = 0\nposition_m = [0, 0, 2]\nheading_deg = 0\nlook_at_m = [0, 1, 2]"),
     "path.toml: key[0]: heading_deg/pitch_deg and look_at_m are both given; give one form"},
    {"LookAtItself", two_keys("time_s = 0\nposition_m = [0, 0, 2]\nlook_at_m = [0, 0, 2]"),
     "path.toml: key[0].look_at_m = (0, 0, 2): is the key's position"},
    {"UnknownKeyInAKey", two_keys(kKey0 + "\nheadng_deg = 3"),
     "path.toml: key[0]: unknown key 'headng_deg' (allowed: time_s, position_m, lat_deg, lon_deg, "
     "altitude_m, heading_deg, pitch_deg, roll_deg, look_at_m, fov_deg)"},
    {"UnknownTopLevelKey", "speed = 3\n" + two_keys(kKey0),
     "path.toml: unknown key 'speed' (a camera path has only [[key]] tables)"},
    {"KeyNotATable", "key = 3\n", "path.toml: key = 3: expected [[key]] tables"},
    {"WrongType",
     two_keys("time_s = \"soon\"\nposition_m = [0, 0, 2]\nheading_deg = 0\npitch_deg = 0"),
     "path.toml: key[0].time_s = \"soon\": expected a number"},
    {"ShortVector", two_keys("time_s = 0\nposition_m = [0, 2]\nheading_deg = 0\npitch_deg = 0"),
     "path.toml: key[0].position_m = [0, 2]: expected an array of 3 numbers [east, north, up]"},
    {"NotFinite", two_keys("time_s = 0\nposition_m = [0, 0, 2]\nheading_deg = nan\npitch_deg = 0"),
     "path.toml: key[0].heading_deg = nan: must be a finite number"},
    {"InfinitePosition",
     two_keys("time_s = 0\nposition_m = [inf, 0, 2]\nheading_deg = 0\npitch_deg = 0"),
     "path.toml: key[0].position_m = (inf, 0, 2): must be finite"},
    {"PitchOutOfRange",
     two_keys("time_s = 0\nposition_m = [0, 0, 2]\nheading_deg = 0\npitch_deg = 95"),
     "path.toml: key[0].pitch_deg = 95: must be in [-90, 90]"},
    {"RollOutOfRange", two_keys(kKey0 + "\nroll_deg = 200"),
     "path.toml: key[0].roll_deg = 200: must be in [-180, 180]"},
    {"FovOutOfRange", two_keys(kKey0 + "\nfov_deg = 180"),
     "path.toml: key[0].fov_deg = 180: must be in [0.01, 180)"},
    {"BelowTheGround",
     two_keys("time_s = 0\nposition_m = [0, 0, -1]\nheading_deg = 0\npitch_deg = 0"),
     "path.toml: key[0].position_m = (0, 0, -1): the up component must be >= 0 (below the ground)"},
    {"TooFar", two_keys("time_s = 0\nposition_m = [2e9, 0, 1]\nheading_deg = 0\npitch_deg = 0"),
     "path.toml: key[0].position_m = (2e+09, 0, 1): east and north must be in [-1e+09, 1e+09] m "
     "(as camera.position_m)"},
    {"LatitudeOutOfRange",
     two_keys(
         "time_s = 0\nlat_deg = 91\nlon_deg = 0\naltitude_m = 5\nheading_deg = 0\npitch_deg = 0"),
     "path.toml: key[0].lat_deg = 91: must be in [-90, 90]"},
    {"FarPointBelowTheGroundPlane",
     two_keys(
         "time_s = 0\nlat_deg = 1\nlon_deg = 0\naltitude_m = 5\nheading_deg = 0\npitch_deg = 0"),
     "path.toml: key[0].altitude_m = 5: at lat_deg 1, lon_deg 0 the point is 963", false},
    {"TimeOutOfRange",
     two_keys("time_s = 2e6\nposition_m = [0, 0, 2]\nheading_deg = 0\npitch_deg = 0"),
     "path.toml: key[0].time_s = 2e+06: must be in [-1e+06, 1e+06]"},
    {"DeeplyNestedKey",
     [] {
       std::string deep;
       for (int i = 0; i < 40; ++i) deep += "k.";
       return deep + "x = 1\n";
     }(),
     "path.toml:1: a key with more than 32 dotted parts"},
    {"MalformedToml", "[[key]\ntime_s = 0\n", "path.toml:1:", false},
};

class CameraPathErrors : public ::testing::TestWithParam<BadPath> {};

// Each malformed path: one line naming the file, the key and the problem.
TEST_P(CameraPathErrors, OneLineNamingTheFileTheKeyAndTheProblem) {
  const BadPath& bad = GetParam();
  Scene scene;
  const std::string message = input_error([&] { parse_camera_path(bad.toml, "path.toml", scene); });
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  if (bad.whole)
    EXPECT_EQ(message, bad.message);
  else
    EXPECT_EQ(message.rfind(bad.message, 0), 0u) << message;
}

INSTANTIATE_TEST_SUITE_P(CameraPath, CameraPathErrors, ::testing::ValuesIn(kBadPaths),
                         [](const ::testing::TestParamInfo<BadPath>& info) {
                           return std::string(info.param.name);
                         });

TEST(CameraPathErrors, EqualTimesAndProgrammaticKeysAreCheckedToo) {
  EXPECT_EQ(input_error([] {
              CameraPath({key(1, {0, 0, 2}, 0, 0), key(1, {0, 5, 2}, 0, 0)}, "recorded");
            }),
            "recorded: key[1].time_s = 1: must be greater than key[0].time_s = 1");
  EXPECT_EQ(input_error([] {
              CameraPath({key(1, {0, 0, 2}, 0, 0)});
            }),
            "camera path: 1 key: a camera path needs at least 2 keys ([[key]] tables)");
}

}  // namespace
}  // namespace nephele

// nephele-view — the interactive camera.
#include "camera_control.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "nephele/scene_io.h"

namespace nephele::view {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
constexpr float kMaxPitchDeg = 89.5f;  // the view never points straight up or down
// The scene's limits (scene.h): east and north within 1e9 m, up in [0, 1e9].
constexpr float kMaxCoordinateM = 1e9f;

glm::vec3 clamp_to_scene(glm::vec3 p) {
  p.x = std::clamp(p.x, -kMaxCoordinateM, kMaxCoordinateM);
  p.y = std::clamp(p.y, -kMaxCoordinateM, kMaxCoordinateM);
  p.z = std::clamp(p.z, 0.0f, kMaxCoordinateM);
  return p;
}

}  // namespace

bool CameraInput::any() const {
  return forward != 0.0f || right != 0.0f || up != 0.0f || roll != 0.0f || look_dx_px != 0.0f ||
         look_dy_px != 0.0f;
}

void CameraControl::sync_from(const CameraParams& camera) {
  position_m_ = camera.position_m;
  const SunAngles angles = sun_angles_from_direction(camera.view_dir);
  yaw_deg_ = float(angles.azimuth_deg);
  pitch_deg_ = std::clamp(float(angles.elevation_deg), -kMaxPitchDeg, kMaxPitchDeg);
  set_roll_deg(camera.roll_deg);
  if (mode_ == CameraMode::kOrbit) orbit_target_m_ = position_m_ + view_dir() * orbit_distance_m_;
}

void CameraControl::apply_to(CameraParams& camera) const {
  camera.position_m = position_m_;
  camera.view_dir = view_dir();
  camera.roll_deg = roll_deg_;  // the same sign: right wing down is positive in both
}

void CameraControl::set_roll_deg(float roll_deg) {
  if (!std::isfinite(roll_deg)) return;
  roll_deg_ = std::clamp(std::remainder(roll_deg, 360.0f), -180.0f, 180.0f);
}

// The level right (horizontal, perpendicular to the heading) and the world's up, turned by the
// roll about the heading: positive roll turns the right downwards and the up towards the right.
glm::vec3 CameraControl::strafe_right() const {
  const float yaw = yaw_deg_ / float(kDegPerRad), roll = roll_deg_ / float(kDegPerRad);
  const glm::vec3 level_right(std::cos(yaw), -std::sin(yaw), 0.0f);
  return level_right * std::cos(roll) - glm::vec3(0.0f, 0.0f, 1.0f) * std::sin(roll);
}

glm::vec3 CameraControl::strafe_up() const {
  const float yaw = yaw_deg_ / float(kDegPerRad), roll = roll_deg_ / float(kDegPerRad);
  const glm::vec3 level_right(std::cos(yaw), -std::sin(yaw), 0.0f);
  return level_right * std::sin(roll) + glm::vec3(0.0f, 0.0f, 1.0f) * std::cos(roll);
}

glm::vec3 CameraControl::view_dir() const {
  return sun_direction_from_angles(pitch_deg_, yaw_deg_);
}

void CameraControl::update(const CameraInput& input, float dt_s) {
  dt_s = std::clamp(dt_s, 0.0f, 1.0f);  // a stall (a table rebuild) is not a leap
  // The mouse moves the view towards the image's right (dx) and down (dy). In (yaw, pitch) the
  // rolled image's right is (cos r, -sin r) and its up (sin r, cos r).
  const float roll_rad = roll_deg_ / float(kDegPerRad);
  const float cos_roll = std::cos(roll_rad), sin_roll = std::sin(roll_rad);
  const float look_yaw_deg =
      (input.look_dx_px * cos_roll - input.look_dy_px * sin_roll) * kLookDegPerPx;
  const float look_pitch_deg =
      (-input.look_dx_px * sin_roll - input.look_dy_px * cos_roll) * kLookDegPerPx;
  yaw_deg_ = std::fmod(std::fmod(yaw_deg_ + look_yaw_deg, 360.0f) + 360.0f, 360.0f);
  pitch_deg_ = std::clamp(pitch_deg_ + look_pitch_deg, -kMaxPitchDeg, kMaxPitchDeg);
  set_roll_deg(roll_deg_ + input.roll * kRollDegPerS * dt_s);
  if (mode_ == CameraMode::kOrbit) {
    // W/S move in and out, A/D and Q/E circle the target.
    const float factor = std::pow(2.0f, -input.forward * dt_s);
    orbit_distance_m_ = std::clamp(orbit_distance_m_ * factor, kMinOrbitDistanceM, kMaxCoordinateM);
    yaw_deg_ = std::fmod(yaw_deg_ - input.right * 45.0f * dt_s + 360.0f, 360.0f);
    pitch_deg_ = std::clamp(pitch_deg_ - input.up * 45.0f * dt_s, -kMaxPitchDeg, kMaxPitchDeg);
    update_orbit_position();
    return;
  }
  const glm::vec3 move =
      view_dir() * input.forward + strafe_right() * input.right + strafe_up() * input.up;
  position_m_ = clamp_to_scene(position_m_ + move * speed_mps_ * dt_s);
}

void CameraControl::update_orbit_position() {
  position_m_ = clamp_to_scene(orbit_target_m_ - view_dir() * orbit_distance_m_);
}

void CameraControl::scale_speed(float notches) {
  set_speed_mps(speed_mps_ * std::pow(1.25f, notches));
}

void CameraControl::set_speed_mps(float speed) {
  if (!std::isfinite(speed)) return;
  speed_mps_ = std::clamp(speed, kMinSpeedMps, kMaxSpeedMps);
}

void CameraControl::set_mode(CameraMode mode) {
  if (mode == mode_) return;
  mode_ = mode;
  if (mode_ == CameraMode::kOrbit) orbit_target_m_ = position_m_ + view_dir() * orbit_distance_m_;
}

void CameraControl::set_orbit_distance_m(float distance_m) {
  if (!std::isfinite(distance_m)) return;
  orbit_distance_m_ = std::clamp(distance_m, kMinOrbitDistanceM, kMaxCoordinateM);
  if (mode_ == CameraMode::kOrbit) update_orbit_position();
}

void CameraControl::go_to_altitude(float altitude_m, float planet_radius_km) {
  if (!std::isfinite(altitude_m)) return;
  // From the planet's centre (0, 0, -R) out through the camera, to radius R + altitude.
  const double radius_m = double(planet_radius_km) * 1000.0;
  const double x = position_m_.x, y = position_m_.y, z = double(position_m_.z) + radius_m;
  const double length = std::sqrt(x * x + y * y + z * z);
  const double scale = (radius_m + std::max(0.0, double(altitude_m))) / length;
  position_m_ = clamp_to_scene(glm::vec3(float(x * scale), float(y * scale),
                                         float(z * scale - radius_m)));
  if (mode_ == CameraMode::kOrbit) orbit_target_m_ = position_m_ + view_dir() * orbit_distance_m_;
}

Geodetic geodetic_from_enu(const glm::vec3& position_m, const LocationParams& location,
                           float planet_radius_km) {
  const double radius_m = double(planet_radius_km) * 1000.0;
  const double lat = location.lat_deg / kDegPerRad, lon = location.lon_deg / kDegPerRad;
  // The origin's east, north and up axes in planet-centred coordinates (x towards lon 0 on
  // the equator, z towards the north pole).
  const double east[3] = {-std::sin(lon), std::cos(lon), 0.0};
  const double north[3] = {-std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon),
                           std::cos(lat)};
  const double up[3] = {std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)};
  const double e = position_m.x, n = position_m.y, u = double(position_m.z) + radius_m;
  double p[3];
  for (int i = 0; i < 3; ++i) p[i] = e * east[i] + n * north[i] + u * up[i];
  const double length = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  Geodetic g;
  g.lat_deg = std::asin(std::clamp(p[2] / length, -1.0, 1.0)) * kDegPerRad;
  g.lon_deg = std::atan2(p[1], p[0]) * kDegPerRad;
  g.altitude_m = length - radius_m + location.altitude_m;
  return g;
}

}  // namespace nephele::view

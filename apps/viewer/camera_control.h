// nephele-view — the interactive camera: flight and orbit, and where it is on the planet.
//
// Angles: yaw_deg is the azimuth of the view from north through east, pitch_deg its elevation
// above the local horizontal plane, roll_deg a turn about the view axis with the scene's sign
// (camera.roll_deg: positive turns the camera clockwise as its viewer sees it, right wing down).
// Positions are the scene's ENU metres (scene.h).
//
// Flight with a rolled camera, as a pilot sees the image:
//   - W/S fly along the view direction, whatever the roll;
//   - A/D and Q/E move along the image's right and up as the roll turns them about the heading:
//     the level right (horizontal, perpendicular to the heading) and the world's up, turned by
//     roll_deg in their plane. With roll 0 they are the level right and straight up, as before;
//     at pitch 0 they are exactly the rolled image's right and up;
//   - the mouse turns the view towards the image's right and up: a drag of (dx, dy) pixels is
//     turned by the roll into yaw and pitch, so the scene follows the mouse in a rolled image
//     as in a level one. The roll itself stays as it is (Z/C change it).
#pragma once

#include <glm/vec3.hpp>

#include "nephele/scene.h"

namespace nephele::view {

// What the keys and the mouse did since the last frame.
struct CameraInput {
  float forward = 0.0f;  // W +1, S -1
  float right = 0.0f;    // D +1, A -1
  float up = 0.0f;       // E +1, Q -1
  float roll = 0.0f;     // C +1, Z -1
  float look_dx_px = 0.0f, look_dy_px = 0.0f;  // mouse motion with the right button held
  bool any() const;
};

enum class CameraMode { kFly, kOrbit };

class CameraControl {
 public:
  static constexpr float kMinSpeedMps = 0.1f;
  static constexpr float kMaxSpeedMps = 1e6f;
  static constexpr float kLookDegPerPx = 0.15f;
  static constexpr float kRollDegPerS = 45.0f;
  static constexpr float kMinOrbitDistanceM = 1.0f;

  // Takes position, direction and roll from the scene's camera.
  void sync_from(const CameraParams& camera);
  // Writes position, direction and roll (camera.roll_deg, in [-180, 180]) into the scene's
  // camera; the field of view stays the scene's.
  void apply_to(CameraParams& camera) const;

  // One frame of `dt_s` seconds.
  void update(const CameraInput& input, float dt_s);

  // Speed: mouse wheel notches or +/- (each x1.25), within [kMinSpeedMps, kMaxSpeedMps].
  void scale_speed(float notches);
  float speed_mps() const { return speed_mps_; }
  void set_speed_mps(float speed);

  // Orbit around the point `distance_m` ahead of the camera; back to flight keeps the pose.
  void set_mode(CameraMode mode);
  CameraMode mode() const { return mode_; }
  float orbit_distance_m() const { return orbit_distance_m_; }
  void set_orbit_distance_m(float distance_m);
  glm::vec3 orbit_target_m() const { return orbit_target_m_; }

  // Moves to `altitude_m` above the planet's surface (a sphere of radius planet_radius_km
  // through the ENU origin), straight up or down from where the camera is.
  void go_to_altitude(float altitude_m, float planet_radius_km);

  glm::vec3 position_m() const { return position_m_; }
  glm::vec3 view_dir() const;
  float yaw_deg() const { return yaw_deg_; }
  float pitch_deg() const { return pitch_deg_; }
  float roll_deg() const { return roll_deg_; }
  // Wrapped into [-180, 180]; a value that is not finite is ignored.
  void set_roll_deg(float roll_deg);
  // The directions A/D and Q/E move along (unit vectors, ENU): see the top of this file.
  glm::vec3 strafe_right() const;
  glm::vec3 strafe_up() const;

 private:
  void update_orbit_position();

  glm::vec3 position_m_{0.0f, 0.0f, 2.0f};
  float yaw_deg_ = 0.0f, pitch_deg_ = 0.0f, roll_deg_ = 0.0f;
  float speed_mps_ = 50.0f;
  CameraMode mode_ = CameraMode::kFly;
  glm::vec3 orbit_target_m_{0.0f};
  float orbit_distance_m_ = 1000.0f;
};

// A place on the planet: latitude and longitude (deg) and altitude above sea level (m).
struct Geodetic {
  double lat_deg = 0.0, lon_deg = 0.0, altitude_m = 0.0;
};

// Where ENU position `position_m` is, for the scene's location (the ENU origin, on the ground
// at location.altitude_m above sea level) on a sphere of `planet_radius_km` (the local tangent
// plane's up is the sphere's normal at the origin).
Geodetic geodetic_from_enu(const glm::vec3& position_m, const LocationParams& location,
                           float planet_radius_km);

}  // namespace nephele::view

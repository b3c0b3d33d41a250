// nephele — camera paths: a flight through a scene as keyframes in time, interpolated.
//
// A path file (TOML) is a list of [[key]] tables, each a moment of the flight:
//
//   [[key]]
//   time_s = 0                       # seconds on the path's clock, increasing from key to key
//   position_m = [0, -2000, 300]     # ENU (scene.h), or lat_deg, lon_deg and altitude_m
//   heading_deg = 0                  # from north through east, [-360, 360]
//   pitch_deg = 5                    # above the horizontal, [-90, 90]
//   roll_deg = 0                     # as camera.roll_deg, [-180, 180]; optional, 0
//   fov_deg = 60                     # optional: the scene's camera.fov_deg
//
// A key gives its position as position_m or as lat_deg, lon_deg and altitude_m (all three;
// enu_from_lat_lon), and its orientation as heading_deg and pitch_deg or as look_at_m (the ENU
// point the camera looks at from the key's position), with an optional roll_deg either way.
// Keys are counted from 0 in messages: "path.toml: key[3].time_s = 2: must be greater than
// key[2].time_s = 5".
//
// Between keys the position follows a centripetal Catmull-Rom spline (Yuksel, Schaefer and
// Keyser 2011: no cusps or self-intersections within a segment, tight to the keys), the
// orientation a spherical interpolation of the keys' quaternions along the shorter arc, and the
// field of view a straight line. The spline's knots are spaced by the square root of the
// distance between keys; each key's time maps to its knot through a monotone cubic (Fritsch and
// Carlson 1980), so the camera is at each key exactly at its time_s and its velocity is
// continuous across keys. Before the first key and after the last the camera stays there.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "nephele/scene.h"

namespace nephele {

// One key of a path: where the camera is at time_s, where it looks, its field of view.
struct CameraKey {
  double time_s = 0.0;                   // [-1e6, 1e6], increasing from key to key
  glm::dvec3 position_m{0.0, 0.0, 2.0};  // ENU (m), in camera.position_m's range
  double heading_deg = 0.0;              // from north through east, [-360, 360]
  double pitch_deg = 0.0;                // above the horizontal, [-90, 90]
  double roll_deg = 0.0;  // about the looking direction (camera.roll_deg), [-180, 180]
  double fov_deg = 70.0;  // vertical field of view, [0.01, 180)
  bool operator==(const CameraKey&) const = default;
};

// The camera at one time of a path, in double precision.
struct CameraPose {
  glm::dvec3 position_m{0.0};  // ENU (m)
  // Turns the camera's axes (x right, y forward, z the image's up) into ENU: heading 0, pitch 0,
  // roll 0 is the identity (looking north, right east).
  glm::dquat orientation{1.0, 0.0, 0.0, 0.0};
  double fov_deg = 70.0;
  glm::dvec3 forward() const { return orientation * glm::dvec3(0.0, 1.0, 0.0); }
  glm::dvec3 right() const { return orientation * glm::dvec3(1.0, 0.0, 0.0); }
  glm::dvec3 up() const { return orientation * glm::dvec3(0.0, 0.0, 1.0); }
};

// The orientation of heading, pitch and roll (deg): yaw about up by -heading, then pitch about
// the camera's right, then roll about its forward axis (positive: right side down).
glm::dquat orientation_from_angles(double heading_deg, double pitch_deg, double roll_deg);

struct CameraAngles {
  double heading_deg = 0.0;  // [0, 360); 0 when looking straight up or down
  double pitch_deg = 0.0;    // [-90, 90]
  double roll_deg = 0.0;     // (-180, 180]
};
// Inverse of orientation_from_angles for the camera whose looking direction is `forward` and
// whose image's up is `up` (perpendicular to forward; neither need be normalised).
CameraAngles angles_from_basis(const glm::dvec3& forward, const glm::dvec3& up);

// The heading and pitch of the direction from `from_m` to `to_m` (roll 0); throws InputError
// when the points coincide.
CameraAngles look_at_angles(const glm::dvec3& from_m, const glm::dvec3& to_m);

// The scene's ENU position (m) of a point at latitude, longitude (deg) and altitude_m above the
// ground. The ground is the sphere of atmosphere.planet_radius_km and the ENU frame is the
// tangent plane at the scene's location (location.lat_deg, lon_deg), its origin on the ground
// there (the frame the renderer puts the planet's centre below, planet_from_enu): a point keeps
// its altitude above the sphere, so away from the origin its up component is less than
// altitude_m (by d^2 / 2R: 7.9 m at 10 km on the earth).
glm::dvec3 enu_from_lat_lon(const Scene& scene, double lat_deg, double lon_deg, double altitude_m);

// The key of a camera (the viewer records flights so): heading, pitch and roll from the camera's
// basis, so that CameraPath::at gives the camera back (to float rounding).
CameraKey key_from_camera(double time_s, const CameraParams& camera);

class CameraPath {
 public:
  // Throws InputError naming `source_name` and the key (see above) unless there are at least two
  // keys, their times increase and every value is finite and in its range.
  explicit CameraPath(std::vector<CameraKey> keys, const std::string& source_name = "camera path");

  const std::vector<CameraKey>& keys() const { return keys_; }
  double start_s() const { return keys_.front().time_s; }  // the first key's time
  double end_s() const { return keys_.back().time_s; }     // the last key's time
  double duration_s() const { return end_s() - start_s(); }

  // The camera at path time t_s (held at the ends outside [start_s, end_s]); exactly the key at
  // a key's time.
  CameraPose pose_at(double t_s) const;
  // The same as the scene's camera: position (up at least 0), view_dir, roll_deg, fov_deg.
  CameraParams at(double t_s) const;

 private:
  glm::dvec3 position_at(size_t segment, double s) const;
  std::vector<CameraKey> keys_;
  std::vector<double> knots_;        // the spline's knot of each key: sqrt(distance) spacing
  std::vector<double> knot_slopes_;  // d knot / d time at each key (Fritsch-Carlson)
};

// Parses a path file's text. `scene` places lat/lon keys (enu_from_lat_lon) and gives the
// field of view of keys without one. Throws InputError: "path.toml: key[1]: ...".
CameraPath parse_camera_path(std::string_view toml, const std::string& source_name,
                             const Scene& scene);

// Reads and parses a path file (a regular file of at most 1 MiB).
CameraPath load_camera_path(const std::string& path, const Scene& scene);

// The path as TOML: every key with time_s, position_m, heading_deg, pitch_deg, roll_deg and
// fov_deg, numbers written so that parse_camera_path reads back the same keys exactly.
std::string camera_path_to_toml(const CameraPath& path);

}  // namespace nephele

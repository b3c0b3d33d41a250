// nephele — camera paths: keys, interpolation, the path file (TOML) and its writer.
#include "nephele/camera_path.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>

#include "nephele/error.h"
#include "render/frame_params.h"
#include "scene/scene_fields.h"

namespace nephele {
namespace {

using scene_detail::format_double;

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
constexpr double kMaxTimeS = 1.0e6;            // as the scene's time_s
constexpr double kMaxCameraDistanceM = 1.0e9;  // as camera.position_m

double radians(double degrees) {
  return degrees / kDegPerRad;
}

// "(1, 2, 3)". (Appended piece by piece: GCC 12 warns falsely about "(" + a + ...).
std::string vector_text(const glm::dvec3& v) {
  std::string text = "(";
  for (int c = 0; c < 3; ++c) text.append(c ? ", " : "").append(format_double(v[c]));
  return text.append(")");
}

// --------------------------------------------------------------------------- key checks

// Throws InputError "source: key[i].name = value: what".
class KeyChecker {
 public:
  explicit KeyChecker(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(size_t key, const std::string& what) const {
    throw InputError(source_ + ": key[" + std::to_string(key) + "]" + what);
  }
  [[noreturn]] void fail(size_t key, const std::string& name, const std::string& value,
                         const std::string& what) const {
    fail(key, "." + name + " = " + shorten_for_message(value) + ": " + what);
  }

  // A finite number in [min, max] (or [min, max) when max_open).
  void in_range(size_t key, const std::string& name, double value, double min, double max,
                bool max_open = false) const {
    if (!std::isfinite(value)) fail(key, name, format_double(value), "must be a finite number");
    if (value < min || (max_open ? value >= max : value > max))
      fail(
          key, name, format_double(value),
          "must be in [" + format_double(min) + ", " + format_double(max) + (max_open ? ")" : "]"));
  }

  // A camera position: as validate_scene checks camera.position_m.
  void position(size_t key, const std::string& name, const glm::dvec3& p) const {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail(key, name, vector_text(p), "must be finite");
    if (std::abs(p.x) > kMaxCameraDistanceM || std::abs(p.y) > kMaxCameraDistanceM)
      fail(key, name, vector_text(p),
           "east and north must be in [-1e+09, 1e+09] m (as camera.position_m)");
    if (p.z < 0.0)
      fail(key, name, vector_text(p), "the up component must be >= 0 (below the ground)");
    if (p.z > kMaxCameraDistanceM)
      fail(key, name, vector_text(p), "the up component must be at most 1e+09 m");
  }

  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

void check_keys(const std::vector<CameraKey>& keys, const KeyChecker& check) {
  if (keys.size() < 2)
    throw InputError(check.source() + ": " + std::to_string(keys.size()) +
                     (keys.size() == 1 ? " key" : " keys") +
                     ": a camera path needs at least 2 keys ([[key]] tables)");
  for (size_t i = 0; i < keys.size(); ++i) {
    const CameraKey& k = keys[i];
    check.in_range(i, "time_s", k.time_s, -kMaxTimeS, kMaxTimeS);
    if (i > 0 && !(k.time_s > keys[i - 1].time_s))
      check.fail(i, "time_s", format_double(k.time_s),
                 "must be greater than key[" + std::to_string(i - 1) +
                     "].time_s = " + format_double(keys[i - 1].time_s));
    check.position(i, "position_m", k.position_m);
    check.in_range(i, "heading_deg", k.heading_deg, -360.0, 360.0);
    check.in_range(i, "pitch_deg", k.pitch_deg, -90.0, 90.0);
    check.in_range(i, "roll_deg", k.roll_deg, -180.0, 180.0);
    check.in_range(i, "fov_deg", k.fov_deg, 0.01, 180.0, true);
  }
}

// --------------------------------------------------------------------------- interpolation

// Barry and Goldman's pyramidal form of the Catmull-Rom segment between p1 and p2 with knots
// t0 < t1 = 0 < t2 < t3, at u in [0, t2]: two levels of linear interpolation between knots
// (A, B), then one between t1 and t2.
glm::dvec3 barry_goldman(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2,
                         const glm::dvec3& p3, double t0, double t2, double t3, double u) {
  const double t1 = 0.0;
  const glm::dvec3 a1 = ((t1 - u) * p0 + (u - t0) * p1) / (t1 - t0);
  const glm::dvec3 a2 = ((t2 - u) * p1 + (u - t1) * p2) / (t2 - t1);
  const glm::dvec3 a3 = ((t3 - u) * p2 + (u - t2) * p3) / (t3 - t2);
  const glm::dvec3 b1 = ((t2 - u) * a1 + (u - t0) * a2) / (t2 - t0);
  const glm::dvec3 b2 = ((t3 - u) * a2 + (u - t1) * a3) / (t3 - t1);
  return ((t2 - u) * b1 + (u - t1) * b2) / (t2 - t1);
}

// Centripetal knot spacing (alpha = 1/2): the square root of the distance.
double knot_spacing(const glm::dvec3& a, const glm::dvec3& b) {
  return std::sqrt(glm::distance(a, b));
}

// The cubic Hermite interpolant on [0, 1] of values v0, v1 and slopes (per unit s) d0, d1.
double hermite(double v0, double v1, double d0, double d1, double s) {
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * v0 + (s3 - 2 * s2 + s) * d0 + (-2 * s3 + 3 * s2) * v1 +
         (s3 - s2) * d1;
}

}  // namespace

// --------------------------------------------------------------------------- orientation

glm::dquat orientation_from_angles(double heading_deg, double pitch_deg, double roll_deg) {
  const glm::dquat yaw = glm::angleAxis(-radians(heading_deg), glm::dvec3(0.0, 0.0, 1.0));
  const glm::dquat pitch = glm::angleAxis(radians(pitch_deg), glm::dvec3(1.0, 0.0, 0.0));
  const glm::dquat roll = glm::angleAxis(radians(roll_deg), glm::dvec3(0.0, 1.0, 0.0));
  return yaw * pitch * roll;
}

CameraAngles angles_from_basis(const glm::dvec3& forward, const glm::dvec3& up) {
  const glm::dvec3 f = glm::normalize(forward);
  CameraAngles a;
  a.pitch_deg = std::asin(std::clamp(f.z, -1.0, 1.0)) * kDegPerRad;
  if (f.x != 0.0 || f.y != 0.0) {
    a.heading_deg = std::atan2(f.x, f.y) * kDegPerRad;
    if (a.heading_deg < 0.0) a.heading_deg += 360.0;
  }
  // The roll turns the unrolled camera's up (roll 0) towards its right.
  const glm::dquat unrolled = orientation_from_angles(a.heading_deg, a.pitch_deg, 0.0);
  const glm::dvec3 u = up - glm::dot(up, f) * f;
  a.roll_deg = std::atan2(glm::dot(u, unrolled * glm::dvec3(1.0, 0.0, 0.0)),
                          glm::dot(u, unrolled * glm::dvec3(0.0, 0.0, 1.0))) *
               kDegPerRad;
  return a;
}

CameraAngles look_at_angles(const glm::dvec3& from_m, const glm::dvec3& to_m) {
  const glm::dvec3 d = to_m - from_m;
  if (!(glm::length(d) > 0.0))
    throw InputError("look_at_m " + vector_text(to_m) + ": is the camera's position");
  CameraAngles a;
  a.heading_deg = std::atan2(d.x, d.y) * kDegPerRad;
  if (a.heading_deg < 0.0) a.heading_deg += 360.0;
  a.pitch_deg = std::atan2(d.z, std::hypot(d.x, d.y)) * kDegPerRad;
  return a;
}

// Points on the sphere of radius R (planet centre at the origin, z through the north pole, x
// through longitude 0): g(lat, lon) = (cos lat cos lon, cos lat sin lon, sin lat). The ENU axes
// at the scene's location are east = (-sin lon0, cos lon0, 0), north = (-sin lat0 cos lon0,
// -sin lat0 sin lon0, cos lat0), up = g(lat0, lon0), the origin R up; a point (R + h) g(lat, lon)
// is at ((R + h) g - R up) in them.
glm::dvec3 enu_from_lat_lon(const Scene& scene, double lat_deg, double lon_deg, double altitude_m) {
  const double r_m = double(scene.atmosphere.planet_radius_km) * 1000.0;
  const double lat0 = radians(scene.location.lat_deg), lon0 = radians(scene.location.lon_deg);
  const double lat = radians(lat_deg), lon = radians(lon_deg);
  const glm::dvec3 east(-std::sin(lon0), std::cos(lon0), 0.0);
  const glm::dvec3 north(-std::sin(lat0) * std::cos(lon0), -std::sin(lat0) * std::sin(lon0),
                         std::cos(lat0));
  const glm::dvec3 up(std::cos(lat0) * std::cos(lon0), std::cos(lat0) * std::sin(lon0),
                      std::sin(lat0));
  const glm::dvec3 point =
      (r_m + altitude_m) *
      glm::dvec3(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
  const glm::dvec3 offset = point - r_m * up;
  return {glm::dot(offset, east), glm::dot(offset, north), glm::dot(offset, up)};
}

CameraKey key_from_camera(double time_s, const CameraParams& camera) {
  const CameraBasis basis = camera_basis(camera);
  const CameraAngles angles = angles_from_basis(glm::dvec3(basis.forward), glm::dvec3(basis.up));
  CameraKey key;
  key.time_s = time_s;
  key.position_m = glm::dvec3(camera.position_m);
  key.heading_deg = angles.heading_deg;
  key.pitch_deg = angles.pitch_deg;
  key.roll_deg = angles.roll_deg;
  key.fov_deg = camera.fov_deg;
  return key;
}

// --------------------------------------------------------------------------- CameraPath

CameraPath::CameraPath(std::vector<CameraKey> keys, const std::string& source_name)
    : keys_(std::move(keys)) {
  check_keys(keys_, KeyChecker(shorten_path_for_message(source_name)));
  const size_t n = keys_.size();
  knots_.assign(n, 0.0);
  for (size_t i = 1; i < n; ++i)
    knots_[i] = knots_[i - 1] + knot_spacing(keys_[i - 1].position_m, keys_[i].position_m);
  // Knot against time: a monotone piecewise cubic through (time_s, knot) with Fritsch-Carlson
  // slopes (the weighted harmonic mean of the neighbouring secants, PCHIP; 0 where a key
  // stands still), so the spline's parameter, and with it the camera's velocity, is
  // continuous in time across keys.
  std::vector<double> h(n - 1), secant(n - 1);
  for (size_t i = 0; i + 1 < n; ++i) {
    h[i] = keys_[i + 1].time_s - keys_[i].time_s;
    secant[i] = (knots_[i + 1] - knots_[i]) / h[i];
  }
  knot_slopes_.assign(n, 0.0);
  knot_slopes_.front() = secant.front();
  knot_slopes_.back() = secant.back();
  for (size_t i = 1; i + 1 < n; ++i) {
    if (secant[i - 1] <= 0.0 || secant[i] <= 0.0) continue;
    const double w1 = 2.0 * h[i] + h[i - 1], w2 = h[i] + 2.0 * h[i - 1];
    knot_slopes_[i] = (w1 + w2) / (w1 / secant[i - 1] + w2 / secant[i]);
  }
}

// The spline between keys `segment` and segment + 1, `u` knot units from the segment's start.
// The end segments reflect their missing neighbour (2 p1 - p2); so does a segment whose
// neighbour stands on its end point (a key where the camera stops).
glm::dvec3 CameraPath::position_at(size_t segment, double u) const {
  const glm::dvec3& p1 = keys_[segment].position_m;
  const glm::dvec3& p2 = keys_[segment + 1].position_m;
  const double d12 = knots_[segment + 1] - knots_[segment];
  if (!(d12 > 0.0)) return p1;  // the camera stands still
  glm::dvec3 p0 = 2.0 * p1 - p2, p3 = 2.0 * p2 - p1;
  if (segment > 0 && keys_[segment - 1].position_m != p1) p0 = keys_[segment - 1].position_m;
  if (segment + 2 < keys_.size() && keys_[segment + 2].position_m != p2)
    p3 = keys_[segment + 2].position_m;
  const double t0 = -knot_spacing(p0, p1), t2 = d12, t3 = d12 + knot_spacing(p2, p3);
  return barry_goldman(p0, p1, p2, p3, t0, t2, t3, std::clamp(u, 0.0, d12));
}

CameraPose CameraPath::pose_at(double t_s) const {
  const auto pose_of = [](const CameraKey& k) {
    return CameraPose{k.position_m, orientation_from_angles(k.heading_deg, k.pitch_deg, k.roll_deg),
                      k.fov_deg};
  };
  if (!(t_s > start_s())) return pose_of(keys_.front());
  if (!(t_s < end_s())) return pose_of(keys_.back());
  // The segment: the last key at or before t_s.
  const auto after = std::upper_bound(keys_.begin(), keys_.end(), t_s,
                                      [](double t, const CameraKey& k) { return t < k.time_s; });
  const size_t i = size_t(after - keys_.begin()) - 1;
  const CameraKey &a = keys_[i], &b = keys_[i + 1];
  if (t_s == a.time_s) return pose_of(a);
  const double h = b.time_s - a.time_s;
  const double s = (t_s - a.time_s) / h;
  const double u =
      hermite(0.0, knots_[i + 1] - knots_[i], knot_slopes_[i] * h, knot_slopes_[i + 1] * h, s);
  CameraPose pose;
  pose.position_m = position_at(i, u);
  glm::dquat qa = orientation_from_angles(a.heading_deg, a.pitch_deg, a.roll_deg);
  glm::dquat qb = orientation_from_angles(b.heading_deg, b.pitch_deg, b.roll_deg);
  if (glm::dot(qa, qb) < 0.0) qb = -qb;  // q and -q are the same turn: take the shorter arc
  pose.orientation = glm::normalize(glm::slerp(qa, qb, s));
  pose.fov_deg = a.fov_deg + s * (b.fov_deg - a.fov_deg);
  return pose;
}

CameraParams CameraPath::at(double t_s) const {
  const CameraPose pose = pose_at(t_s);
  CameraParams camera;
  // A spline between keys on the ground may dip below it by rounding; the camera stays on it.
  camera.position_m =
      glm::vec3(glm::dvec3(pose.position_m.x, pose.position_m.y, std::max(pose.position_m.z, 0.0)));
  camera.view_dir = glm::vec3(pose.forward());
  // The roll relative to the renderer's unrolled basis for this view_dir (camera_basis).
  const CameraBasis unrolled = camera_basis(camera.view_dir);
  const glm::dvec3 up = pose.up();
  camera.roll_deg = float(
      std::atan2(glm::dot(up, glm::dvec3(unrolled.right)), glm::dot(up, glm::dvec3(unrolled.up))) *
      kDegPerRad);
  camera.fov_deg = float(pose.fov_deg);
  return camera;
}

// --------------------------------------------------------------------------- the path file

namespace {

constexpr const char* kAllowedKeys =
    "time_s, position_m, lat_deg, lon_deg, altitude_m, heading_deg, pitch_deg, roll_deg, "
    "look_at_m, fov_deg";

// One-line rendering of a TOML value for messages: "abc", 3, [1, 2], {...}.
std::string describe(const toml::node& node) {
  if (const auto* s = node.as_string()) return scene_detail::toml_quote(s->get());
  if (const auto* i = node.as_integer()) return std::to_string(i->get());
  if (const auto* f = node.as_floating_point()) return format_double(f->get());
  if (const auto* b = node.as_boolean()) return b->get() ? "true" : "false";
  if (const auto* a = node.as_array()) {
    std::string text = "[";
    for (size_t i = 0; i < a->size(); ++i) text += (i ? ", " : "") + describe(*a->get(i));
    return text + "]";
  }
  if (node.is_table()) return "{...}";
  return "a date or time";
}

class PathReader {
 public:
  PathReader(const std::string& source, const Scene& scene)
      : check_(shorten_path_for_message(source)), scene_(scene) {}

  CameraPath read(std::string_view text) const {
    if (int line = scene_detail::line_of_too_deep_key(text))
      throw InputError(check_.source() + ":" + std::to_string(line) + ": a key with more than " +
                       std::to_string(scene_detail::kMaxKeyParts) + " dotted parts");
    toml::table root;
    try {
      root = toml::parse(text, check_.source());
    } catch (const toml::parse_error& error) {
      const toml::source_position at = error.source().begin;
      throw InputError(check_.source() + ":" + std::to_string(at.line) + ":" +
                       std::to_string(at.column) + ": malformed TOML: " +
                       one_line_for_message(error.description()));
    }
    for (const auto& [name, node] : root)
      if (name.str() != "key")
        throw InputError(check_.source() + ": unknown key '" + shorten_for_message(name.str()) +
                         "' (a camera path has only [[key]] tables)");
    const toml::node* list = root.get("key");
    const toml::array* array = list ? list->as_array() : nullptr;
    if (list && (!array || !array->is_array_of_tables()))
      throw InputError(check_.source() + ": key = " + shorten_for_message(describe(*list)) +
                       ": expected [[key]] tables");
    std::vector<CameraKey> keys;
    if (array)
      for (size_t i = 0; i < array->size(); ++i)
        keys.push_back(read_key(i, *array->get(i)->as_table()));
    return CameraPath(std::move(keys), check_.source());
  }

 private:
  [[noreturn]] void fail_value(size_t key, const std::string& name, const toml::node& node,
                               const std::string& what) const {
    check_.fail(key, name, describe(node), what);
  }

  double number(size_t key, const toml::table& table, const std::string& name) const {
    const toml::node& node = *table.get(name);
    if (const auto* i = node.as_integer()) return double(i->get());
    if (const auto* f = node.as_floating_point()) return f->get();
    fail_value(key, name, node, "expected a number");
  }

  std::optional<double> optional_number(size_t key, const toml::table& table,
                                        const std::string& name) const {
    if (!table.contains(name)) return std::nullopt;
    return number(key, table, name);
  }

  glm::dvec3 vector3(size_t key, const toml::table& table, const std::string& name) const {
    const toml::node& node = *table.get(name);
    const toml::array* a = node.as_array();
    if (!a || a->size() != 3 ||
        !std::all_of(a->begin(), a->end(), [](const toml::node& n) { return n.is_number(); }))
      fail_value(key, name, node, "expected an array of 3 numbers [east, north, up]");
    glm::dvec3 v;
    for (int c = 0; c < 3; ++c) {
      const toml::node& item = *a->get(size_t(c));
      v[c] = item.is_integer() ? double(item.as_integer()->get()) : item.as_floating_point()->get();
    }
    return v;
  }

  CameraKey read_key(size_t i, const toml::table& table) const {
    for (const auto& [name, node] : table) {
      const std::string_view n = name.str();
      if (!is_allowed(n))
        check_.fail(
            i, ": unknown key '" + shorten_for_message(n) + "' (allowed: " + kAllowedKeys + ")");
    }
    CameraKey key;
    if (!table.contains("time_s")) check_.fail(i, ": time_s is missing");
    key.time_s = number(i, table, "time_s");
    key.position_m = read_position(i, table);
    read_orientation(i, table, key);
    key.fov_deg = optional_number(i, table, "fov_deg").value_or(vertical_fov_deg(scene_));
    return key;
  }

  static bool is_allowed(std::string_view name) {
    for (std::string_view allowed :
         {"time_s", "position_m", "lat_deg", "lon_deg", "altitude_m", "heading_deg", "pitch_deg",
          "roll_deg", "look_at_m", "fov_deg"})
      if (name == allowed) return true;
    return false;
  }

  glm::dvec3 read_position(size_t i, const toml::table& table) const {
    const bool enu = table.contains("position_m");
    const int geo = int(table.contains("lat_deg")) + int(table.contains("lon_deg")) +
                    int(table.contains("altitude_m"));
    if (enu && geo > 0)
      check_.fail(i, ": position_m and lat_deg/lon_deg/altitude_m are both given; give one form");
    if (enu) return vector3(i, table, "position_m");
    if (geo == 0)
      check_.fail(i,
                  ": no position: give position_m = [east, north, up] or lat_deg, lon_deg "
                  "and altitude_m");
    for (const char* name : {"lat_deg", "lon_deg", "altitude_m"})
      if (!table.contains(name))
        check_.fail(i, std::string(": ") + name +
                           " is missing (lat_deg, lon_deg and altitude_m go together)");
    const double lat = number(i, table, "lat_deg"), lon = number(i, table, "lon_deg"),
                 altitude = number(i, table, "altitude_m");
    check_.in_range(i, "lat_deg", lat, -90.0, 90.0);
    check_.in_range(i, "lon_deg", lon, -180.0, 360.0);
    check_.in_range(i, "altitude_m", altitude, 0.0, kMaxCameraDistanceM);
    const glm::dvec3 p = enu_from_lat_lon(scene_, lat, lon, altitude);
    if (p.z < 0.0)
      check_.fail(i, "altitude_m", format_double(altitude),
                  "at lat_deg " + format_double(lat) + ", lon_deg " + format_double(lon) +
                      " the point is " + format_double(-p.z) +
                      " m below the ground plane of the scene's location (ENU up must be >= 0)");
    return p;
  }

  void read_orientation(size_t i, const toml::table& table, CameraKey& key) const {
    const bool heading = table.contains("heading_deg"), pitch = table.contains("pitch_deg");
    const bool look_at = table.contains("look_at_m");
    if (look_at && (heading || pitch))
      check_.fail(i, ": heading_deg/pitch_deg and look_at_m are both given; give one form");
    key.roll_deg = optional_number(i, table, "roll_deg").value_or(0.0);
    if (look_at) {
      const glm::dvec3 target = vector3(i, table, "look_at_m");
      if (target == key.position_m)
        check_.fail(i, "look_at_m", vector_text(target), "is the key's position");
      const CameraAngles angles = look_at_angles(key.position_m, target);
      if (!std::isfinite(angles.heading_deg) || !std::isfinite(angles.pitch_deg))
        check_.fail(i, "look_at_m", vector_text(target), "must be finite");
      key.heading_deg = angles.heading_deg;
      key.pitch_deg = angles.pitch_deg;
      return;
    }
    if (!heading && !pitch)
      check_.fail(i, ": no orientation: give heading_deg and pitch_deg, or look_at_m");
    if (!heading || !pitch)
      check_.fail(i, std::string(": ") + (heading ? "pitch_deg" : "heading_deg") +
                         " is missing (heading_deg and pitch_deg go together; or give look_at_m)");
    key.heading_deg = number(i, table, "heading_deg");
    key.pitch_deg = number(i, table, "pitch_deg");
  }

  KeyChecker check_;
  const Scene& scene_;
};

// A TOML float that reads back as exactly `value`: the shortest round-trip digits, with ".0"
// where they would read as an integer.
std::string toml_double(double value) {
  std::string text = format_double(value);
  if (text.find_first_of(".eni") == std::string::npos) text += ".0";
  return text;
}

}  // namespace

CameraPath parse_camera_path(std::string_view toml, const std::string& source_name,
                             const Scene& scene) {
  return PathReader(source_name, scene).read(toml);
}

CameraPath load_camera_path(const std::string& path, const Scene& scene) {
  return parse_camera_path(
      scene_detail::read_small_text_file(path, "camera path", "it is larger than 1 MiB"), path,
      scene);
}

std::string camera_path_to_toml(const CameraPath& path) {
  std::string out =
      "# nephele camera path: keys in time order; position_m east, north, up (m), heading from "
      "north through east, pitch up, roll clockwise (deg)\n";
  for (const CameraKey& k : path.keys()) {
    out += "\n[[key]]\n";
    out += "time_s = " + toml_double(k.time_s) + "\n";
    out += "position_m = [" + toml_double(k.position_m.x) + ", " + toml_double(k.position_m.y) +
           ", " + toml_double(k.position_m.z) + "]\n";
    out += "heading_deg = " + toml_double(k.heading_deg) + "\n";
    out += "pitch_deg = " + toml_double(k.pitch_deg) + "\n";
    out += "roll_deg = " + toml_double(k.roll_deg) + "\n";
    out += "fov_deg = " + toml_double(k.fov_deg) + "\n";
  }
  return out;
}

}  // namespace nephele

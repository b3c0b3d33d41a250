// nephele — film output: the layers of a still in one EXR with its camera, place, time and
// exposure in the header (nephele/film.h).
#include "nephele/film.h"

#include <cmath>
#include <cstdio>

#include "nephele/camera_path.h"
#include "nephele/exposure.h"
#include "nephele/version.h"
#include "render/frame_params.h"

namespace nephele {

namespace {

std::string vector_text(const glm::vec3& v) {
  char text[96];
  std::snprintf(text, sizeof text, "%.9g %.9g %.9g", v.x, v.y, v.z);
  return text;
}

// OpenEXR's worldToCamera (row vectors, p_camera = p_world M): camera space is left-handed,
// x right and y up in the image, z the viewing direction, the origin at the camera.
std::array<float, 16> world_to_camera(const CameraParams& camera) {
  const CameraBasis b = camera_basis(camera);
  const glm::vec3 axes[3] = {b.right, b.up, glm::normalize(b.forward)};
  std::array<float, 16> m{};
  for (int column = 0; column < 3; ++column) {
    for (int row = 0; row < 3; ++row) m[size_t(row * 4 + column)] = axes[column][row];
    m[size_t(12 + column)] = -glm::dot(camera.position_m, axes[column]);
  }
  m[15] = 1.0f;
  return m;
}

}  // namespace

Image film_beauty(const FilmLayers& layers, bool holdout) {
  if (!holdout) return layers.frame.color;
  Image out(layers.sky.width, layers.sky.height);
  for (size_t i = 0; i < out.pixels.size(); ++i) {
    const float visible = 1.0f - layers.clouds.pixels[i].a;  // the sky's share seen through
    out.pixels[i] = glm::vec4(glm::vec3(layers.sky.pixels[i]) * visible, visible);
  }
  return out;
}

ExrAttributes film_exr_attributes(const Scene& scene, const FrameStats& stats,
                                  const FilmExrOptions& options) {
  ExrAttributes a;
  const CameraKey angles = key_from_camera(0.0, scene.camera);
  const float aspect = float(scene.output.width) / float(scene.output.height);
  const float vertical = vertical_fov_deg(scene);
  const float horizontal =
      float(2.0 * std::atan(std::tan(double(vertical) * M_PI / 360.0) * aspect) * 180.0 / M_PI);
  a.strings = {
      {"software", std::string("nephele ") + kVersion},
      {"nephele.units",
       "cd/m^2 per channel, linear Rec.709, exposure not applied; clouds.depth_m in metres"},
      {"nephele.layers",
       "R,G,B,A = clouds over sky" + std::string(options.holdout ? " with the clouds held out: "
                                                                    "(1 - clouds.A) sky, A = 1 - clouds.A"
                                                                  : "") +
           "; sky = everything behind the clouds; clouds = premultiplied, A = 1 - "
           "transmittance, with the haze in front of them; clouds.depth_m = opacity-weighted "
           "distance (0: no cloud); R,G,B = clouds.RGB + (1 - clouds.A) sky.RGB"},
      {"nephele.holdout", options.holdout ? "true" : "false"},
      {"nephele.camera.position_m", vector_text(scene.camera.position_m)},
      {"nephele.camera.view_dir", vector_text(glm::normalize(scene.camera.view_dir))},
      {"nephele.frame", "x east, y north, z up (m); azimuths from north through east"},
      {"nephele.time", scene.time.empty() ? "none" : scene.time},
      {"nephele.exposure_mode", scene.output.auto_exposure ? "auto" : "manual"},
  };
  a.floats = {
      {"nephele.camera.heading_deg", float(angles.heading_deg)},
      {"nephele.camera.pitch_deg", float(angles.pitch_deg)},
      {"nephele.camera.roll_deg", scene.camera.roll_deg},
      {"nephele.fov_vertical_deg", vertical},
      {"nephele.fov_horizontal_deg", horizontal},
      {"nephele.time_s", scene.time_s},
      {"nephele.sun.illuminance_lux", scene.sun.illuminance_lux},
      {"nephele.sun.elevation_deg", float(stats.sun.elevation_deg)},
      {"nephele.sun.azimuth_deg", float(stats.sun.azimuth_deg)},
      {"nephele.ev100", float(options.ev100)},
      // What multiplies the layers' cd/m^2 before the tone map: 1 / (1.2 2^EV100).
      {"nephele.exposure", float(exposure_from_ev100(options.ev100))},
      // OpenEXR's standard attributes (ImfStandardAttributes.h).
      {"latitude", scene.location.lat_deg},
      {"longitude", scene.location.lon_deg},
      {"altitude", scene.location.altitude_m + scene.camera.position_m.z},
  };
  if (scene.camera.focal_length_mm > 0.0f) {
    a.floats.push_back({"nephele.camera.focal_length_mm", scene.camera.focal_length_mm});
    a.floats.push_back({"nephele.camera.sensor_width_mm", scene.camera.sensor_width_mm});
  }
  a.matrices = {{"worldToCamera", world_to_camera(scene.camera)}};
  return a;
}

void write_film_exr(const FilmLayers& layers, const Scene& scene, const std::string& path,
                    const FilmExrOptions& options) {
  const Image beauty = film_beauty(layers, options.holdout);
  write_exr_layers({{"", &beauty, 4, {}},
                    {"sky", &layers.sky, 3, {}},
                    {"clouds", &layers.clouds, 4, {}},
                    {"clouds", &layers.clouds_depth_m, 1, {"depth_m"}}},
                   path, options.pixels, film_exr_attributes(scene, layers.frame.stats, options));
}

}  // namespace nephele

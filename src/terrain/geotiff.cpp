#include "terrain/geotiff.h"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "nephele/camera_path.h"
#include "nephele/error.h"

namespace nephele::terrain {
namespace {

[[noreturn]] void fail(const std::string& key, const std::string& path, const std::string& why) {
  throw InputError(key + " '" + shorten_path_for_message(path) + "': " + why);
}

// GDAL's messages while one of these lives are kept, not printed (GDAL writes "ERROR 1: ..."
// lines to stderr by default): a refusal is nephele's one line, quoting the last error.
class GdalMessages {
 public:
  GdalMessages() { CPLPushErrorHandlerEx(&GdalMessages::keep, this); }
  ~GdalMessages() { CPLPopErrorHandler(); }
  GdalMessages(const GdalMessages&) = delete;
  GdalMessages& operator=(const GdalMessages&) = delete;
  // " (GDAL: the last error)", or "" when there was none.
  std::string last() const {
    return last_.empty() ? "" : " (GDAL: " + shorten_for_message(one_line_for_message(last_)) + ")";
  }

 private:
  static void CPL_STDCALL keep(CPLErr level, CPLErrorNum, const char* message) {
    auto* self = static_cast<GdalMessages*>(CPLGetErrorHandlerUserData());
    if (self && level >= CE_Failure && message) self->last_ = message;
  }
  std::string last_;
};

struct Closer {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};
using Dataset = std::unique_ptr<GDALDataset, Closer>;

// The latitude and longitude (deg) of the ground point whose ENU east and north (the tangent
// plane's coordinates, camera_path.h's enu_from_lat_lon) are e, n: the exact inverse.
glm::dvec2 lat_lon_from_enu(const Scene& scene, double e, double n) {
  const double r = double(scene.atmosphere.planet_radius_km) * 1000.0;
  const double lat0 = glm::radians(double(scene.location.lat_deg));
  const double lon0 = glm::radians(double(scene.location.lon_deg));
  const glm::dvec3 east(-std::sin(lon0), std::cos(lon0), 0.0);
  const glm::dvec3 north(-std::sin(lat0) * std::cos(lon0), -std::sin(lat0) * std::sin(lon0), std::cos(lat0));
  const glm::dvec3 up(std::cos(lat0) * std::cos(lon0), std::cos(lat0) * std::sin(lon0), std::sin(lat0));
  const double u = std::sqrt(std::max(r * r - e * e - n * n, 0.0));
  const glm::dvec3 p = e * east + n * north + u * up;
  return {glm::degrees(std::asin(std::clamp(p.z / r, -1.0, 1.0))), glm::degrees(std::atan2(p.y, p.x))};
}

// The file opened read-only (GDAL's messages are kept by the caller's GdalMessages).
Dataset open(const std::string& path) {
  GDALAllRegister();
  return Dataset(static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_ReadOnly)));
}

// The file's coordinate system and WGS84 (longitude, latitude), both ways.
struct Transforms {
  std::unique_ptr<OGRCoordinateTransformation> to_file, to_geo;
};

Transforms transforms(const OGRSpatialReference& srs) {
  OGRSpatialReference wgs84;
  wgs84.SetWellKnownGeogCS("WGS84");
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // longitude, latitude
  OGRSpatialReference file_srs(srs);
  file_srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return {std::unique_ptr<OGRCoordinateTransformation>(OGRCreateCoordinateTransformation(&wgs84, &file_srs)),
          std::unique_ptr<OGRCoordinateTransformation>(OGRCreateCoordinateTransformation(&file_srs, &wgs84))};
}

// The point at fractions f of the raster's width and height, in the file's coordinates.
glm::dvec2 raster_point(const double gt[6], int w, int h, glm::dvec2 f) {
  return {gt[0] + f.x * w * gt[1] + f.y * h * gt[2], gt[3] + f.x * w * gt[4] + f.y * h * gt[5]};
}

// Points along the raster's border, as fractions of its width and height.
std::vector<glm::dvec2> border_fractions() {
  std::vector<glm::dvec2> out;
  for (int i = 0; i <= 64; ++i)
    for (const glm::dvec2 f : {glm::dvec2(i / 64.0, 0.0), glm::dvec2(i / 64.0, 1.0), glm::dvec2(0.0, i / 64.0),
                               glm::dvec2(1.0, i / 64.0)})
      out.push_back(f);
  return out;
}

std::string range_text(double lo, double hi) {
  return "[" + number_for_message(lo) + ", " + number_for_message(hi) + "]";
}

// A geographic raster's own coordinates must lie on the globe: PROJ would wrap a latitude of 95
// to 85 and place the model on the other side of the pole.
std::string geographic_extent_problem(const OGRSpatialReference& srs, const double gt[6], int w, int h) {
  const double deg = srs.GetAngularUnits() * 180.0 / M_PI;
  double lon_lo = HUGE_VAL, lon_hi = -HUGE_VAL, lat_lo = HUGE_VAL, lat_hi = -HUGE_VAL;
  for (const glm::dvec2 f : {glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(0, 1), glm::dvec2(1, 1)}) {
    const glm::dvec2 p = raster_point(gt, w, h, f) * deg;
    lon_lo = std::min(lon_lo, p.x), lon_hi = std::max(lon_hi, p.x);
    lat_lo = std::min(lat_lo, p.y), lat_hi = std::max(lat_hi, p.y);
  }
  constexpr double kSlack = 1e-9;
  if (lat_lo < -90.0 - kSlack || lat_hi > 90.0 + kSlack)
    return "spans latitudes " + range_text(lat_lo, lat_hi) + ", beyond a pole; latitudes must be in [-90, 90]";
  if (lon_lo < -360.0 - kSlack || lon_hi > 360.0 + kSlack || lon_hi - lon_lo > 360.0 + kSlack)
    return "spans longitudes " + range_text(lon_lo, lon_hi) +
           "; longitudes must be in [-360, 360] and span at most 360 degrees";
  return "";
}

std::string extent_problem(const OGRSpatialReference& srs, const double gt[6], int w, int h) {
  for (int k = 0; k < 6; ++k)
    if (!std::isfinite(gt[k])) return "its geotransform holds a value that is not finite";
  if (!(std::abs(gt[1] * gt[5] - gt[2] * gt[4]) > 0.0))
    return "its geotransform is degenerate (its pixels have no area)";
  if (srs.IsGeographic())
    if (std::string why = geographic_extent_problem(srs, gt, w, h); !why.empty()) return why;
  const Transforms t = transforms(srs);
  if (!t.to_file || !t.to_geo) return "its coordinate system cannot be converted to WGS84 latitude and longitude";
  for (const glm::dvec2 f : border_fractions()) {
    glm::dvec2 p = raster_point(gt, w, h, f);
    if (!t.to_geo->Transform(1, &p.x, &p.y) || !std::isfinite(p.x) || !std::isfinite(p.y) ||
        std::abs(p.y) > 90.0 + 1e-6)
      return "a point of its border cannot be placed in latitude and longitude";
  }
  return "";
}

std::string problem_of(GDALDataset* data, const GdalMessages& messages) {
  if (!data) return "cannot read the GeoTIFF" + messages.last();
  if (data->GetRasterCount() < 1) return "holds no raster band of heights";
  double gt[6];
  if (data->GetGeoTransform(gt) != CE_None || !data->GetSpatialRef())
    return "has no georeferencing (a geotransform and a coordinate system are needed to place it; "
           "a plain heightfield is a 16-bit PNG or an EXR with --terrain-extent-m)";
  const int w = data->GetRasterXSize(), h = data->GetRasterYSize();
  if (w < 2 || h < 2 || w > kMaxSide || h > kMaxSide)
    return std::to_string(w) + " x " + std::to_string(h) + " points: from 2 x 2 to " + std::to_string(kMaxSide) +
           " a side are allowed (resample it smaller)";
  return extent_problem(*data->GetSpatialRef(), gt, w, h);
}

// The model's heights, no-data and non-finite values as NaN; its lowest valid height.
std::vector<float> read_heights(GDALDataset& data, const GdalMessages& messages, const std::string& key,
                                const std::string& path, float& lowest) {
  const int w = data.GetRasterXSize(), h = data.GetRasterYSize();
  GDALRasterBand* band = data.GetRasterBand(1);
  std::vector<float> dem(size_t(w) * size_t(h));
  if (band->RasterIO(GF_Read, 0, 0, w, h, dem.data(), w, h, GDT_Float32, 0, 0) != CE_None)
    fail(key, path, "cannot read its heights; the file is corrupt" + messages.last());
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  lowest = std::numeric_limits<float>::max();
  for (float& v : dem)
    if (!std::isfinite(v) || (has_nodata && double(v) == nodata)) v = std::numeric_limits<float>::quiet_NaN();
    else lowest = std::min(lowest, v);
  if (lowest == std::numeric_limits<float>::max()) fail(key, path, "holds no valid height");
  return dem;
}

}  // namespace

std::string geotiff_problem(const std::string& path) {
  const GdalMessages messages;
  const Dataset data = open(path);
  return problem_of(data.get(), messages);
}

// The footprint about the scene's location may be as large, and lie as far, as terrain.extent_m
// and terrain.center_m allow a plain heightfield.
constexpr double kMaxFootprintM = 1.0e6;

Heightfield read_geotiff(const Scene& scene, const std::string& key) {
  const std::string& path = scene.terrain.file;
  const GdalMessages messages;  // outlives the dataset: closing it may report errors too
  const Dataset data = open(path);
  if (const std::string why = problem_of(data.get(), messages); !why.empty()) fail(key, path, why);
  double gt[6];
  data->GetGeoTransform(gt);
  const int w = data->GetRasterXSize(), h = data->GetRasterYSize();
  float lowest = 0.0f;
  const std::vector<float> dem = read_heights(*data, messages, key, path, lowest);
  const Transforms t = transforms(*data->GetSpatialRef());

  // The model's outline in the scene's east-north frame: its border's points.
  glm::dvec2 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const glm::dvec2 f : border_fractions()) {
    glm::dvec2 p = raster_point(gt, w, h, f);
    if (!t.to_geo->Transform(1, &p.x, &p.y)) fail(key, path, "a point of its border cannot be placed in latitude and longitude");
    const glm::dvec3 enu = enu_from_lat_lon(scene, p.y, p.x, 0.0);
    lo = glm::min(lo, glm::dvec2(enu));
    hi = glm::max(hi, glm::dvec2(enu));
  }
  const glm::dvec2 size = hi - lo, middle = 0.5 * (lo + hi);
  if (!(size.x <= kMaxFootprintM && size.y <= kMaxFootprintM && std::abs(middle.x) <= kMaxFootprintM &&
        std::abs(middle.y) <= kMaxFootprintM))
    fail(key, path, "covers " + number_for_message(size.x / 1000.0) + " x " + number_for_message(size.y / 1000.0) +
                        " km centred " + number_for_message(glm::length(middle) / 1000.0) +
                        " km from location (lat_deg, lon_deg); at most 1000 km a side, centred within 1000 km "
                        "east and north of it, are allowed");
  double inverse[6];
  if (!GDALInvGeoTransform(gt, inverse)) fail(key, path, "its geotransform cannot be inverted");
  Heightfield field{w, h, glm::vec2(hi - lo), glm::vec2(0.5 * (lo + hi)), std::vector<float>(size_t(w) * size_t(h))};
  const float ground = scene.location.altitude_m;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const double e = lo.x + (hi.x - lo.x) * i / (w - 1), n = hi.y - (hi.y - lo.y) * j / (h - 1);
      const glm::dvec2 lat_lon = lat_lon_from_enu(scene, e, n);
      double x = lat_lon.y, y = lat_lon.x;
      float value = lowest;
      if (t.to_file->Transform(1, &x, &y)) {
        // Pixel coordinates of the point; the model's samples stand at pixel centres.
        const double px = inverse[0] + x * inverse[1] + y * inverse[2] - 0.5;
        const double py = inverse[3] + x * inverse[4] + y * inverse[5] - 0.5;
        if (px >= 0.0 && py >= 0.0 && px <= w - 1 && py <= h - 1) {
          const int x0 = std::min(int(px), w - 2), y0 = std::min(int(py), h - 2);
          const float fx = float(px - x0), fy = float(py - y0);
          const auto at = [&](int a, int b) {
            const float v = dem[size_t(b) * size_t(w) + size_t(a)];
            return std::isnan(v) ? lowest : v;
          };
          value = (at(x0, y0) * (1 - fx) + at(x0 + 1, y0) * fx) * (1 - fy) +
                  (at(x0, y0 + 1) * (1 - fx) + at(x0 + 1, y0 + 1) * fx) * fy;
        }
      }
      field.height_m[size_t(j) * size_t(w) + size_t(i)] = value - ground;
    }
  return field;
}

}  // namespace nephele::terrain

#include "terrain/geotiff.h"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "nephele/camera_path.h"
#include "nephele/error.h"

namespace nephele::terrain {
namespace {

[[noreturn]] void fail(const std::string& key, const std::string& path, const std::string& why) {
  throw InputError(key + " '" + path + "': " + why);
}

struct Closer {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};

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

// The file opened read-only, errors kept quiet (they are reported as InputErrors instead).
std::unique_ptr<GDALDataset, Closer> open(const std::string& path) {
  GDALAllRegister();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  std::unique_ptr<GDALDataset, Closer> data(static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_ReadOnly)));
  CPLPopErrorHandler();
  return data;
}

std::string problem_of(GDALDataset* data) {
  if (!data) return std::string("cannot read the GeoTIFF (") + CPLGetLastErrorMsg() + ")";
  if (data->GetRasterCount() < 1) return "holds no raster band of heights";
  double gt[6];
  if (data->GetGeoTransform(gt) != CE_None || !data->GetSpatialRef())
    return "has no georeferencing (a geotransform and a coordinate system are needed to place it; "
           "a plain heightfield is a 16-bit PNG or an EXR with --terrain-extent-m)";
  const int w = data->GetRasterXSize(), h = data->GetRasterYSize();
  if (w < 2 || h < 2 || w > kMaxSide || h > kMaxSide)
    return std::to_string(w) + " x " + std::to_string(h) + " points: from 2 x 2 to 16384 a side are allowed";
  return "";
}

}  // namespace

std::string geotiff_problem(const std::string& path) { return problem_of(open(path).get()); }

Heightfield read_geotiff(const Scene& scene, const std::string& key) {
  const std::string& path = scene.terrain.file;
  const std::unique_ptr<GDALDataset, Closer> data = open(path);
  if (const std::string why = problem_of(data.get()); !why.empty()) fail(key, path, why);
  double gt[6];
  data->GetGeoTransform(gt);
  const OGRSpatialReference* srs = data->GetSpatialRef();
  const int w = data->GetRasterXSize(), h = data->GetRasterYSize();
  GDALRasterBand* band = data->GetRasterBand(1);
  std::vector<float> dem(size_t(w) * size_t(h));
  if (band->RasterIO(GF_Read, 0, 0, w, h, dem.data(), w, h, GDT_Float32, 0, 0) != CE_None)
    fail(key, path, std::string("cannot read its heights (") + CPLGetLastErrorMsg() + ")");
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  float lowest = std::numeric_limits<float>::max();
  for (float& v : dem)
    if (!std::isfinite(v) || (has_nodata && double(v) == nodata)) v = std::numeric_limits<float>::quiet_NaN();
    else lowest = std::min(lowest, v);
  if (lowest == std::numeric_limits<float>::max()) fail(key, path, "holds no valid height");

  OGRSpatialReference wgs84;
  wgs84.SetWellKnownGeogCS("WGS84");
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // longitude, latitude
  OGRSpatialReference file_srs(*srs);
  file_srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> to_file(OGRCreateCoordinateTransformation(&wgs84, &file_srs));
  std::unique_ptr<OGRCoordinateTransformation> to_geo(OGRCreateCoordinateTransformation(&file_srs, &wgs84));
  if (!to_file || !to_geo) fail(key, path, "its coordinate system cannot be converted to WGS84 latitude and longitude");

  // The model's outline in the scene's east-north frame: its border's points.
  glm::dvec2 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (int i = 0; i <= 64; ++i)
    for (const glm::dvec2 f : {glm::dvec2(i / 64.0, 0.0), glm::dvec2(i / 64.0, 1.0), glm::dvec2(0.0, i / 64.0),
                               glm::dvec2(1.0, i / 64.0)}) {
      double x = gt[0] + f.x * w * gt[1] + f.y * h * gt[2], y = gt[3] + f.x * w * gt[4] + f.y * h * gt[5];
      if (!to_geo->Transform(1, &x, &y)) fail(key, path, "a corner of it cannot be placed in latitude and longitude");
      const glm::dvec3 enu = enu_from_lat_lon(scene, y, x, 0.0);
      lo = glm::min(lo, glm::dvec2(enu));
      hi = glm::max(hi, glm::dvec2(enu));
    }
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
      if (to_file->Transform(1, &x, &y)) {
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

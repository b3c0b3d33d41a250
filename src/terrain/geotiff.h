// A GeoTIFF elevation model (GDAL) as the scene's heightfield: resampled onto an east-north grid
// about the scene's location (location.lat_deg, lon_deg), heights above location.altitude_m.
#pragma once

#include <string>

#include "nephele/scene.h"
#include "terrain/heightfield.h"

namespace nephele::terrain {

// Why the file cannot be placed as a heightfield ("" when it can): unreadable, no raster band,
// no georeferencing, or outside 2 to kMaxSide points a side.
std::string geotiff_problem(const std::string& path);

// Throws InputError naming `key` and scene.terrain.file: unreadable, no georeferencing (no
// geotransform or no coordinate system), or too many points.
Heightfield read_geotiff(const Scene& scene, const std::string& key);

}  // namespace nephele::terrain

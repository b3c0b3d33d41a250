// Elevation files for the terrain's tests, written with GDAL (16-bit PNGs, GeoTIFFs).
#pragma once

#include <string>
#include <vector>

namespace nephele::test {

// A w x h PNG of `bands` 16-bit channels (1 grey, 3 colour), every channel the row-major
// `values` (row 0 the top).
void write_png16(const std::string& path, int w, int h, int bands, const std::vector<unsigned short>& values);

// A w x h GeoTIFF of float heights (row-major, row 0 the north edge) on a latitude-longitude
// grid (EPSG:4326): its north-west corner at (north_lat_deg, west_lon_deg), cells of
// cell_deg; with `georeferenced` false, no geotransform and no coordinate system.
void write_geotiff(const std::string& path, int w, int h, const std::vector<float>& heights_m,
                   double north_lat_deg, double west_lon_deg, double cell_deg, bool georeferenced = true);

}  // namespace nephele::test

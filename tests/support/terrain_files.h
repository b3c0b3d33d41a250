// Elevation files for the terrain's tests, written with GDAL (16-bit PNGs, GeoTIFFs), and PNGs
// built byte by byte for the input limits' tests (any declared size, any corruption).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace nephele::test {

// A w x h PNG of `bands` 16-bit channels (1 grey, 3 colour), every channel the row-major
// `values` (row 0 the top).
void write_png16(const std::string& path, int w, int h, int bands, const std::vector<unsigned short>& values);

// A w x h GeoTIFF of float heights (row-major, row 0 the north edge) on a latitude-longitude
// grid (EPSG:4326): its north-west corner at (north_lat_deg, west_lon_deg), cells of
// cell_deg; with `georeferenced` false, no geotransform and no coordinate system.
// With `deflate`, its strips are compressed (so that corrupting one is an error GDAL reports).
void write_geotiff(const std::string& path, int w, int h, const std::vector<float>& heights_m,
                   double north_lat_deg, double west_lon_deg, double cell_deg, bool georeferenced = true,
                   bool deflate = false);

// Overwrites `count` bytes of the GeoTIFF's first strip, from its middle, with 0x5a.
void corrupt_first_strip(const std::string& path, int count);

// The bytes of a PNG declaring w x h pixels of `depth` bits and `color_type` (0 grey, 2 RGB,
// 3 palette, 4 grey and alpha, 6 RGBA), its IDAT holding `idat` as given.
std::string png_bytes(uint32_t w, uint32_t h, int depth, int color_type, const std::string& idat);
// A zlib stream of `raw` in stored (uncompressed) deflate blocks.
std::string zlib_stored(const std::string& raw);
// A valid w x h 8-bit RGBA PNG, every sample `value`.
std::string png_rgba8_bytes(int w, int h, unsigned char value);
void write_bytes(const std::string& path, const std::string& bytes);

}  // namespace nephele::test

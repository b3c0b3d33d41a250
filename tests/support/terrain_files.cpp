#include "support/terrain_files.h"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <fstream>
#include <stdexcept>

namespace nephele::test {

void write_png16(const std::string& path, int w, int h, int bands, const std::vector<unsigned short>& values) {
  GDALAllRegister();
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDriver* png = GetGDALDriverManager()->GetDriverByName("PNG");
  if (!mem || !png) throw std::runtime_error("GDAL has no MEM or PNG driver");
  GDALDataset* data = mem->Create("", w, h, bands, GDT_UInt16, nullptr);
  for (int b = 1; b <= bands; ++b)
    if (data->GetRasterBand(b)->RasterIO(GF_Write, 0, 0, w, h, const_cast<unsigned short*>(values.data()), w, h,
                                         GDT_UInt16, 0, 0) != CE_None)
      throw std::runtime_error("cannot fill the PNG's band");
  GDALDataset* out = png->CreateCopy(path.c_str(), data, FALSE, nullptr, nullptr, nullptr);
  if (!out) throw std::runtime_error("cannot write " + path);
  GDALClose(out);
  GDALClose(data);
}

void write_geotiff(const std::string& path, int w, int h, const std::vector<float>& heights_m,
                   double north_lat_deg, double west_lon_deg, double cell_deg, bool georeferenced,
                   bool deflate) {
  GDALAllRegister();
  GDALDriver* tiff = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (!tiff) throw std::runtime_error("GDAL has no GTiff driver");
  char** options = deflate ? CSLSetNameValue(nullptr, "COMPRESS", "DEFLATE") : nullptr;
  GDALDataset* data = tiff->Create(path.c_str(), w, h, 1, GDT_Float32, options);
  CSLDestroy(options);
  if (!data) throw std::runtime_error("cannot write " + path);
  if (georeferenced) {
    double gt[6] = {west_lon_deg, cell_deg, 0.0, north_lat_deg, 0.0, -cell_deg};
    data->SetGeoTransform(gt);
    OGRSpatialReference wgs84;
    wgs84.SetWellKnownGeogCS("WGS84");
    data->SetSpatialRef(&wgs84);
  }
  if (data->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, w, h, const_cast<float*>(heights_m.data()), w, h,
                                       GDT_Float32, 0, 0) != CE_None)
    throw std::runtime_error("cannot write the heights of " + path);
  GDALClose(data);
}

void corrupt_first_strip(const std::string& path, int count) {
  GDALAllRegister();
  GDALDataset* data = static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_ReadOnly));
  if (!data) throw std::runtime_error("cannot open " + path);
  const char* offset = data->GetRasterBand(1)->GetMetadataItem("BLOCK_OFFSET_0_0", "TIFF");
  const char* size = data->GetRasterBand(1)->GetMetadataItem("BLOCK_SIZE_0_0", "TIFF");
  if (!offset || !size) throw std::runtime_error("no strip in " + path);
  const long long at = std::stoll(offset) + std::stoll(size) / 2;
  GDALClose(data);
  std::fstream file(path, std::ios::binary | std::ios::in | std::ios::out);
  file.seekp(at);
  file << std::string(size_t(count), '\x5a');
}

namespace {

void append_u32(std::string& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out += char((v >> shift) & 0xff);
}

uint32_t crc32(const std::string& bytes, uint32_t crc = 0xffffffffu) {
  for (unsigned char byte : bytes) {
    crc ^= byte;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return crc;
}

void append_chunk(std::string& out, const std::string& type, const std::string& data) {
  append_u32(out, uint32_t(data.size()));
  out += type + data;
  append_u32(out, crc32(type + data) ^ 0xffffffffu);
}

}  // namespace

std::string png_bytes(uint32_t w, uint32_t h, int depth, int color_type, const std::string& idat) {
  std::string header;
  append_u32(header, w);
  append_u32(header, h);
  header += char(depth);
  header += char(color_type);
  header += std::string(3, '\0');  // deflate, adaptive filters, no interlace
  std::string png = "\x89PNG\r\n\x1a\n";
  append_chunk(png, "IHDR", header);
  append_chunk(png, "IDAT", idat);
  append_chunk(png, "IEND", "");
  return png;
}

std::string zlib_stored(const std::string& raw) {
  std::string zlib = "\x78\x01";
  size_t at = 0;
  do {
    const size_t n = std::min<size_t>(65535, raw.size() - at);
    zlib += char(at + n == raw.size() ? 1 : 0);  // BFINAL, stored
    zlib += char(n & 0xff);
    zlib += char(n >> 8);
    zlib += char(~n & 0xff);
    zlib += char((~n >> 8) & 0xff);
    zlib += raw.substr(at, n);
    at += n;
  } while (at < raw.size());
  uint32_t a = 1, b = 0;  // Adler-32
  for (unsigned char byte : raw) {
    a = (a + byte) % 65521;
    b = (b + a) % 65521;
  }
  append_u32(zlib, (b << 16) | a);
  return zlib;
}

std::string png_rgba8_bytes(int w, int h, unsigned char value) {
  std::string rows;
  for (int y = 0; y < h; ++y) rows += '\0' + std::string(size_t(w) * 4, char(value));
  return png_bytes(uint32_t(w), uint32_t(h), 8, 6, zlib_stored(rows));
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace nephele::test

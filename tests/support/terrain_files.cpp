#include "support/terrain_files.h"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

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
                   double north_lat_deg, double west_lon_deg, double cell_deg, bool georeferenced) {
  GDALAllRegister();
  GDALDriver* tiff = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (!tiff) throw std::runtime_error("GDAL has no GTiff driver");
  GDALDataset* data = tiff->Create(path.c_str(), w, h, 1, GDT_Float32, nullptr);
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

}  // namespace nephele::test

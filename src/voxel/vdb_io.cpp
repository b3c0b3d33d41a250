// nephele — voxel clouds: reading OpenVDB (.vdb) and NanoVDB (.nvdb) files into the dense
// grid, and writing it as OpenVDB. Every way a file can be wrong is one line of InputError.
// clang-format off
#include <iostream>  // before GridValidator.h, which uses std::cerr without including it
#include <nanovdb/util/GridValidator.h>
// clang-format on
#include <nanovdb/util/IO.h>
#include <nanovdb/util/NanoToOpenVDB.h>
#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "nephele/error.h"
#include "nephele/output_file.h"
#include "voxel/common.h"
#include "voxel/level_set.h"
#include "voxel/voxel_grid.h"

namespace nephele::voxel {
namespace {

namespace fs = std::filesystem;

// The largest active bounding box a file may have: beyond it the file is taken for corrupt
// (or a grid far larger than a cloud needs), and refused before its tree is read.
constexpr int kMaxSourceDim = 4096;
constexpr int64_t kMaxSourceVoxels = int64_t(1) << 30;
const char* const kLimits = "at most 4096 voxels per axis and 2^30 in all";

// Dense voxels sample a coarser grid's voxels with up to this many points per axis (a box
// filter; beyond it, some aliasing rather than minutes of sampling).
constexpr int kMaxSupersampling = 4;

struct Source {
  openvdb::FloatGrid::Ptr density, sdf;
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw InputError(file_prefix(path) + what);
}

std::string quoted_list(const std::vector<std::string>& names) {
  if (names.empty()) return "none";
  std::string out;
  for (const std::string& n : names) {
    if (out.size() > kMaxEchoedChars) return out + ", ...";
    out += (out.empty() ? "\"" : ", \"") + shorten_for_message(n) + "\"";
  }
  return out;
}

void check_dims(const std::string& path, const std::string& grid, int64_t nx, int64_t ny,
                int64_t nz) {
  if (nx > kMaxSourceDim || ny > kMaxSourceDim || nz > kMaxSourceDim ||
      nx * ny * nz > kMaxSourceVoxels)
    fail(path, "grid \"" + grid + "\" spans " + std::to_string(nx) + " x " + std::to_string(ny) +
                   " x " + std::to_string(nz) + " voxels (" + kLimits + ")");
}

// A grid of the file, read only after its metadata (type, size) passed.
void check_read_grid(const std::string& path, const std::string& name,
                     const openvdb::FloatGrid& grid, bool level_set) {
  const openvdb::Vec3d voxel = grid.transform().voxelSize();
  for (int a = 0; a < 3; ++a)
    if (!(voxel[a] > 0.0) || !std::isfinite(voxel[a]))
      fail(path, "grid \"" + name + "\" has voxel size " + std::to_string(voxel[a]) +
                     " (a finite voxel size > 0 is required)");
  if (!grid.transform().isLinear())
    fail(path, "grid \"" + name + "\" has a frustum transform (a linear transform is required)");
  const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
  if (box.empty()) {
    if (level_set) return;
    fail(path, "grid \"density\" has no active voxels (a non-empty fog volume is required)");
  }
  check_dims(path, name, box.dim().x(), box.dim().y(), box.dim().z());
  if (!std::isfinite(grid.background()))
    fail(path, "grid \"" + name + "\" has a non-finite background (finite values are required)");
  for (auto it = grid.cbeginValueOn(); it; ++it)
    if (!std::isfinite(*it))
      fail(path, "grid \"" + name + "\" has a non-finite value at index " +
                     std::to_string(it.getCoord().x()) + "," + std::to_string(it.getCoord().y()) +
                     "," + std::to_string(it.getCoord().z()) + " (finite values are required)");
}

Source read_openvdb(const std::string& path) {
  initialize_openvdb();
  openvdb::io::File file(path);
  try {
    // Not delayed: a truncated file fails here and in readGrid, not later on first access.
    file.open(/*delayLoad=*/false);
  } catch (const std::exception& e) {
    // A file that starts as OpenVDB's do but fails is cut short or damaged; a file written
    // as a stream (write_vdb's) is read whole here, so its truncation shows here too.
    int32_t magic = 0;
    std::ifstream(path, std::ios::binary).read(reinterpret_cast<char*>(&magic), sizeof magic);
    if (magic == openvdb::OPENVDB_MAGIC)
      fail(path, "is truncated or corrupt (" + shorten_for_message(e.what()) + ")");
    fail(path, "is not a readable OpenVDB file (" + shorten_for_message(e.what()) +
                   "; a .vdb with a float grid \"density\" is required)");
  }
  openvdb::GridPtrVecPtr metadata;
  try {
    metadata = file.readAllGridMetadata();
  } catch (const std::exception& e) {
    fail(path, "is truncated or corrupt (" + shorten_for_message(e.what()) + ")");
  }
  std::vector<std::string> names;
  openvdb::GridBase::Ptr density_meta, sdf_meta;
  for (const openvdb::GridBase::Ptr& g : *metadata) {
    names.push_back(g->getName());
    if (g->getName() == "density" && !density_meta) density_meta = g;
    if (g->getName() == "sdf" && !sdf_meta) sdf_meta = g;
  }
  if (!density_meta)
    fail(path, "has no grid named \"density\" (it has: " + quoted_list(names) +
                   "; a float fog volume named \"density\" is required)");
  for (const auto& [name, meta] : {std::pair{"density", density_meta}, {"sdf", sdf_meta}}) {
    if (!meta) continue;
    if (!meta->isType<openvdb::FloatGrid>())
      fail(path, std::string("grid \"") + name + "\" holds " +
                     shorten_for_message(meta->valueType()) + " values (a float grid is required)");
    // The bounding box the writer recorded: an absurd grid is refused before it is read.
    const auto lo =
        meta->getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MIN);
    const auto hi =
        meta->getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MAX);
    if (lo && hi) {
      const openvdb::Vec3i a = lo->value(), b = hi->value();
      if (b.x() >= a.x() && b.y() >= a.y() && b.z() >= a.z())
        check_dims(path, name, int64_t(b.x()) - a.x() + 1, int64_t(b.y()) - a.y() + 1,
                   int64_t(b.z()) - a.z() + 1);
    }
  }
  Source source;
  try {
    source.density = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("density"));
    if (sdf_meta) source.sdf = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("sdf"));
  } catch (const std::exception& e) {
    fail(path, "is truncated or corrupt (" + shorten_for_message(e.what()) + ")");
  }
  if (!source.density) fail(path, "is truncated or corrupt (grid \"density\" unreadable)");
  return source;
}

// --- NanoVDB -------------------------------------------------------------------------------

struct NanoEntry {
  std::string name;
  nanovdb::GridType type;
  nanovdb::io::Codec codec;
  int64_t dim[3];
};

// The grids of an .nvdb, from its segment headers, every size checked against the file's:
// NanoVDB's reader trusts them (and allocates what they say).
std::vector<NanoEntry> scan_nanovdb(const std::string& path, uint64_t file_bytes) {
  std::ifstream is(path, std::ios::binary);
  if (!is) fail(path, "cannot be read");
  std::vector<NanoEntry> entries;
  uint64_t pos = 0;
  const auto truncated = [&] { fail(path, "is truncated (a whole NanoVDB file is required)"); };
  while (pos < file_bytes) {
    nanovdb::io::Header header;
    if (file_bytes - pos < sizeof(header)) truncated();
    is.read(reinterpret_cast<char*>(&header), sizeof(header));
    if (!is) truncated();
    pos += sizeof(header);
    if (header.magic != NANOVDB_MAGIC_NUMBER)
      fail(path, entries.empty() ? "is not a NanoVDB file (a .nvdb with a float grid "
                                   "\"density\" is required)"
                                 : "is corrupt (a segment without the NanoVDB magic number)");
    if (header.version.getMajor() != NANOVDB_MAJOR_VERSION_NUMBER)
      fail(path, "is NanoVDB version " + std::string(header.version.c_str()) + " (version " +
                     std::to_string(NANOVDB_MAJOR_VERSION_NUMBER) + ".x is required)");
    if (header.codec != nanovdb::io::Codec::NONE)
      fail(path, "is compressed (an uncompressed NanoVDB file is required)");
    uint64_t data_bytes = 0;
    for (uint16_t g = 0; g < header.gridCount; ++g) {
      nanovdb::io::MetaData meta;
      if (file_bytes - pos < sizeof(meta)) truncated();
      is.read(reinterpret_cast<char*>(&meta), sizeof(meta));
      pos += sizeof(meta);
      if (meta.nameSize == 0 || meta.nameSize > 4096 || file_bytes - pos < meta.nameSize)
        truncated();
      std::string name(meta.nameSize, '\0');
      is.read(name.data(), meta.nameSize);
      if (!is) truncated();
      pos += meta.nameSize;
      name.resize(std::strlen(name.c_str()));
      if (meta.fileSize != meta.gridSize || meta.gridSize > file_bytes) truncated();
      data_bytes += meta.fileSize;
      const nanovdb::CoordBBox& b = meta.indexBBox;
      NanoEntry entry{name, meta.gridType, header.codec, {}};
      for (int a = 0; a < 3; ++a)
        entry.dim[a] = std::max<int64_t>(int64_t(b.max()[a]) - b.min()[a] + 1, 0);
      entries.push_back(entry);
    }
    if (file_bytes - pos < data_bytes) truncated();
    pos += data_bytes;
    is.seekg(std::streamoff(pos));
  }
  return entries;
}

openvdb::FloatGrid::Ptr read_nano_grid(const std::string& path, const std::string& name) {
  nanovdb::GridHandle<> handle;
  try {
    handle = nanovdb::io::readGrid(path, name);
  } catch (const std::exception& e) {
    fail(path, "is truncated or corrupt (" + shorten_for_message(e.what()) + ")");
  }
  const nanovdb::NanoGrid<float>* grid = handle.grid<float>();
  // The checksum and the tree's offsets: a corrupt grid is refused before it is walked.
  if (!grid || !nanovdb::isValid(*grid, /*detailed=*/true))
    fail(path, "grid \"" + name + "\" is corrupt (its checksum or structure does not hold)");
  return nanovdb::nanoToOpenVDB(*grid);
}

Source read_nanovdb(const std::string& path, uint64_t file_bytes) {
  initialize_openvdb();
  const std::vector<NanoEntry> entries = scan_nanovdb(path, file_bytes);
  std::vector<std::string> names;
  const NanoEntry *density = nullptr, *sdf = nullptr;
  for (const NanoEntry& e : entries) {
    names.push_back(e.name);
    if (e.name == "density" && !density) density = &e;
    if (e.name == "sdf" && !sdf) sdf = &e;
  }
  if (!density)
    fail(path, "has no grid named \"density\" (it has: " + quoted_list(names) +
                   "; a float fog volume named \"density\" is required)");
  for (const NanoEntry* e : {density, sdf}) {
    if (!e) continue;
    if (e->type != nanovdb::GridType::Float)
      fail(path, "grid \"" + e->name + "\" holds " + nanovdb::toStr(e->type) +
                     " values (a float grid is required)");
    check_dims(path, e->name, e->dim[0], e->dim[1], e->dim[2]);
  }
  Source source;
  source.density = read_nano_grid(path, "density");
  if (sdf) source.sdf = read_nano_grid(path, "sdf");
  return source;
}

// --- to the dense grid ---------------------------------------------------------------------

// The dense grid of the file's density (and level set, where it has one that bounds the
// density's distance), in the cloud's frame, resampled to at most max_dim voxels an axis.
VoxelGrid to_dense(const std::string& path, const Source& source, int max_dim) {
  check_read_grid(path, "density", *source.density, false);
  if (source.sdf) check_read_grid(path, "sdf", *source.sdf, true);
  const openvdb::math::Transform& xform = source.density->transform();
  const openvdb::CoordBBox box = source.density->evalActiveVoxelBoundingBox();
  // The active voxels' cubes, in world space (any linear transform: its bounding box).
  const openvdb::BBoxd world =
      xform.indexToWorld(openvdb::BBoxd(box.min().asVec3d() - 0.5, box.max().asVec3d() + 0.5));
  const glm::vec3 lo(world.min().x(), world.min().y(), world.min().z());
  const glm::vec3 hi(world.max().x(), world.max().y(), world.max().z());
  const openvdb::Vec3d source_voxel = xform.voxelSize();
  constexpr int kPad = 2;
  VoxelGrid grid;
  grid.voxel_m = float(std::min({source_voxel.x(), source_voxel.y(), source_voxel.z()}));
  fit_grid(hi - lo, kPad, max_dim, grid);
  if (!(grid.voxel_m > 0.0f) || !std::isfinite(grid.voxel_m) || !std::isfinite(hi.x - lo.x) ||
      !std::isfinite(hi.y - lo.y) || !std::isfinite(hi.z - lo.z))
    fail(path, "grid \"density\" has an extent that is not finite (finite sizes are required)");
  const glm::vec3 origin_world(0.5f * (lo.x + hi.x) - 0.5f * grid.dims.x * grid.voxel_m,
                               0.5f * (lo.y + hi.y) - 0.5f * grid.dims.y * grid.voxel_m,
                               lo.z - kPad * grid.voxel_m);
  const size_t count = size_t(grid.dims.x) * grid.dims.y * grid.dims.z;
  grid.density.assign(count, 0.0f);
  const float ratio = grid.voxel_m / float(source_voxel.length() / std::sqrt(3.0));
  const int sub = ratio > 1.01f ? std::min(int(std::ceil(ratio)), kMaxSupersampling) : 1;
  tbb::parallel_for(0, grid.dims.z, [&](int k) {
    // The sampler keeps a reference to the accessor: it must outlive the sampler (a
    // temporary here was a use after scope, found by AddressSanitizer).
    const openvdb::FloatGrid::ConstAccessor accessor = source.density->getConstAccessor();
    openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler>
        sampler(accessor, xform);
    for (int j = 0; j < grid.dims.y; ++j)
      for (int i = 0; i < grid.dims.x; ++i) {
        double sum = 0.0;
        float largest = 0.0f;
        for (int c = 0; c < sub * sub * sub; ++c) {
          const glm::vec3 f((c % sub + 0.5f) / sub, ((c / sub) % sub + 0.5f) / sub,
                            (c / (sub * sub) + 0.5f) / sub);
          const glm::vec3 p = origin_world + (glm::vec3(i, j, k) + f) * grid.voxel_m;
          const float v = std::max(sampler.wsSample(openvdb::Vec3d(p.x, p.y, p.z)), 0.0f);
          sum += v;
          largest = std::max(largest, v);
        }
        // Averaged, but never to zero where any sample had density: the surface stays where
        // the file has it.
        float v = float(sum / (sub * sub * sub));
        if (largest > 0.0f && !(v > 0.0f)) v = std::numeric_limits<float>::min();
        grid.density[grid.index(i, j, k)] = v;
      }
  });
  // Densities above 1 (fog volumes are not always normalised) scale down to [0, 1]: the
  // renderer's density scale sets the extinction.
  const float peak = *std::max_element(grid.density.begin(), grid.density.end());
  if (!(peak > 0.0f)) fail(path, "grid \"density\" is zero everywhere (density > 0 is required)");
  if (peak > 1.0f) {
    for (float& v : grid.density) v /= peak;
    grid.file_density_scale = peak;
  }
  bool sdf_bounds_density = false;
  if (source.sdf && source.sdf->evalActiveVoxelBoundingBox().empty() == false) {
    grid.sdf_m.assign(count, 0.0f);
    std::atomic<bool> consistent{true};
    tbb::parallel_for(0, grid.dims.z, [&](int k) {
      const openvdb::FloatGrid::ConstAccessor accessor = source.sdf->getConstAccessor();
      openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler>
          sampler(accessor, source.sdf->transform());
      for (int j = 0; j < grid.dims.y; ++j)
        for (int i = 0; i < grid.dims.x; ++i) {
          const glm::vec3 p = origin_world + (glm::vec3(i, j, k) + 0.5f) * grid.voxel_m;
          const float d = sampler.wsSample(openvdb::Vec3d(p.x, p.y, p.z));
          const size_t v = grid.index(i, j, k);
          grid.sdf_m[v] = d;
          // The file's level set must not put density outside its surface by more than a
          // voxel (a sphere tracer would step over it); else it is computed afresh.
          if (grid.density[v] > 0.0f && d > grid.voxel_m) consistent = false;
        }
    });
    sdf_bounds_density = consistent;
  }
  if (!sdf_bounds_density) compute_sdf_from_density(grid);
  // The cloud's frame: the anchor is the centre of the active box's base.
  grid.file_anchor_m = glm::vec3(0.5f * (lo.x + hi.x), 0.5f * (lo.y + hi.y), lo.z);
  grid.origin_m = origin_world - grid.file_anchor_m;
  return grid;
}

}  // namespace

VoxelGrid load_voxel_cloud(const std::string& path, int max_dim) {
  check_max_dim(max_dim);
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) fail(path, "does not exist (a .vdb or .nvdb file is required)");
  if (!fs::is_regular_file(status))
    fail(path, "is not a regular file (a .vdb or .nvdb file is required)");
  const uint64_t bytes = fs::file_size(path, ec);
  if (ec) fail(path, "cannot be read (" + ec.message() + ")");
  if (!std::ifstream(path, std::ios::binary))
    fail(path, "cannot be read (a readable .vdb or .nvdb file is required)");
  if (bytes == 0) fail(path, "is empty (a .vdb or .nvdb file is required)");
  const std::string extension = fs::path(path).extension().string();
  const bool nano = extension == ".nvdb";
  if (!nano && extension != ".vdb")
    fail(path, "has extension '" + shorten_for_message(extension) +
                   "' (.vdb (OpenVDB) or .nvdb (NanoVDB) is required)");
  const Source source = nano ? read_nanovdb(path, bytes) : read_openvdb(path);
  return to_dense(path, source, max_dim);
}

void write_vdb(const VoxelGrid& grid, const std::string& path) {
  const size_t count = size_t(grid.dims.x) * grid.dims.y * grid.dims.z;
  if (grid.dims.x <= 0 || grid.dims.y <= 0 || grid.dims.z <= 0 || grid.density.size() != count ||
      grid.sdf_m.size() != count || !(grid.voxel_m > 0.0f))
    throw std::invalid_argument("write_vdb: the grid's dims, voxel size and arrays disagree");
  initialize_openvdb();
  // Index (i, j, k) is the centre of voxel (i, j, k); world space is the cloud's frame.
  openvdb::math::Transform::Ptr xform =
      openvdb::math::Transform::createLinearTransform(grid.voxel_m);
  const glm::vec3 first_centre = grid.origin_m + 0.5f * grid.voxel_m;
  xform->postTranslate(openvdb::Vec3d(first_centre.x, first_centre.y, first_centre.z));

  openvdb::FloatGrid::Ptr density = openvdb::FloatGrid::create(0.0f);
  density->setName("density");
  density->setGridClass(openvdb::GRID_FOG_VOLUME);
  density->setTransform(xform);
  // A level set's background is the distance beyond its band: here every voxel is in it.
  float largest = grid.voxel_m;
  for (float d : grid.sdf_m) largest = std::max(largest, std::fabs(d));
  openvdb::FloatGrid::Ptr sdf = openvdb::FloatGrid::create(largest);
  sdf->setName("sdf");
  sdf->setGridClass(openvdb::GRID_LEVEL_SET);
  sdf->setTransform(xform->copy());
  {
    openvdb::FloatGrid::Accessor dens = density->getAccessor(), dist = sdf->getAccessor();
    for (int k = 0; k < grid.dims.z; ++k)
      for (int j = 0; j < grid.dims.y; ++j)
        for (int i = 0; i < grid.dims.x; ++i) {
          const size_t v = grid.index(i, j, k);
          const openvdb::Coord ijk(i, j, k);
          if (grid.density[v] > 0.0f) dens.setValue(ijk, grid.density[v]);
          dist.setValue(ijk, grid.sdf_m[v]);
        }
  }
  std::ostringstream bytes(std::ios::binary);
  openvdb::io::Stream(bytes).write(openvdb::GridCPtrVec{density, sdf});
  write_file_atomically(path, bytes.str());
}

}  // namespace nephele::voxel

// nephele — voxel clouds: reading OpenVDB (.vdb) and NanoVDB (.nvdb) files into the dense
// grid, and writing it as OpenVDB. Every way a file can be wrong is one line of InputError.
// clang-format off
#include <iostream>  // before GridValidator.h, which uses std::cerr without including it
#include <nanovdb/util/GridValidator.h>
// clang-format on
#include <nanovdb/util/IO.h>
#include <nanovdb/util/NanoToOpenVDB.h>
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
#include "voxel/vdb_scan.h"
#include "voxel/voxel_grid.h"

namespace nephele::voxel {
namespace {

namespace fs = std::filesystem;

// The largest active bounding box a file may have: beyond it the file is taken for corrupt
// (or a grid far larger than a cloud needs), and refused before its tree is read.
constexpr int kMaxSourceDim = 4096;
constexpr int64_t kMaxSourceVoxels = int64_t(1) << 30;
const char* const kLimits = "at most 4096 voxels per axis and 2^30 in all";

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
  // Inactive values and the background may be anything (NaN or inf included): only the
  // active values are read.
  for (auto it = grid.cbeginValueOn(); it; ++it)
    if (!std::isfinite(*it))
      fail(path, "grid \"" + name + "\" has a non-finite value at index " +
                     std::to_string(it.getCoord().x()) + "," + std::to_string(it.getCoord().y()) +
                     "," + std::to_string(it.getCoord().z()) + " (finite values are required)");
}

// The bytes the scan passed, in order, as one stream for io::Stream: the file's header and
// the chosen grids (without their metadata), with nephele's own counts between them.
class SegmentBuf : public std::streambuf {
 public:
  SegmentBuf(const std::string& path, std::vector<VdbSegment> segments)
      : file_(path, std::ios::binary), segments_(std::move(segments)) {}

 protected:
  int_type underflow() override {
    for (; next_ < segments_.size(); ++next_, done_ = 0) {
      const VdbSegment& s = segments_[next_];
      if (!s.literal.empty() && done_ == 0) {
        buffer_.assign(s.literal.begin(), s.literal.end());
        done_ = s.literal.size();
      } else if (done_ < s.bytes) {
        buffer_.resize(std::min<uint64_t>(s.bytes - done_, 1 << 16));
        file_.seekg(std::streamoff(s.offset + done_));
        if (!file_.read(buffer_.data(), std::streamsize(buffer_.size()))) break;
        done_ += buffer_.size();
      } else {
        continue;
      }
      setg(buffer_.data(), buffer_.data(), buffer_.data() + buffer_.size());
      return traits_type::to_int_type(buffer_[0]);
    }
    return traits_type::eof();
  }

 private:
  std::ifstream file_;
  std::vector<VdbSegment> segments_;
  size_t next_ = 0;
  uint64_t done_ = 0;  // bytes of segments_[next_] given out
  std::vector<char> buffer_;
};

// The file's first "density" grid, and its first "sdf", checked by the pre-scan before
// OpenVDB reads them: it reads only those, from a stream that fails rather than runs past
// the end (and, having no other grid of the same name, warns of none).
Source read_openvdb(const std::string& path, uint64_t file_bytes) {
  initialize_openvdb();
  const VdbScan scan = scan_openvdb(path, file_bytes);
  std::vector<std::string> names;
  const VdbGridInfo *density = nullptr, *sdf = nullptr;
  for (const VdbGridInfo& g : scan.grids) {
    names.push_back(g.name);
    if (g.name == "density" && !density) density = &g;
    if (g.name == "sdf" && !sdf) sdf = &g;
  }
  if (!density && scan.stopped)
    fail(path, "has grid \"" + shorten_for_message(scan.grids.back().name) + "\" of " +
                   scan.grids.back().value_type +
                   " values before any grid \"density\", which a stream without grid offsets "
                   "cannot pass (float grids only before \"density\", or a file written "
                   "with grid offsets, are required)");
  if (!density)
    fail(path, "has no grid named \"density\" (it has: " + quoted_list(names) +
                   "; a float fog volume named \"density\" is required)");
  std::vector<VdbSegment> segments = scan.header;
  const int32_t count = sdf ? 2 : 1;
  segments.push_back({0, 0, std::string(reinterpret_cast<const char*>(&count), sizeof count)});
  uint64_t tree_bytes = 0;
  for (const auto& [name, grid] : {std::pair{"density", density}, {"sdf", sdf}}) {
    if (!grid) continue;
    if (grid->value_type != "float")
      fail(path, std::string("grid \"") + name + "\" holds " + grid->value_type +
                     " values (a float grid is required)");
    if (grid->instance || !grid->walked)
      fail(path, std::string("grid \"") + name +
                     "\" shares another grid's tree (a grid with its own tree is required)");
    tree_bytes += grid->tree_bytes;
    segments.insert(segments.end(), grid->segments.begin(), grid->segments.end());
  }
  if (tree_bytes > kMaxVdbTreeBytes)
    fail(path, "grids \"density\" and \"sdf\" take more than " +
                   std::to_string(kMaxVdbTreeBytes >> 20) + " MiB in memory (at most " +
                   std::to_string(kMaxVdbTreeBytes >> 20) + " MiB of float trees is read)");
  SegmentBuf buffer(path, std::move(segments));
  std::istream is(&buffer);
  Source source;
  try {
    is.exceptions(std::ios::failbit | std::ios::badbit);
    openvdb::io::Stream stream(is, /*delayLoad=*/false);
    const openvdb::GridPtrVecPtr grids = stream.getGrids();
    if (grids && grids->size() == size_t(count)) {
      source.density = openvdb::gridPtrCast<openvdb::FloatGrid>(grids->front());
      if (sdf) source.sdf = openvdb::gridPtrCast<openvdb::FloatGrid>(grids->back());
    }
  } catch (const std::exception& e) {
    fail(path, "is truncated or corrupt (" + shorten_for_message(e.what()) + ")");
  }
  if (!source.density || (sdf && !source.sdf))
    fail(path, "is truncated or corrupt (its grids are unreadable)");
  return source;
}

// --- NanoVDB -------------------------------------------------------------------------------

struct NanoEntry {
  std::string name;
  nanovdb::GridType type;
  nanovdb::io::Codec codec;
  int64_t dim[3];
};

// "32.4.0". Not nanovdb::Version::c_str(): that returns a malloc'd buffer its callers must
// free, and a std::string made from it leaked it (FuzzFiles' .nvdb cases, LeakSanitizer).
// NanoVDB's own io::Segment::read leaks it the same way for a segment of an older major
// version, which scan_nanovdb refuses before nanovdb::io::readGrid reads the file.
std::string version_text(const nanovdb::Version& version) {
  return std::to_string(version.getMajor()) + "." + std::to_string(version.getMinor()) + "." +
         std::to_string(version.getPatch());
}

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
      fail(path, "is NanoVDB version " + version_text(header.version) + " (version " +
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

// Why a NanoVDB float grid's tree does not lie within its buffer ("" when it does): every node
// offset, the root's table and the node counts, checked before anything follows an offset.
// NanoVDB's own validator computes the checksum first, walking the tree through offsets it has
// not checked (a flipped byte crashed it), and never checks the leaves' offsets.
std::string nano_tree_problem(const nanovdb::GridHandle<>& handle,
                              const nanovdb::NanoGrid<float>& grid) {
  using Tree = nanovdb::NanoTree<float>;
  using Root = Tree::RootType;
  using Upper = Root::ChildNodeType;
  using Lower = Upper::ChildNodeType;
  using Leaf = Lower::ChildNodeType;
  const uintptr_t begin = reinterpret_cast<uintptr_t>(&grid);
  const uintptr_t buffer_end = reinterpret_cast<uintptr_t>(handle.data()) + handle.size();
  const uint64_t grid_bytes = grid.gridSize();
  if (begin < reinterpret_cast<uintptr_t>(handle.data()) || begin > buffer_end ||
      grid_bytes > buffer_end - begin ||
      grid_bytes < sizeof(nanovdb::GridData) + sizeof(Tree::DataType) + sizeof(Root))
    return "its size does not fit the file";
  const uintptr_t end = begin + grid_bytes;
  // Whether `bytes` at `base + offset` lie within the grid, aligned as NanoVDB aligns nodes.
  const auto within = [&](uintptr_t base, int64_t offset, uint64_t bytes) {
    const uintptr_t at = base + uintptr_t(offset);
    return (offset >= 0 ? uint64_t(offset) <= end - base
                        : uint64_t(-(offset + 1)) < base - begin) &&
           at >= begin && at <= end && bytes <= end - at && at % NANOVDB_DATA_ALIGNMENT == 0;
  };
  const uintptr_t tree = reinterpret_cast<uintptr_t>(&grid.tree());
  const Tree::DataType& data = *grid.tree().data();
  if (!within(tree, int64_t(data.mNodeOffset[3]), sizeof(Root))) return "its root lies outside it";
  const uint64_t node_bytes[3] = {sizeof(Leaf), sizeof(Lower), sizeof(Upper)};
  for (int level = 0; level < 3; ++level)
    if (data.mNodeCount[level] > 0 && (data.mNodeCount[level] > grid_bytes / node_bytes[level] ||
                                       !within(tree, int64_t(data.mNodeOffset[level]),
                                               data.mNodeCount[level] * node_bytes[level])))
      return "its nodes of level " + std::to_string(level) + " lie outside it";
  const Root& root = grid.tree().root();
  const uintptr_t root_at = reinterpret_cast<uintptr_t>(&root);
  if (root.tileCount() > grid_bytes / sizeof(Root::Tile) || !within(root_at, 0, root.memUsage()))
    return "its root's table lies outside it";
  // Each node reached once at most: shared or looping offsets exceed the counts.
  uint64_t seen[3] = {0, 0, 0};
  const auto child = [&](uintptr_t parent, int64_t offset, int level) -> uintptr_t {
    if (!within(parent, offset, node_bytes[level]) || ++seen[level] > data.mNodeCount[level])
      return 0;
    return parent + uintptr_t(offset);
  };
  for (uint32_t t = 0; t < root.tileCount(); ++t) {
    const Root::Tile* tile = root.data()->tile(t);
    if (!tile->isChild()) continue;
    const uintptr_t upper = child(root_at, tile->child, 2);
    if (!upper) return "a node lies outside it";
    const auto* upper_data = reinterpret_cast<const Upper*>(upper)->data();
    for (auto n = upper_data->mChildMask.beginOn(); n; ++n) {
      const uintptr_t lower = child(upper, upper_data->mTable[*n].child, 1);
      if (!lower) return "a node lies outside it";
      const auto* lower_data = reinterpret_cast<const Lower*>(lower)->data();
      for (auto m = lower_data->mChildMask.beginOn(); m; ++m)
        if (!child(lower, lower_data->mTable[*m].child, 0)) return "a node lies outside it";
    }
  }
  return "";
}

openvdb::FloatGrid::Ptr read_nano_grid(const std::string& path, const std::string& name) {
  nanovdb::GridHandle<> handle;
  try {
    handle = nanovdb::io::readGrid(path, name);
  } catch (const std::exception& e) {
    fail(path, "is truncated or corrupt (" + shorten_for_message(e.what()) + ")");
  }
  const nanovdb::NanoGrid<float>* grid = handle.grid<float>();
  if (!grid) fail(path, "grid \"" + name + "\" is corrupt (it is not a float grid)");
  if (const std::string why = nano_tree_problem(handle, *grid); !why.empty())
    fail(path, "grid \"" + name + "\" is corrupt (" + why + ")");
  // The grid's own version, which may differ from its segment's: NanoVDB's validator formats a
  // wrong one with Version::c_str() and never frees it (a grid without a checksum reaches it).
  if (const nanovdb::Version version = grid->version();
      version.getMajor() != NANOVDB_MAJOR_VERSION_NUMBER)
    fail(path, "grid \"" + name + "\" is NanoVDB version " + version_text(version) + " (version " +
                   std::to_string(NANOVDB_MAJOR_VERSION_NUMBER) + ".x is required)");
  // The checksum and the tree's offsets: a corrupt grid is refused before it is walked.
  if (!nanovdb::isValid(*grid, /*detailed=*/true))
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

// Inactive values and the background become zero: between active voxels and zero, all the
// density sampled is the file's active values (inactive NaN or inf are valid in a file).
void keep_active_only(openvdb::FloatGrid& grid) {
  for (auto it = grid.tree().beginValueOff(); it; ++it) it.setValue(0.0f);
  grid.tree().root().setBackground(0.0f, /*updateChildNodes=*/false);
}

// Dense voxels no coarser than the file's: the file's density, trilinear, at their centres.
void sample_active(const openvdb::FloatGrid& source, glm::vec3 origin_world, VoxelGrid& grid) {
  tbb::parallel_for(0, grid.dims.z, [&](int k) {
    // The sampler keeps a reference to the accessor: it must outlive the sampler (a
    // temporary here was a use after scope, found by AddressSanitizer).
    const openvdb::FloatGrid::ConstAccessor accessor = source.getConstAccessor();
    openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler>
        sampler(accessor, source.transform());
    for (int j = 0; j < grid.dims.y; ++j)
      for (int i = 0; i < grid.dims.x; ++i) {
        const glm::vec3 p = origin_world + (glm::vec3(i, j, k) + 0.5f) * grid.voxel_m;
        const float v = sampler.wsSample(openvdb::Vec3d(p.x, p.y, p.z));
        grid.density[grid.index(i, j, k)] = std::max(v, 0.0f);
      }
  });
}

// Adds `value` spread over the world box [lo, hi) to the dense voxels it overlaps, each by
// the fraction of the voxel it covers.
void splat_box(const glm::dvec3& lo, const glm::dvec3& hi, float value, glm::vec3 origin_world,
               VoxelGrid& grid) {
  glm::ivec3 first, last;
  glm::dvec3 a, b;  // the box in dense voxels
  for (int c = 0; c < 3; ++c) {
    a[c] = (lo[c] - origin_world[c]) / grid.voxel_m;
    b[c] = (hi[c] - origin_world[c]) / grid.voxel_m;
    first[c] = std::clamp(int(std::floor(a[c])), 0, grid.dims[c] - 1);
    last[c] = std::clamp(int(std::ceil(b[c])) - 1, first[c], grid.dims[c] - 1);
  }
  const auto cover = [&](int c, int cell) {
    return std::max(0.0, std::min(b[c], cell + 1.0) - std::max(a[c], double(cell)));
  };
  for (int k = first.z; k <= last.z; ++k)
    for (int j = first.y; j <= last.y; ++j)
      for (int i = first.x; i <= last.x; ++i)
        grid.density[grid.index(i, j, k)] += float(value * cover(0, i) * cover(1, j) * cover(2, k));
}

// Dense voxels coarser than the file's: each active voxel (and active tile, as its voxels)
// adds its density times the part of each dense voxel it covers, so that the mass is kept
// and no grid is too thin to be seen (a sheet one voxel thick falls between sample points).
void splat_active(const openvdb::FloatGrid& source, glm::vec3 origin_world, VoxelGrid& grid) {
  const openvdb::math::Transform& xform = source.transform();
  const openvdb::Vec3d voxel = xform.voxelSize();
  for (auto it = source.cbeginValueOn(); it; ++it) {
    if (!(*it > 0.0f)) continue;
    openvdb::CoordBBox box;
    it.getBoundingBox(box);
    const openvdb::Vec3d centre =
        xform.indexToWorld(0.5 * (box.min().asVec3d() + box.max().asVec3d()));
    const openvdb::Vec3d half = 0.5 * voxel * box.dim().asVec3d();
    splat_box(glm::dvec3(centre.x() - half.x(), centre.y() - half.y(), centre.z() - half.z()),
              glm::dvec3(centre.x() + half.x(), centre.y() + half.y(), centre.z() + half.z()), *it,
              origin_world, grid);
  }
}

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
  // Checked before fit_grid turns them into voxel counts: a corrupt transform's NaN would be
  // converted to an int (undefined behaviour, found by FuzzFiles under UBSan).
  if (!(grid.voxel_m > 0.0f) || !std::isfinite(grid.voxel_m) || !std::isfinite(hi.x - lo.x) ||
      !std::isfinite(hi.y - lo.y) || !std::isfinite(hi.z - lo.z))
    fail(path, "grid \"density\" has an extent that is not finite (finite sizes are required)");
  fit_grid(hi - lo, kPad, max_dim, grid);
  const glm::vec3 origin_world(0.5f * (lo.x + hi.x) - 0.5f * grid.dims.x * grid.voxel_m,
                               0.5f * (lo.y + hi.y) - 0.5f * grid.dims.y * grid.voxel_m,
                               lo.z - kPad * grid.voxel_m);
  const size_t count = size_t(grid.dims.x) * grid.dims.y * grid.dims.z;
  grid.density.assign(count, 0.0f);
  keep_active_only(*source.density);
  const float ratio = grid.voxel_m / float(source_voxel.length() / std::sqrt(3.0));
  if (ratio > 1.01f)
    splat_active(*source.density, origin_world, grid);
  else
    sample_active(*source.density, origin_world, grid);
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
          // voxel (a sphere tracer would step over it), nor be undefined (a non-finite
          // background); else it is computed afresh.
          if (!std::isfinite(d) || (grid.density[v] > 0.0f && d > grid.voxel_m)) consistent = false;
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
  const Source source = nano ? read_nanovdb(path, bytes) : read_openvdb(path, bytes);
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

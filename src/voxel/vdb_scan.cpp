// nephele — voxel clouds: the structural pre-scan of OpenVDB files (see vdb_scan.h). The
// layout walked here is what OpenVDB 10 reads (io/Archive.cc, io/GridDescriptor.cc,
// MetaMap.cc, math/Transform.cc and Maps.h, tree/RootNode.h, InternalNode.h, LeafNode.h,
// io/Compression.h and .cc), for file format versions 222 to 224; the comments cite it.
#include "voxel/vdb_scan.h"

#include <openvdb/openvdb.h>

#include <bit>
#include <fstream>
#include <map>
#include <set>
#include <tuple>

#include "nephele/error.h"
#include "voxel/common.h"

namespace nephele::voxel {
namespace {

using Tree = openvdb::FloatTree;
using Upper = Tree::RootNodeType::ChildNodeType;  // 32^3 slots (level 2)
using Lower = Upper::ChildNodeType;               // 16^3 slots (level 1)
using Leaf = Tree::LeafNodeType;                  // 8^3 voxels

// What each node takes in memory once read: the node, and a leaf's value buffer (allocated
// apart), and an entry of the root's std::map.
constexpr uint64_t kLeafBytes = sizeof(Leaf) + Leaf::SIZE * sizeof(float);
constexpr uint64_t kRootEntryBytes = 96;

// io/Compression.h: the per-grid compression flags and a node's value-metadata byte.
constexpr uint32_t kZip = 0x1, kActiveMask = 0x2, kBlosc = 0x4;
enum ValueMetadata : uint8_t {
  kOneInactive = 2,      // one inactive value follows
  kMaskNoInactive = 3,   // a selection mask follows
  kMaskOneInactive = 4,  // one inactive value and a selection mask follow
  kMaskTwoInactive = 5,  // two inactive values and a selection mask follow
  kAllValues = 6,        // every value is stored, active or not
};

// Root children and tiles sit at multiples of 4096 voxels; a file placing them beyond
// +-2^30 is taken for corrupt (and index arithmetic stays far from int32 overflow).
constexpr int32_t kMaxIndex = int32_t(1) << 30;

class Scanner {
 public:
  Scanner(const std::string& path, uint64_t file_bytes)
      : path_(path), in_(path, std::ios::binary), size_(file_bytes) {
    if (!in_) throw InputError(file_prefix(path) + "cannot be read");
  }

  VdbScan scan();

 private:
  [[noreturn]] void corrupt(const std::string& what) const {
    throw InputError(file_prefix(path_) + "is truncated or corrupt (" + context_ + what +
                     " at byte " + std::to_string(pos_) + ")");
  }
  uint64_t left() const { return size_ - pos_; }
  void need(uint64_t bytes, const char* what) const {
    if (bytes > left())
      corrupt(std::string(what) + " of " + std::to_string(bytes) + " bytes, " +
              std::to_string(left()) + " left");
  }
  template <class T>
  T read(const char* what) {
    need(sizeof(T), what);
    T value;
    in_.read(reinterpret_cast<char*>(&value), sizeof value);
    if (!in_) corrupt(std::string("unreadable ") + what);
    pos_ += sizeof value;
    return value;
  }
  void skip(uint64_t bytes, const char* what) {
    need(bytes, what);
    seek(pos_ + bytes);
  }
  void seek(uint64_t pos) {
    pos_ = pos;
    in_.seekg(std::streamoff(pos));
  }
  // util/Name.h: a uint32 length, then the bytes.
  std::string read_string(const char* what) {
    const uint32_t bytes = read<uint32_t>(what);
    if (bytes > kMaxVdbNameBytes)
      corrupt(std::string(what) + " of " + std::to_string(bytes) + " bytes (at most " +
              std::to_string(kMaxVdbNameBytes) + ")");
    need(bytes, what);
    std::string text(bytes, '\0');
    in_.read(text.data(), bytes);
    if (!in_) corrupt(std::string("unreadable ") + what);
    pos_ += bytes;
    return text;
  }
  // util/NodeMasks.h: a node's mask, 64-bit words of one bit a slot.
  std::vector<uint64_t> read_mask(uint32_t slots, const char* what) {
    need(slots / 8, what);
    std::vector<uint64_t> words(slots / 64);
    in_.read(reinterpret_cast<char*>(words.data()), slots / 8);
    if (!in_) corrupt(std::string("unreadable ") + what);
    pos_ += slots / 8;
    return words;
  }

  void header();
  void skip_metadata(const char* what);
  void transform();
  void grid(VdbGridInfo& info, uint64_t begin, bool half);
  void tree(VdbGridInfo& info);
  void internal_node(int level, VdbGridInfo& info, uint64_t& leaves);
  void values(uint32_t slots, uint32_t active);
  void add_bytes(VdbGridInfo& info, uint64_t bytes) const;

  std::string path_;
  std::ifstream in_;
  uint64_t size_, pos_ = 0;
  bool offsets_ = false;  // the file records where each grid ends (io::File's)
  uint32_t compression_ = 0;
  bool half_ = false;
  std::string context_;  // 'grid "name": ' while a grid is walked
};

// io/Archive.cc readHeader: int64 magic, uint32 file version, two uint32 library version
// numbers, a byte saying whether grid offsets are recorded, and the UUID as 36 characters.
void Scanner::header() {
  if (size_ < 8 || read<int64_t>("magic number") != openvdb::OPENVDB_MAGIC)
    throw InputError(file_prefix(path_) +
                     "is not a readable OpenVDB file (no OpenVDB magic number; a .vdb with a "
                     "float grid \"density\" is required)");
  const uint32_t version = read<uint32_t>("file version");
  if (version < openvdb::OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION ||
      version > openvdb::OPENVDB_FILE_VERSION)
    throw InputError(file_prefix(path_) + "is OpenVDB file format " + std::to_string(version) +
                     " (formats 222 to " + std::to_string(openvdb::OPENVDB_FILE_VERSION) +
                     ", OpenVDB 3 and later, are read)");
  skip(8, "library version");
  const uint8_t offsets = read<uint8_t>("grid offsets flag");
  if (offsets > 1) corrupt("grid offsets flag " + std::to_string(offsets));
  offsets_ = offsets == 1;
  // boost's uuid reader skips white space: only the exact form keeps its reading in step.
  need(36, "UUID");
  std::string uuid(36, '\0');
  in_.read(uuid.data(), 36);
  for (int i = 0; i < 36; ++i) {
    const bool dash = i == 8 || i == 13 || i == 18 || i == 23;
    if (dash ? uuid[i] != '-' : !std::isxdigit(static_cast<unsigned char>(uuid[i])))
      corrupt("malformed UUID");
  }
  pos_ += 36;
}

// MetaMap.cc: a uint32 count, then name, type name, a uint32 byte count and the value. The
// scan skips it; OpenVDB is given none (its readers trust the sizes inside some values).
void Scanner::skip_metadata(const char* what) {
  const uint32_t count = read<uint32_t>(what);
  if (uint64_t(count) * 12 > left()) corrupt(std::string(what) + " count " + std::to_string(count));
  for (uint32_t i = 0; i < count; ++i) {
    skip(read<uint32_t>("metadata name"), "metadata name");
    skip(read<uint32_t>("metadata type"), "metadata type");
    skip(read<uint32_t>("metadata value"), "metadata value");
  }
}

// math/Transform.cc: the map's type name, then its Vec3d or Mat4d members (Maps.h read()).
void Scanner::transform() {
  static const std::map<std::string, uint64_t> kLinearMapBytes = {
      {"AffineMap", 128},
      {"UnitaryMap", 128},
      {"ScaleMap", 5 * 24},
      {"UniformScaleMap", 5 * 24},
      {"TranslationMap", 24},
      {"ScaleTranslateMap", 6 * 24},
      {"UniformScaleTranslateMap", 6 * 24}};
  const std::string type = read_string("transform type");
  if (type == "NonlinearFrustumMap")
    throw InputError(file_prefix(path_) + context_ +
                     "has a frustum transform (a linear transform is required)");
  const auto map = kLinearMapBytes.find(type);
  if (map == kLinearMapBytes.end())
    corrupt("unknown transform \"" + shorten_for_message(type) + "\"");
  skip(map->second, "transform");
}

void Scanner::add_bytes(VdbGridInfo& info, uint64_t bytes) const {
  info.tree_bytes += bytes;
  if (info.tree_bytes > kMaxVdbTreeBytes)
    throw InputError(file_prefix(path_) + context_ + "takes more than " +
                     std::to_string(kMaxVdbTreeBytes >> 20) +
                     " MiB in memory (a float tree of at most " +
                     std::to_string(kMaxVdbTreeBytes >> 20) + " MiB is read)");
}

// io/Compression.h readCompressedValues: a node's `slots` values, of which `active` are on.
void Scanner::values(uint32_t slots, uint32_t active) {
  const uint8_t meta = read<uint8_t>("value metadata");
  if (meta > kAllValues) corrupt("value metadata " + std::to_string(meta));
  if (meta == kOneInactive || meta == kMaskOneInactive || meta == kMaskTwoInactive)
    skip(meta == kMaskTwoInactive ? 8 : 4, "inactive values");
  if (meta >= kMaskNoInactive && meta <= kMaskTwoInactive) skip(slots / 8, "selection mask");
  // With mask compression only the active values are stored (unless all are).
  const uint64_t count = (compression_ & kActiveMask) && meta != kAllValues ? active : slots;
  // HalfReader reads nothing for no values; readData reads a chunk's size even then.
  if (half_ && count == 0) return;
  const uint64_t raw = count * (half_ ? 2 : 4);
  if (!(compression_ & (kZip | kBlosc))) return skip(raw, "values");
  // zipFromStream / bloscFromStream: an int64 size, negative for raw bytes. OpenVDB reads a
  // raw chunk into its buffer before comparing sizes, and allocates a compressed one whole.
  const int64_t bytes = read<int64_t>("chunk size");
  if (bytes <= 0) {
    if (bytes != -int64_t(raw))
      corrupt("an uncompressed chunk of " + std::to_string(bytes) + " bytes for " +
              std::to_string(raw));
    return skip(raw, "uncompressed chunk");
  }
  // zlib's and blosc's worst cases stay well inside this.
  if (uint64_t(bytes) > raw + raw / 64 + 64)
    corrupt("a compressed chunk of " + std::to_string(bytes) + " bytes for " + std::to_string(raw));
  skip(uint64_t(bytes), "compressed chunk");
}

// tree/InternalNode.h readTopology: child mask, value mask, the node's values, then each
// child's topology in slot order (a leaf's topology is its value mask).
void Scanner::internal_node(int level, VdbGridInfo& info, uint64_t& leaves) {
  const uint32_t slots = level == 2 ? Upper::NUM_VALUES : Lower::NUM_VALUES;
  add_bytes(info, level == 2 ? sizeof(Upper) : sizeof(Lower));
  const std::vector<uint64_t> children = read_mask(slots, "child mask");
  const std::vector<uint64_t> on = read_mask(slots, "value mask");
  uint32_t active = 0, child_count = 0;
  for (size_t w = 0; w < on.size(); ++w) {
    if (children[w] & on[w]) corrupt("a node slot both child and active tile");
    active += std::popcount(on[w]);
    child_count += std::popcount(children[w]);
  }
  values(slots, active);
  for (uint32_t c = 0; c < child_count; ++c) {
    if (level == 2) {
      internal_node(1, info, leaves);
    } else {
      add_bytes(info, kLeafBytes);
      skip(Leaf::NUM_VALUES / 8, "leaf value mask");
      ++leaves;
    }
  }
}

// tree/RootNode.h readTopology (after TreeBase's uint32 buffer count): the background, the
// tile and child counts, the tiles (origin, value, active byte), the children (origin, node);
// then readBuffers: each leaf's value mask and values, as many as the topology has leaves.
void Scanner::tree(VdbGridInfo& info) {
  if (read<int32_t>("buffer count") != 1) corrupt("buffer count other than 1");
  read<float>("background");
  const uint32_t tiles = read<uint32_t>("tile count");
  const uint32_t children = read<uint32_t>("child count");
  if (uint64_t(tiles) * 17 + uint64_t(children) * (12 + Upper::NUM_VALUES / 4) > left())
    corrupt(std::to_string(tiles) + " root tiles and " + std::to_string(children) + " children");
  add_bytes(info, (uint64_t(tiles) + children) * kRootEntryBytes);
  // OpenVDB keys root entries by origin: a repeated one would replace (and orphan) the
  // first, and its buffers would no longer follow the topology.
  std::set<std::tuple<int32_t, int32_t, int32_t>> origins;
  const auto origin = [&](const char* what) {
    int32_t xyz[3];
    for (int32_t& c : xyz) {
      c = read<int32_t>(what);
      if (c % int32_t(Upper::DIM) != 0 || c < -kMaxIndex || c > kMaxIndex)
        corrupt(std::string(what) + " at index " + std::to_string(c));
    }
    if (!origins.emplace(xyz[0], xyz[1], xyz[2]).second) corrupt(std::string("repeated ") + what);
  };
  for (uint32_t t = 0; t < tiles; ++t) {
    origin("root tile");
    read<float>("tile value");
    // Read as a bool: any byte but 0 or 1 is undefined behaviour.
    if (read<uint8_t>("tile state") > 1) corrupt("tile state other than 0 or 1");
  }
  uint64_t leaves = 0;
  for (uint32_t c = 0; c < children; ++c) {
    origin("root child");
    internal_node(2, info, leaves);
  }
  for (uint64_t l = 0; l < leaves; ++l) {
    const std::vector<uint64_t> on = read_mask(Leaf::NUM_VALUES, "leaf value mask");
    uint32_t active = 0;
    for (uint64_t w : on) active += std::popcount(w);
    values(Leaf::NUM_VALUES, active);
  }
}

// A grid's metadata map holding only what its reading needs: whether its values are stored
// as half floats (Grid.cc: the flag is this metadata, replaced as the map is read).
std::string half_float_metadata(bool half) {
  std::string map;
  const auto append_u32 = [&](uint32_t v) { map.append(reinterpret_cast<const char*>(&v), 4); };
  const auto append_string = [&](const std::string& text) {
    append_u32(uint32_t(text.size()));
    map += text;
  };
  append_u32(1);
  append_string(openvdb::GridBase::META_SAVE_HALF_FLOAT);
  append_string(openvdb::BoolMetadata::staticTypeName());
  append_u32(1);
  map += char(half ? 1 : 0);
  return map;
}

// io/Archive.cc doReadGrid, after the descriptor: uint32 compression flags, the grid's
// metadata, its transform, then (unless an instance) its topology and buffers.
void Scanner::grid(VdbGridInfo& info, uint64_t begin, bool half) {
  compression_ = read<uint32_t>("compression flags");
  if (compression_ & ~(kZip | kActiveMask | kBlosc))
    corrupt("compression flags " + std::to_string(compression_));
  half_ = half;
  info.segments.push_back({begin, pos_ - begin, {}});
  info.segments.push_back({0, 0, half_float_metadata(half)});
  skip_metadata("grid metadata");
  const uint64_t rest = pos_;
  transform();
  if (!info.instance) tree(info);
  info.segments.push_back({rest, pos_ - rest, {}});
  info.walked = true;
}

// The value type a grid type name holds ("Tree_float_5_4_3" holds "float").
std::string value_type_of(const std::string& type) {
  if (!openvdb::GridBase::isRegistered(type)) return shorten_for_message(type);
  return openvdb::GridBase::createGrid(type)->valueType();
}

// io/Archive.cc: header, file metadata, int32 grid count; then per grid its descriptor
// (io/GridDescriptor.cc: unique name, type name, instance parent's name, and three int64
// offsets: grid start, buffers start, grid end) and the grid.
VdbScan Scanner::scan() {
  VdbScan result;
  header();
  result.header.push_back({0, pos_, {}});
  skip_metadata("file metadata");
  result.header.push_back({0, 0, std::string(4, '\0')});  // no file metadata
  const int32_t count = read<int32_t>("grid count");
  // A descriptor takes at least 3 lengths and 3 offsets.
  if (count < 0 || uint64_t(count) * 36 > left()) corrupt("grid count " + std::to_string(count));
  static const std::string kHalfSuffix = "_HalfFloat";
  for (int32_t g = 0; g < count; ++g) {
    const uint64_t begin = pos_;
    VdbGridInfo info;
    info.name = read_string("grid name");
    info.name = info.name.substr(0, info.name.find('\x1e'));  // a duplicate's suffix
    context_ = "grid \"" + shorten_for_message(info.name) + "\": ";
    std::string type = read_string("grid type");
    const bool half = type.size() > kHalfSuffix.size() && type.ends_with(kHalfSuffix);
    if (half) type.resize(type.size() - kHalfSuffix.size());
    info.value_type = value_type_of(type);
    info.instance = !read_string("instance parent").empty();
    read<int64_t>("grid offset");
    read<int64_t>("buffer offset");
    const int64_t end = read<int64_t>("grid end");
    const uint64_t grid_start = pos_;
    if (type == openvdb::FloatGrid::gridType()) {
      grid(info, begin, half);
      if (offsets_ && uint64_t(end) != pos_) corrupt("grid end offset " + std::to_string(end));
    } else if (offsets_) {
      if (end < int64_t(grid_start) || uint64_t(end) > size_)
        corrupt("grid end offset " + std::to_string(end));
      seek(uint64_t(end));
    } else {
      result.grids.push_back(info);
      result.stopped = true;
      return result;
    }
    result.grids.push_back(info);
    context_.clear();
  }
  return result;
}

}  // namespace

VdbScan scan_openvdb(const std::string& path, uint64_t file_bytes) {
  return Scanner(path, file_bytes).scan();
}

}  // namespace nephele::voxel

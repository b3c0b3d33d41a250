// nephele — voxel clouds: a structural pre-scan of OpenVDB files. OpenVDB's reader trusts the
// counts and sizes a file declares (string lengths, node counts, compressed-chunk sizes) and
// allocates what they say; the scan walks the same structure first, checks each against the
// bytes left in the file and nephele's limits, and says which bytes OpenVDB may then read.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace nephele::voxel {

// A byte range of the file, or (where `literal` is set) bytes of nephele's own.
struct VdbSegment {
  uint64_t offset = 0, bytes = 0;
  std::string literal;
};

struct VdbGridInfo {
  std::string name;                  // the grid's name (a duplicate's "[N]" suffix removed)
  std::string value_type;            // "float", "vec3s", ...; the file's type name when unknown
  bool walked = false;               // a float grid whose every byte the scan checked
  bool instance = false;             // shares another grid's tree
  uint64_t tree_bytes = 0;           // what its tree takes in memory once read (an estimate)
  std::vector<VdbSegment> segments;  // where walked: the grid as OpenVDB may read it
};

struct VdbScan {
  std::vector<VdbSegment> header;  // the file's header, then an empty file metadata map
  std::vector<VdbGridInfo> grids;  // in file order
  // A stream (no grid offsets) holds a grid of a type the scan cannot walk: the grids after
  // it are unknown. It is the last of `grids`.
  bool stopped = false;
};

// The most a float tree may take in memory (nodes as OpenVDB allocates them).
constexpr uint64_t kMaxVdbTreeBytes = uint64_t(1) << 30;
// The longest grid name or type name read.
constexpr uint32_t kMaxVdbNameBytes = 4096;

// Walks an OpenVDB file of `file_bytes` (file format 222 to 224: OpenVDB 3 and later) and
// returns its grids. Throws InputError of one line: "is not a readable OpenVDB file", "is
// truncated or corrupt (...)", an unsupported version or transform, or a tree over
// kMaxVdbTreeBytes. The segments of a walked grid hold none of the file's metadata (only
// nephele's own half-float flag): OpenVDB then parses only what the scan checked (the grid's
// descriptor, compression flags, transform and tree).
VdbScan scan_openvdb(const std::string& path, uint64_t file_bytes);

}  // namespace nephele::voxel

// Voxel clouds from hostile OpenVDB files: a corrupt byte, a truncation or an inflated count
// is one line of InputError within bounded memory, never a runaway allocation; valid files
// with NaN or inf where no voxel is active, or grids thinner than a dense voxel, load.
#include <gtest/gtest.h>
#include <openvdb/io/Compression.h>
#include <openvdb/openvdb.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>

#include "nephele/error.h"
#include "support/fuzz_support.h"
#include "support/vdb_files.h"
#include "voxel/voxel_grid.h"

namespace nephele::voxel {
namespace {

namespace fs = std::filesystem;
using test::kAsan;
using test::leaks_found;

// How much a batch of loads may raise the process's peak resident memory. AddressSanitizer
// keeps up to 256 MB of freed memory in quarantine.
constexpr int64_t kMaxGrowthMb = kAsan ? 640 : 256;

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}
void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}
template <class T>
void put(std::string& bytes, size_t at, T value) {
  std::memcpy(&bytes[at], &value, sizeof value);
}
template <class T>
T get(const std::string& bytes, size_t at) {
  T value;
  std::memcpy(&value, &bytes[at], sizeof value);
  return value;
}

// A line of /proc/self/status in kB ("VmHWM:", "VmSize:").
int64_t status_kb(const char* key) {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key, 0) == 0) return std::stoll(line.substr(std::strlen(key)));
  return -1;
}

// Loads each file: each must load (where `may_load`) or throw InputError of one line naming
// it, and the peak resident memory must grow by kMaxGrowthMb at most. Returns what failed.
std::string load_all(const std::vector<std::string>& files, bool may_load) {
  if (!kAsan) {
    // A runaway ends as bad_alloc (a failure below) rather than taking the machine.
    const rlim_t limit = rlim_t(status_kb("VmSize:")) * 1024 + (rlim_t(3) << 30);
    const rlimit as{limit, limit};
    setrlimit(RLIMIT_AS, &as);
  }
  const int64_t before_kb = status_kb("VmHWM:");
  std::string problems;
  for (const std::string& file : files) {
    try {
      load_voxel_cloud(file, 16);
      if (!may_load) problems += file + ": loaded\n";
    } catch (const InputError& e) {
      const std::string message = e.what();
      if (message.find('\n') != std::string::npos ||
          message.find(fs::path(file).filename().string() + ": ") == std::string::npos)
        problems += file + ": not one line naming it: " + message + "\n";
    } catch (const std::exception& e) {
      problems += file + ": " + e.what() + " (not an InputError)\n";
    }
  }
  const int64_t growth_mb = (status_kb("VmHWM:") - before_kb) / 1024;
  if (growth_mb > kMaxGrowthMb)
    problems += "peak memory grew by " + std::to_string(growth_mb) + " MB\n";
  return problems;
}

// The InputError's message loading `file` gives, or "loaded".
std::string load_message(const std::string& file) {
  try {
    load_voxel_cloud(file, 16);
  } catch (const InputError& e) {
    return e.what();
  }
  return "loaded";
}

class VoxelIoHostile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(NEPHELE_TEST_OUTPUT_DIR) /
           ("voxel_io_hostile_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // The bytes of `make-cloud --type cumulus --resolution 16`: a stream without grid offsets.
  std::string cloud_stream() {
    write_vdb(make_cloud(CloudPreset::Cumulus, 1, 16), path("c16.vdb"));
    return read_bytes(path("c16.vdb"));
  }
  // `bytes` with `edit` applied, as a file named `name`.
  std::string variant(const std::string& name, std::string bytes,
                      const std::function<void(std::string&)>& edit) {
    edit(bytes);
    write_bytes(path(name), bytes);
    return path(name);
  }
  // Runs `files` through load_all in a fresh process (a runaway must not take this one).
  void expect_bounded(const std::vector<std::string>& files, bool may_load) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_EXIT(
        {
          const std::string problems = load_all(files, may_load);
          std::fputs(problems.c_str(), stderr);
          std::fflush(stderr);
          std::_Exit(problems.empty() ? 0 : 1);
        },
        ::testing::ExitedWithCode(0), "");
  }
  fs::path dir_;
};

// Where write_vdb's stream holds its root's counts and its first node's compressed values.
struct StreamLayout {
  size_t grid_count = 61, name_length = 65, grid_metadata_count = 128;
  size_t metadata_value_bytes, tiles, children, chunk;
};
StreamLayout layout_of(const std::string& bytes) {
  StreamLayout at;
  size_t p = at.grid_metadata_count + 4;
  p += 4 + get<uint32_t>(bytes, p);  // the first entry's name
  p += 4 + get<uint32_t>(bytes, p);  // its type name
  at.metadata_value_bytes = p;
  // UniformScaleTranslateMap: 6 Vec3d; then buffer count and background.
  const size_t map = bytes.find("UniformScaleTranslateMap");
  at.tiles = map + 24 + 144 + 8;
  at.children = at.tiles + 4;
  // The first child: two 4096-byte masks, the metadata byte, its extras, the chunk's size.
  const size_t meta = at.children + 4 + 12 + 8192;
  const int m = bytes[meta];
  at.chunk = meta + 1 + (m == 2 || m == 4 ? 4 : m == 5 ? 8 : 0) + (m >= 3 && m <= 5 ? 4096 : 0);
  return at;
}

TEST_F(VoxelIoHostile, TheIssuesByte129IsOneLineInBoundedMemory) {
  const std::string file =
      variant("b129.vdb", cloud_stream(), [](std::string& b) { b[129] = '\xe2'; });
  expect_bounded({file}, /*may_load=*/false);
}

TEST_F(VoxelIoHostile, InflatedCountsAndSizesAreOneLineInBoundedMemory) {
  const std::string bytes = cloud_stream();
  const StreamLayout at = layout_of(bytes);
  ASSERT_EQ(get<int32_t>(bytes, at.grid_count), 2);
  ASSERT_EQ(get<uint32_t>(bytes, at.children), 1u);
  std::vector<std::string> files;
  const auto add = [&](const std::string& name, const std::function<void(std::string&)>& edit) {
    files.push_back(variant(name, bytes, edit));
  };
  add("grids.vdb", [&](std::string& b) { put<int32_t>(b, at.grid_count, 0x7fffffff); });
  add("name.vdb", [&](std::string& b) { put<uint32_t>(b, at.name_length, 0xf0000000u); });
  add("meta.vdb", [&](std::string& b) { put<uint32_t>(b, at.grid_metadata_count, ~0u); });
  add("metabytes.vdb", [&](std::string& b) { put<uint32_t>(b, at.metadata_value_bytes, ~0u); });
  add("tiles.vdb", [&](std::string& b) { put<uint32_t>(b, at.tiles, ~0u); });
  add("children.vdb", [&](std::string& b) { put<uint32_t>(b, at.children, ~0u); });
  add("children2.vdb", [&](std::string& b) { put<uint32_t>(b, at.children, 2); });
  add("chunk40.vdb", [&](std::string& b) { put<int64_t>(b, at.chunk, int64_t(1) << 40); });
  add("chunk62.vdb", [&](std::string& b) { put<int64_t>(b, at.chunk, int64_t(1) << 62); });
  add("raw62.vdb", [&](std::string& b) { put<int64_t>(b, at.chunk, -(int64_t(1) << 62)); });
  add("version.vdb", [&](std::string& b) { put<uint32_t>(b, 8, 0xffffu); });
  for (size_t at_byte : {61, 66, 72, 133})
    add("flip" + std::to_string(at_byte) + ".vdb",
        [&](std::string& b) { b[at_byte] = char(b[at_byte] ^ 0xe2); });
  for (size_t keep :
       {size_t(10), size_t(64), size_t(130), size_t(400), bytes.size() / 2, bytes.size() - 1})
    add("cut" + std::to_string(keep) + ".vdb", [&](std::string& b) { b.resize(keep); });
  expect_bounded(files, /*may_load=*/false);

  // The same, read here: each message says what is wrong.
  EXPECT_NE(load_message(path("chunk40.vdb"))
                .find("is truncated or corrupt (grid \"density\": a "
                      "compressed chunk of 1099511627776 bytes"),
            std::string::npos)
      << load_message(path("chunk40.vdb"));
  EXPECT_NE(load_message(path("version.vdb")).find("is OpenVDB file format 65535"),
            std::string::npos);
  EXPECT_NE(load_message(path("cut64.vdb")).find("is truncated or corrupt ("), std::string::npos);
}

// Each of 200 bytes of a stream and of a file with grid offsets flipped in turn: every
// result loads or is one line, in bounded memory, quickly.
TEST_F(VoxelIoHostile, FlippedBytesLoadOrAreOneLine) {
  const auto start = std::chrono::steady_clock::now();
  test::write_fog_balls_vdb(path("balls.vdb"), {"temperature", "density"});
  std::vector<std::string> files;
  std::mt19937 rng(40);
  for (const auto& [name, bytes] :
       {std::pair{"stream", cloud_stream()}, {"file", read_bytes(path("balls.vdb"))}}) {
    for (int n = 0; n < 200; ++n) {
      // Half in the first 700 bytes (header, descriptors, metadata, transform, root), half
      // anywhere.
      const size_t at = rng() % (n < 100 ? std::min<size_t>(700, bytes.size()) : bytes.size());
      const char mask = char(1 + rng() % 255);
      files.push_back(variant(std::string(name) + std::to_string(n) + ".vdb", bytes,
                              [&](std::string& b) { b[at] = char(b[at] ^ mask); }));
    }
  }
  expect_bounded(files, /*may_load=*/true);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, kAsan ? 120.0 : 15.0);
}

// A transform made NaN by a changed word (FuzzFiles, vdb-stream #132): the extent is refused
// before it is turned into voxel counts (the NaN was converted to an int, which UBSan reports).
TEST_F(VoxelIoHostile, ANonFiniteTransformIsRefusedBeforeItIsCounted) {
  const std::string file = variant("nan_transform.vdb", cloud_stream(),
                                   [](std::string& b) { put<uint32_t>(b, 600, 0x54); });
  expect_bounded({file}, /*may_load=*/false);
}

// NanoVDB files with bytes flipped: NanoVDB's validator walked the tree through corrupt node
// offsets to compute its checksum before it checked them, and crashed (three bytes found by
// FuzzFiles); every offset is now checked against the file first. Then 80 flips anywhere
// (FuzzFiles flips more).
TEST_F(VoxelIoHostile, NanoVdbOffsetsAreCheckedBeforeTheTreeIsWalked) {
  test::write_fog_balls_nvdb(path("balls.nvdb"), {"density"});
  const std::string bytes = read_bytes(path("balls.nvdb"));
  ASSERT_GT(bytes.size(), 900u);
  expect_bounded({variant("fuzz44.nvdb", bytes,
                          [](std::string& b) {
                            b[826] = char(b[826] ^ 0xe3);
                            b[900] = char(b[900] ^ 0xa8);
                            b[414] = char(b[414] ^ 0xf7);
                          })},
                 /*may_load=*/false);
  std::vector<std::string> files;
  std::mt19937 rng(44);
  for (int n = 0; n < 80; ++n) {
    const size_t at = rng() % bytes.size();
    const char mask = char(1 + rng() % 255);
    files.push_back(variant("flip" + std::to_string(n) + ".nvdb", bytes,
                            [&](std::string& b) { b[at] = char(b[at] ^ mask); }));
  }
  expect_bounded(files, /*may_load=*/true);
}

// A NanoVDB file of another major version, in its segment's header or in its grid's own (the
// grid's checksum cleared, as a writer may leave it): one line naming the version, and nothing
// leaked. Version::c_str(), which mallocs the text it returns, leaked it on both paths (in
// NanoVDB's validator on the second); LeakSanitizer found it through FuzzFiles' .nvdb cases.
TEST_F(VoxelIoHostile, NanoVdbOfAnotherVersionIsOneLineAndLeaksNothing) {
  test::write_fog_balls_nvdb(path("balls.nvdb"), {"density"});
  const std::string bytes = read_bytes(path("balls.nvdb"));
  const auto version = [](uint32_t major, uint32_t minor, uint32_t patch) {
    return major << 21 | minor << 10 | patch;
  };
  // The segment's header: magic, version, grid count, codec; the grid's: magic, checksum,
  // version.
  ASSERT_EQ(bytes.compare(0, 8, "NanoVDB0"), 0);
  const size_t grid = bytes.find("NanoVDB0", 8);
  ASSERT_NE(grid, std::string::npos);
  ASSERT_EQ(get<uint32_t>(bytes, 8) >> 21, 32u);
  ASSERT_EQ(get<uint32_t>(bytes, grid + 16) >> 21, 32u);
  const std::string older =
      variant("older.nvdb", bytes, [&](std::string& b) { put<uint32_t>(b, 8, version(31, 4, 0)); });
  const std::string newer =
      variant("newer.nvdb", bytes, [&](std::string& b) { put<uint32_t>(b, 8, version(33, 1, 2)); });
  const std::string grid_older = variant("grid_older.nvdb", bytes, [&](std::string& b) {
    put<uint64_t>(b, grid + 8, ~uint64_t(0));  // no checksum
    put<uint32_t>(b, grid + 16, version(31, 4, 0));
  });
  const std::vector<std::pair<std::string, std::string>> expected = {
      {older, "older.nvdb: is NanoVDB version 31.4.0 (version 32.x is required)"},
      {newer, "newer.nvdb: is NanoVDB version 33.1.2 (version 32.x is required)"},
      {grid_older,
       "grid_older.nvdb: grid \"density\" is NanoVDB version 31.4.0 (version 32.x is required)"},
  };
  for (const auto& [file, text] : expected) {
    const std::string got = load_message(file);
    EXPECT_NE(got.find(text), std::string::npos) << got;
    EXPECT_EQ(got.find('\n'), std::string::npos) << got;
  }
  EXPECT_FALSE(leaks_found()) << "LeakSanitizer's report is above";
}

TEST_F(VoxelIoHostile, OtherWritersFilesLoadWithoutOpenVdbsWarnings) {
  using namespace openvdb::io;
  openvdb::initialize();  // what it may say of its own set-up is not what is tested
  testing::internal::CaptureStderr();
  for (uint32_t compression :
       std::vector<uint32_t>{COMPRESS_NONE, COMPRESS_ZIP | COMPRESS_ACTIVE_MASK,
                             COMPRESS_BLOSC | COMPRESS_ACTIVE_MASK, COMPRESS_ACTIVE_MASK})
    for (bool half : {false, true})
      for (bool stream : {false, true}) {
        const std::string file = path("balls" + std::to_string(compression) + (half ? "h" : "f") +
                                      (stream ? "s" : "o") + ".vdb");
        test::write_fog_balls_vdb_as(file, {"temperature", "density", "density"}, compression, half,
                                     stream);
        const VoxelGrid grid = load_voxel_cloud(file, 64);
        EXPECT_EQ(grid.dims, glm::ivec3(17)) << file;
        EXPECT_NEAR(grid.density[grid.index(8, 8, 8)], 1.0f, 2e-3f) << file;
      }
  // More than one grid named "density": OpenVDB's reader warned of it, in colour.
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");

  test::write_vector_then_density_stream(path("velocity.vdb"));
  try {
    load_voxel_cloud(path("velocity.vdb"), 16);
    ADD_FAILURE() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("has grid \"velocity\" of vec3s values before any grid "
                                         "\"density\""),
              std::string::npos)
        << e.what();
  }
}

// --- valid files the resampling lost ------------------------------------------------------

// The density of the dense voxel holding world point p.
float density_at(const VoxelGrid& grid, glm::vec3 p_m) {
  const glm::ivec3 v((p_m - grid.origin_m - grid.file_anchor_m) / grid.voxel_m);
  return grid.density[grid.index(v.x, v.y, v.z)];
}

TEST_F(VoxelIoHostile, NanAndInfWhereNothingIsActiveLoad) {
  // Coarser dense voxels than the file's (40 voxels into 16): samples between voxel centres
  // met the NaN and inf.
  const std::vector<test::VoxelBox> block = {{{0, 0, 0}, {39, 39, 39}}};
  const float nan = std::nanf(""), inf = INFINITY;
  test::write_boxes_vdb(path("nan.vdb"), block, 1.0f, nan);
  test::write_boxes_vdb(path("inf.vdb"), block, 1.0f, inf);
  test::write_boxes_vdb(path("minf.vdb"), block, 1.0f, -inf);
  test::write_boxes_vdb(path("nanbg.vdb"), block, 1.0f, 0.0f, nan);
  test::write_boxes_vdb(path("infbg.vdb"), block, 1.0f, inf, inf);
  for (const char* name : {"nan.vdb", "inf.vdb", "minf.vdb", "nanbg.vdb", "infbg.vdb"}) {
    SCOPED_TRACE(name);
    const VoxelGrid grid = load_voxel_cloud(path(name), 16);
    for (float v : grid.density) ASSERT_TRUE(std::isfinite(v));
    for (float d : grid.sdf_m) ASSERT_TRUE(std::isfinite(d));
    EXPECT_NEAR(density_at(grid, glm::vec3(20.0f)), 1.0f, 1e-4f);
  }
  // A non-finite active value stays refused.
  test::write_boxes_vdb(path("active.vdb"), block, nan);
  EXPECT_THROW(load_voxel_cloud(path("active.vdb"), 32), InputError);
}

TEST_F(VoxelIoHostile, ThinGridsKeepTheirDensityAndMass) {
  struct Case {
    const char* name;
    std::vector<test::VoxelBox> boxes;
  };
  const std::vector<Case> cases = {
      {"sheet.vdb", {{{0, 0, 0}, {2047, 2047, 0}}}},
      {"line.vdb", {{{0, 0, 0}, {2999, 0, 0}}}},
      {"far_voxel.vdb", {{{0, 0, 0}, {3, 3, 3}}, {{2500, 1500, 100}, {2500, 1500, 100}}}},
      {"tiles.vdb", {{{0, 0, 0}, {127, 127, 7}}, {{1000, 0, 0}, {1000, 0, 0}}}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    test::write_boxes_vdb(path(c.name), c.boxes, 1.0f, std::nanf(""));
    const VoxelGrid grid = load_voxel_cloud(path(c.name), 32);
    double mass = 0.0, file_mass = 0.0;
    for (float v : grid.density) mass += double(v) * grid.file_density_scale;
    mass *= std::pow(double(grid.voxel_m), 3.0);
    for (const test::VoxelBox& b : c.boxes) {
      double voxels = 1.0;
      for (int a = 0; a < 3; ++a) voxels *= b.hi[a] - b.lo[a] + 1;
      file_mass += voxels;
      // Every box keeps density where the file has it (the file's voxel centres are at
      // integer metres).
      EXPECT_GT(density_at(grid, glm::vec3(b.lo[0], b.lo[1], b.lo[2])), 0.0f);
      EXPECT_GT(density_at(grid, glm::vec3(b.hi[0], b.hi[1], b.hi[2])), 0.0f);
    }
    EXPECT_NEAR(mass, file_mass, 1e-3 * file_mass);
  }
}

}  // namespace
}  // namespace nephele::voxel

// nephele's disk cache (render/disk_cache.h): a file reads back exactly what was written, and
// anything else (short, long, damaged, another texture's) reads as no file; the least recently
// used files go first when a kind of file takes more than its share; the base noise's name.
#include "render/disk_cache.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>

#include "render/modules/noise/noise.h"
#include "support/scoped_env.h"

namespace fs = std::filesystem;
using nephele::read_cache_file;
using nephele::write_cache_file;

namespace {

class DiskCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(NEPHELE_TEST_OUTPUT_DIR) / "disk_cache_test" /
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
  }
  static std::vector<uint8_t> texels(size_t n) {
    std::vector<uint8_t> t(n);
    for (size_t i = 0; i < n; ++i) t[i] = uint8_t(i * 37 + i / 251);
    return t;
  }
  fs::path dir_;
};

}  // namespace

TEST(DiskCacheHash, Fnv1a64OfKnownStrings) {
  const auto h = [](const std::string& s) {
    return nephele::fnv1a64({reinterpret_cast<const uint8_t*>(s.data()), s.size()});
  };
  EXPECT_EQ(h(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(h("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(h("foobar"), 0x85944171f73967e8ull);
}

TEST(NoiseCacheName, ChangesWithTheShaderTheDeviceAndTheSeed) {
  const std::vector<uint32_t> spirv = {0x07230203u, 1u, 2u, 3u}, other = {0x07230203u, 1u, 2u, 4u};
  const std::string a = nephele::noise_cache_name(spirv, "llvmpipe", 1);
  EXPECT_EQ(a, nephele::noise_cache_name(spirv, "llvmpipe", 1));
  EXPECT_NE(a, nephele::noise_cache_name(other, "llvmpipe", 1));
  EXPECT_NE(a, nephele::noise_cache_name(spirv, "NVIDIA H200", 1));
  EXPECT_NE(a, nephele::noise_cache_name(spirv, "llvmpipe", 2));
  EXPECT_EQ(a.rfind("base_noise_", 0), 0u) << a;
}

TEST_F(DiskCacheTest, ReadsBackWhatWasWritten) {
  const fs::path file = dir_ / "sub" / "noise.bin";  // its folders made
  const std::vector<uint8_t> t = texels(4096);
  ASSERT_TRUE(write_cache_file(file, t));
  EXPECT_EQ(read_cache_file(file, t.size()), t);
  // Nothing left beside it (the temporary was renamed).
  EXPECT_EQ(std::distance(fs::directory_iterator(file.parent_path()), fs::directory_iterator()), 1);
}

TEST_F(DiskCacheTest, AnythingElseReadsAsNoFile) {
  const fs::path file = dir_ / "noise.bin";
  const std::vector<uint8_t> t = texels(4096);
  EXPECT_FALSE(read_cache_file(file, t.size()));  // missing
  ASSERT_TRUE(write_cache_file(file, t));
  EXPECT_FALSE(read_cache_file(file, t.size() + 4));  // another texture's size
  EXPECT_FALSE(read_cache_file(file, t.size() - 4));
  const auto rewrite = [&](auto&& change) {
    std::ifstream in(file, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    change(bytes);
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  };
  rewrite([](std::string& b) { b[b.size() / 2] ^= 0x10; });  // a texel damaged
  EXPECT_FALSE(read_cache_file(file, t.size()));
  ASSERT_TRUE(write_cache_file(file, t));  // written over
  EXPECT_EQ(read_cache_file(file, t.size()), t);
  rewrite([](std::string& b) { b.resize(b.size() - 1); });  // cut short
  EXPECT_FALSE(read_cache_file(file, t.size()));
  ASSERT_TRUE(write_cache_file(file, t));
  rewrite([](std::string& b) { b[0] = 'X'; });  // not such a file
  EXPECT_FALSE(read_cache_file(file, t.size()));
}

// Of the files of a kind (named with its prefix), the least recently written or read go first;
// other kinds stay.
TEST_F(DiskCacheTest, PruningRemovesTheLeastRecentlyUsedOfAKind) {
  const std::vector<uint8_t> t = texels(100);
  const auto when = fs::file_time_type::clock::now();
  for (int i = 0; i < 4; ++i) {
    const fs::path f = dir_ / ("lighting_" + std::to_string(i) + ".bin");
    ASSERT_TRUE(write_cache_file(f, t));
    fs::last_write_time(f, when - std::chrono::hours(10 - i));  // 0 the oldest
  }
  ASSERT_TRUE(write_cache_file(dir_ / "base_noise_0.bin", t));
  fs::last_write_time(dir_ / "base_noise_0.bin", when - std::chrono::hours(20));
  ASSERT_TRUE(read_cache_file(dir_ / "lighting_0.bin", t.size()));  // read: now the newest
  const uint64_t file = fs::file_size(dir_ / "lighting_0.bin");
  nephele::prune_cache(dir_, "lighting_", 2 * file + file / 2);
  EXPECT_TRUE(fs::exists(dir_ / "lighting_0.bin"));
  EXPECT_FALSE(fs::exists(dir_ / "lighting_1.bin"));
  EXPECT_FALSE(fs::exists(dir_ / "lighting_2.bin"));
  EXPECT_TRUE(fs::exists(dir_ / "lighting_3.bin"));
  EXPECT_TRUE(fs::exists(dir_ / "base_noise_0.bin"));
  nephele::prune_cache(dir_ / "missing", "lighting_", 0);  // no folder: nothing to do
}

TEST_F(DiskCacheTest, AFolderThatCannotBeMadeIsNoError) {
  fs::create_directories(dir_);
  std::ofstream(dir_ / "plain") << "a file, not a folder";
  EXPECT_FALSE(write_cache_file(dir_ / "plain" / "noise.bin", texels(64)));
}

TEST(DiskCacheDir, FromTheEnvironment) {
  {
    ScopedEnv own("NEPHELE_CACHE_DIR", "/somewhere/cache");
    EXPECT_EQ(nephele::cache_dir(), fs::path("/somewhere/cache"));
  }
  {
    ScopedEnv none("NEPHELE_CACHE_DIR", "");  // set empty: no cache
    EXPECT_TRUE(nephele::cache_dir().empty());
  }
  ScopedEnv unset("NEPHELE_CACHE_DIR", std::nullopt);
  {
    ScopedEnv xdg("XDG_CACHE_HOME", "/x/cache");
    EXPECT_EQ(nephele::cache_dir(), fs::path("/x/cache/nephele"));
  }
  ScopedEnv no_xdg("XDG_CACHE_HOME", std::nullopt);
  {
    ScopedEnv home("HOME", "/home/someone");
    EXPECT_EQ(nephele::cache_dir(), fs::path("/home/someone/.cache/nephele"));
  }
  ScopedEnv no_home("HOME", std::nullopt);
  EXPECT_TRUE(nephele::cache_dir().empty());
}

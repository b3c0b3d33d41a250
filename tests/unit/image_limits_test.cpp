// The image files a scene reads (image/input_images.h): the weather map, the terrain's heights
// and its albedo map are refused from their headers, before anything is decoded, when they
// declare more than the stated limits or are corrupt, with one line naming the key, the value
// and what is allowed (issue 40, items 7 to 9). The files are a few kilobytes whatever size
// they declare, and none is decoded at its declared size.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/packing.hpp>
#include <iterator>
#include <string>

#include "image/input_images.h"
#include "nephele/error.h"
#include "nephele/image.h"
#include "nephele/scene_io.h"
#include "support/terrain_files.h"

namespace nephele {
namespace {

namespace fs = std::filesystem;

class ImageLimits : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(NEPHELE_TEST_OUTPUT_DIR) /
           ("image_limits_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& bytes) const {
    test::write_bytes(path(name), bytes);
    return path(name);
  }
  // The message validate_scene throws for the scene `edit` makes, "" when it accepts it.
  template <typename Edit>
  static std::string rejection(Edit edit) {
    Scene scene = load_preset("default");
    edit(scene);
    try {
      validate_scene(scene);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  static std::string weather_rejection(const std::string& file) {
    return rejection([&](Scene& s) { s.clouds.weather_map = file; });
  }
  // An EXR of 4 x 4 pixels whose header declares the data window (0, 0)-(w - 1, h - 1).
  std::string exr_declaring(const std::string& name, int w, int h) const {
    write_image(Image(4, 4), path(name));
    std::string bytes = read(path(name));
    const std::string tag = std::string("dataWindow") + '\0' + "box2i" + '\0';
    const size_t at = bytes.find(tag);
    EXPECT_NE(at, std::string::npos);
    const int32_t window[4] = {0, 0, w - 1, h - 1};
    std::memcpy(&bytes[at + tag.size() + 4], window, sizeof window);  // little-endian hosts
    return write(name, bytes);
  }
  static std::string read(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  fs::path dir_;
};

void expect_one_line_naming(const std::string& message, const std::string& start,
                            const std::string& what) {
  EXPECT_EQ(message.rfind(start, 0), 0u) << message;
  EXPECT_NE(message.find(what), std::string::npos) << "'" << what << "' in " << message;
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 0) << message;
}

// Item 9: a PNG declaring 12000 x 12000 RGBA (3.56 GB as float pixels) is refused from its
// header, and so are maps over the device's 16384 (item 7) and just over the limit, either way.
TEST_F(ImageLimits, OversizedWeatherMapsAreRefusedFromTheHeader) {
  const std::string idat =
      test::zlib_stored(std::string(64, '\0'));  // far too short: never decoded
  for (const auto& [w, h] :
       {std::pair{12000u, 12000u}, {16385u, 1u}, {1u, 16385u}, {8193u, 8192u}}) {
    const std::string file = write("big.png", test::png_bytes(w, h, 8, 6, idat));
    expect_one_line_naming(
        weather_rejection(file), "clouds.weather_map = \"",
        std::to_string(w) + " x " + std::to_string(h) +
            " pixels: at most 8192 a side are allowed; a weather map is an RGBA PNG");
  }
  // An EXR too: it was not checked at all.
  expect_one_line_naming(weather_rejection(exr_declaring("wide.exr", 9000, 4)),
                         "clouds.weather_map = \"",
                         "9000 x 4 pixels: at most 8192 a side are allowed");
  // At the limit, header-wise, it passes.
  EXPECT_EQ(weather_rejection(write("edge.png", test::png_bytes(8192, 4, 8, 6, idat))), "");
}

// Corruptions the header shows: refused when the scene is checked, naming the key and saying
// what a weather map must be.
TEST_F(ImageLimits, StructurallyCorruptWeatherMapsAreRefusedWhenTheSceneIsChecked) {
  const std::string good = test::png_rgba8_bytes(16, 16, 100);
  const struct {
    std::string name, bytes, expected;
  } cases[] = {
      {"truncated.png", good.substr(0, good.size() / 2),
       "is truncated: its 'IDAT' chunk at byte 33 declares"},
      {"no_iend.png", good.substr(0, good.size() - 12), "is truncated: it ends at byte"},
      {"zero_width.png", test::png_bytes(0, 16, 8, 6, test::zlib_stored("x")),
       "declares 0 x 16 pixels"},
      {"bad_depth.png", test::png_bytes(4, 4, 7, 6, test::zlib_stored("x")),
       "colour type 6 at 7 bits"},
      {"bomb.png", test::png_bytes(4, 4, 8, 6, test::zlib_stored(std::string(100000, '\0'))),
       "bytes of compressed pixel data, more than its 4 x 4 pixels can need"},
      {"empty.png", "", "is empty (0 bytes)"},
      {"lying.exr", exr_declaring("lying.exr", 8000, 8000),
       "is truncated or corrupt: its 8000 x 8000 pixels"},
  };
  for (const auto& c : cases) {
    const std::string file = c.name == "lying.exr" ? c.bytes : write(c.name, c.bytes);
    const std::string message = weather_rejection(file);
    expect_one_line_naming(message, "clouds.weather_map = \"", c.expected);
    EXPECT_NE(message.find(
                  "a weather map is an RGBA PNG (8 or 16 bits) or an EXR of at most 8192 x 8192"),
              std::string::npos)
        << message;
  }
}

// Corruptions only decoding finds are refused when the map is read, before stb decodes it, in
// one line naming the key; a bad CRC (stb does not check it) reads as the pixels it holds.
TEST_F(ImageLimits, CorruptWeatherMapDataIsRefusedNamingTheKey) {
  std::string rows;
  for (int y = 0; y < 8; ++y) rows += '\0' + std::string(8 * 4, char(200));
  std::string bad_block = test::zlib_stored(rows);
  bad_block[2] = char(0x07);  // BFINAL, reserved block type 3
  const struct {
    std::string name, bytes, expected;
  } cases[] = {
      {"bad_block.png", test::png_bytes(8, 8, 8, 6, bad_block), "cannot decode the PNG ("},
      {"short.png", test::png_bytes(8, 8, 8, 6, test::zlib_stored(rows.substr(0, 100))),
       "is truncated: its pixel data inflates to 100 of the 264 bytes"},
      {"long.png", test::png_bytes(8, 8, 8, 6, test::zlib_stored(rows + std::string(30000, '\0'))),
       "inflates to more than its 8 x 8 pixels need"},
  };
  for (const auto& c : cases) {
    const std::string file = write(c.name, c.bytes);
    try {
      read_weather_map(file);
      ADD_FAILURE() << c.name << " was read";
    } catch (const InputError& e) {
      expect_one_line_naming(e.what(), "clouds.weather_map '" + file + "': ", c.expected);
      EXPECT_NE(std::string(e.what()).find("; a weather map is an RGBA PNG"), std::string::npos)
          << e.what();
    }
  }
  std::string bad_crc = test::png_bytes(8, 8, 8, 6, test::zlib_stored(rows));
  bad_crc[bad_crc.size() - 13] ^= 0x01;  // the IDAT's CRC
  const Rgba8Image image = read_weather_map(write("bad_crc.png", bad_crc));
  ASSERT_EQ(image.width, 8);
  ASSERT_EQ(image.height, 8);
  EXPECT_EQ(image.texels[0], 200);
}

// An EXR weather map is read in strips into 8 bits: clamped to [0, 1], a missing alpha 1.
TEST_F(ImageLimits, ExrWeatherMapsAreReadAsEightBitRgba) {
  Image image(3, 70);  // more rows than a strip
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) image.at(x, y) = glm::vec4(0.5f, 2.0f, -1.0f, y / 69.0f);
  write_image(image, path("map.exr"), 1.0f, ExrPixels::kFloat);
  const Rgba8Image map = read_weather_map(path("map.exr"));
  ASSERT_EQ(map.width, 3);
  ASSERT_EQ(map.height, 70);
  EXPECT_EQ(map.texels[0], 128);
  EXPECT_EQ(map.texels[1], 255);
  EXPECT_EQ(map.texels[2], 0);
  EXPECT_EQ(map.texels[3], 0);
  EXPECT_EQ(map.texels[(69 * 3 + 2) * 4 + 3], 255);
}

// Item 9: terrain files are refused from the header above 8192 points a side (a 522 KB PNG of
// 16384^2 took 6.3 GB), and structural corruption at the scene's check, not at decoding.
TEST_F(ImageLimits, TerrainFilesAreRefusedFromTheHeader) {
  const std::string idat = test::zlib_stored(std::string(64, '\0'));
  const auto terrain = [&](const std::string& file) {
    return rejection([&](Scene& s) { s.terrain.file = file; });
  };
  expect_one_line_naming(terrain(write("t16384.png", test::png_bytes(16384, 16384, 16, 0, idat))),
                         "terrain.file = \"",
                         "16384 x 16384 points: at most 8192 a side are allowed");
  expect_one_line_naming(terrain(write("t8193.png", test::png_bytes(8193, 2, 16, 0, idat))),
                         "terrain.file = \"", "8193 x 2 points: at most 8192 a side are allowed");
  expect_one_line_naming(terrain(exr_declaring("t9000.exr", 4, 9000)), "terrain.file = \"",
                         "4 x 9000 points: at most 8192 a side are allowed");
  expect_one_line_naming(
      terrain(exr_declaring("lying.exr", 8000, 8000)), "terrain.file = \"",
      "is truncated or corrupt: its 8000 x 8000 pixels need a table of 500 chunks");
  const std::string good =
      test::png_bytes(4, 4, 16, 0, test::zlib_stored(std::string(4 * 9, '\0')));
  expect_one_line_naming(terrain(write("cut.png", good.substr(0, good.size() - 20))),
                         "terrain.file = \"", "is truncated");
  expect_one_line_naming(terrain(write("text.png", "P6 not a PNG\n")), "terrain.file = \"",
                         "is neither a PNG nor an EXR file");
}

// The albedo map's size is checked from its header too (it is read as float RGBA).
TEST_F(ImageLimits, AlbedoMapsAreRefusedFromTheHeader) {
  const std::string idat = test::zlib_stored(std::string(64, '\0'));
  const auto albedo = [&](const std::string& file) {
    return rejection([&](Scene& s) {
      s.terrain.preset = "mountains";
      s.terrain.albedo_map = file;
    });
  };
  expect_one_line_naming(
      albedo(write("a.png", test::png_bytes(4097, 64, 8, 2, idat))), "terrain.albedo_map = \"",
      "4097 x 64 pixels: at most 4096 a side are allowed; an albedo map is a PNG or an EXR");
  expect_one_line_naming(albedo(exr_declaring("a.exr", 2000, 2000)), "terrain.albedo_map = \"",
                         "is truncated or corrupt");
  expect_one_line_naming(albedo(write("b.png", "GIF89a")), "terrain.albedo_map = \"",
                         "is neither a PNG nor an EXR file");
  EXPECT_EQ(albedo(write("ok.png", test::png_rgba8_bytes(4, 4, 9))), "");
}

// The albedo map is read as linear half floats: a PNG's sRGB codes decoded, an EXR clamped to
// [0, 1] and read in strips, alpha 1. A corrupt one is one line naming the key and its path
// once (through read_image it read "terrain.albedo_map '...': image '...': ...").
TEST_F(ImageLimits, AlbedoMapsAreReadAsLinearHalfFloatsAndRefusedInOneLine) {
  const HalfRgbaImage png = read_albedo_map(write("a.png", test::png_rgba8_bytes(4, 4, 128)));
  ASSERT_EQ(png.width, 4);
  ASSERT_EQ(png.height, 4);
  ASSERT_EQ(png.halfs.size(), 4u * 4u * 4u);
  EXPECT_NEAR(glm::unpackHalf1x16(png.halfs[0]), 0.2158f, 1e-3f);  // sRGB 128
  EXPECT_EQ(glm::unpackHalf1x16(png.halfs[3]), 1.0f);
  Image image(3, 70);  // more rows than a strip
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) image.at(x, y) = glm::vec4(0.25f, 2.0f, -1.0f, 0.1f);
  image.at(2, 69) = glm::vec4(0.5f, 0.0f, 1.0f, 0.0f);
  write_image(image, path("a.exr"), 1.0f, ExrPixels::kFloat);
  const HalfRgbaImage exr = read_albedo_map(path("a.exr"));
  ASSERT_EQ(exr.width, 3);
  ASSERT_EQ(exr.height, 70);
  const float first[4] = {0.25f, 1.0f, 0.0f, 1.0f}, last[4] = {0.5f, 0.0f, 1.0f, 1.0f};
  for (int c = 0; c < 4; ++c) {
    EXPECT_EQ(glm::unpackHalf1x16(exr.halfs[size_t(c)]), first[c]) << c;
    EXPECT_EQ(glm::unpackHalf1x16(exr.halfs[(69 * 3 + 2) * 4 + size_t(c)]), last[c]) << c;
  }

  std::string rows;
  for (int y = 0; y < 8; ++y) rows += '\0' + std::string(8 * 4, char(200));
  std::string bad_block = test::zlib_stored(rows);
  bad_block[2] = char(0x07);  // BFINAL, reserved block type 3
  const std::string file = write("bad.png", test::png_bytes(8, 8, 8, 6, bad_block));
  try {
    read_albedo_map(file);
    ADD_FAILURE() << "a corrupt albedo map was read";
  } catch (const InputError& e) {
    const std::string message = e.what();
    expect_one_line_naming(message,
                           "terrain.albedo_map '" + file + "': ", "cannot decode the PNG (");
    EXPECT_NE(message.find("; an albedo map is a PNG or an EXR of at most 4096 x 4096 pixels"),
              std::string::npos)
        << message;
    EXPECT_EQ(message.find(file), message.rfind(file)) << "the path twice: " << message;
    EXPECT_EQ(message.find("image '"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace nephele

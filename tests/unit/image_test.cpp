// Tests of the image writers, readers, tone mapping and golden-image comparison.
#include "nephele/image.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "nephele/error.h"
#include "nephele/image_compare.h"
#include "nephele/image_compare.h"

namespace nephele {
namespace {

namespace fs = std::filesystem;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

Image uniform(int w, int h, glm::vec4 value) {
  Image image(w, h);
  std::fill(image.pixels.begin(), image.pixels.end(), value);
  return image;
}

// A small image with HDR values, distinct per pixel and channel.
Image test_pattern(int w, int h) {
  Image image(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const float t = float(y * w + x) / float(w * h);
      image.at(x, y) = glm::vec4(t * 4.0f, 0.01f + t, 3.0f * (1.0f - t), 0.25f + 0.5f * t);
    }
  }
  return image;
}

std::vector<unsigned char> tonemap_one(glm::vec4 value, float exposure = 1.0f) {
  return tonemap_srgb8(uniform(1, 1, value), exposure);
}

// Asserts that `f` throws E and that its message contains every one of `parts`.
template <typename E, typename F>
void expect_throw_containing(F f, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no exception thrown";
  } catch (const E& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const std::string& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
    }
  }
}

// --- tone mapping ------------------------------------------------------------------------

TEST(ImageTonemap, LuminanceIsRec709) {
  EXPECT_NEAR(luminance(glm::vec4(1.0f)), 1.0f, 1e-6f);
  EXPECT_FLOAT_EQ(luminance(glm::vec4(1, 0, 0, 0)), 0.2126f);
  EXPECT_FLOAT_EQ(luminance(glm::vec4(0, 1, 0, 0)), 0.7152f);
  EXPECT_FLOAT_EQ(luminance(glm::vec4(0, 0, 1, 0)), 0.0722f);
}

TEST(ImageTonemap, ZeroIsBlackWithOpaqueAlpha) {
  EXPECT_EQ(tonemap_one(glm::vec4(0, 0, 0, 0)), (std::vector<unsigned char>{0, 0, 0, 255}));
}

TEST(ImageTonemap, KnownValue) {
  // ACES fit at 1.0 is 0.80377; sRGB-encoded 0.9082, i.e. code 232.
  EXPECT_EQ(tonemap_one(glm::vec4(1.0f))[0], 232);
}

TEST(ImageTonemap, IsMonotonicAndSaturates) {
  Image ramp(2001, 1);
  for (int x = 0; x < ramp.width; ++x) ramp.at(x, 0) = glm::vec4(float(x) * 0.01f);
  const std::vector<unsigned char> bytes = tonemap_srgb8(ramp, 1.0f);
  ASSERT_EQ(bytes.size(), size_t(ramp.width) * 4);
  for (int x = 1; x < ramp.width; ++x) {
    for (int c = 0; c < 3; ++c) ASSERT_GE(bytes[x * 4 + c], bytes[(x - 1) * 4 + c]) << x;
  }
  EXPECT_EQ(bytes[0], 0);
  EXPECT_EQ(bytes[(ramp.width - 1) * 4], 255);  // 20.0
  EXPECT_EQ(tonemap_one(glm::vec4(1e30f))[0], 255);
  EXPECT_EQ(tonemap_one(glm::vec4(kInf))[0], 255);
}

TEST(ImageTonemap, NanAndNegativeGiveBlack) {
  EXPECT_EQ(tonemap_one(glm::vec4(kNaN, -1.0f, -kInf, kNaN)),
            (std::vector<unsigned char>{0, 0, 0, 255}));
  EXPECT_EQ(tonemap_one(glm::vec4(1.0f), kNaN)[0], 0);
}

TEST(ImageTonemap, ExposureScales) {
  EXPECT_EQ(tonemap_one(glm::vec4(0.5f), 2.0f), tonemap_one(glm::vec4(1.0f)));
  EXPECT_LT(tonemap_one(glm::vec4(0.5f))[0], tonemap_one(glm::vec4(0.5f), 2.0f)[0]);
}

// --- files -------------------------------------------------------------------------------

class ImageIo : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("nephele-image-test-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // Names in the test directory, temporary files included.
  std::set<std::string> listing() const {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) {
      names.insert(entry.path().filename().string());
    }
    return names;
  }

  fs::path dir_;
};

TEST_F(ImageIo, PngRoundTripEqualsTonemappedBytes) {
  const Image image = test_pattern(7, 5);
  const float exposure = 1.5f;
  write_image(image, path("a.png"), exposure);
  const Image back = read_image(path("a.png"));
  ASSERT_EQ(back.width, 7);
  ASSERT_EQ(back.height, 5);
  const std::vector<unsigned char> bytes = tonemap_srgb8(image, exposure);
  for (size_t i = 0; i < back.pixels.size(); ++i) {
    for (int c = 0; c < 4; ++c) {
      ASSERT_EQ(std::lround(back.pixels[i][c] * 255.0f), bytes[i * 4 + c]) << i << " " << c;
    }
  }
  EXPECT_EQ(listing(), (std::set<std::string>{"a.png"}));
}

TEST_F(ImageIo, ExrRoundTripWithinHalfPrecision) {
  Image image = test_pattern(9, 4);
  image.at(0, 0) = glm::vec4(1000.0f, 1e-3f, 0.0f, 1.0f);
  write_image(image, path("a.exr"), 3.0f);  // exposure does not apply to EXR
  const Image back = read_image(path("a.exr"));
  ASSERT_EQ(back.width, 9);
  ASSERT_EQ(back.height, 4);
  for (size_t i = 0; i < back.pixels.size(); ++i) {
    for (int c = 0; c < 4; ++c) {
      const float want = image.pixels[i][c];
      // Half has an 11-bit significand: relative error at most 2^-11.
      ASSERT_NEAR(back.pixels[i][c], want, std::fabs(want) * 4.9e-4f + 1e-7f) << i << " " << c;
    }
  }
}

TEST_F(ImageIo, ExrNeverHoldsInfOrNaN) {
  // The sun's disk is brighter than the largest half (65504): half EXR clamps it there, float
  // EXR keeps it; NaN is stored as 0 and inf as the largest value in both.
  Image image = uniform(3, 1, glm::vec4(1.0f));
  image.at(0, 0) = glm::vec4(3.0e5f, 7.0e4f, 1.0f, 1.0f);
  image.at(1, 0) = glm::vec4(kNaN, kInf, -kInf, 1.0f);
  write_image(image, path("half.exr"));
  write_image(image, path("float.exr"), 1.0f, ExrPixels::kFloat);
  const Image half = read_image(path("half.exr"));
  const Image full = read_image(path("float.exr"));
  for (const Image* back : {&half, &full})
    for (const glm::vec4& p : back->pixels)
      for (int c = 0; c < 4; ++c) EXPECT_TRUE(std::isfinite(p[c])) << c;
  EXPECT_EQ(half.at(0, 0).r, 65504.0f);
  EXPECT_EQ(half.at(0, 0).g, 65504.0f);
  EXPECT_EQ(full.at(0, 0).r, 3.0e5f);
  EXPECT_EQ(full.at(0, 0).g, 7.0e4f);
  EXPECT_EQ(half.at(1, 0).r, 0.0f);
  EXPECT_EQ(full.at(1, 0).r, 0.0f);
  EXPECT_EQ(half.at(1, 0).g, 65504.0f);
  EXPECT_EQ(half.at(1, 0).b, -65504.0f);
  EXPECT_EQ(full.at(1, 0).g, std::numeric_limits<float>::max());
  EXPECT_EQ(full.at(2, 0), glm::vec4(1.0f));
}

TEST_F(ImageIo, ExtensionIsCaseInsensitive) {
  const Image image = test_pattern(3, 2);
  write_image(image, path("a.PNG"));
  write_image(image, path("b.Exr"));
  EXPECT_EQ(read_image(path("a.PNG")).width, 3);
  EXPECT_EQ(read_image(path("b.Exr")).width, 3);
  EXPECT_NO_THROW(check_output_path(path("c.PnG"), "--output"));
}

TEST_F(ImageIo, WriteReplacesExistingFileAndLeavesNoTemporary) {
  write_image(test_pattern(4, 4), path("a.png"));
  write_image(test_pattern(2, 3), path("a.png"));
  EXPECT_EQ(read_image(path("a.png")).width, 2);
  EXPECT_EQ(listing(), (std::set<std::string>{"a.png"}));
}

TEST_F(ImageIo, UnsupportedExtensionThrowsAndWritesNothing) {
  const std::string jpg = path("x.jpg");
  try {
    check_output_path(jpg, "--output");
    ADD_FAILURE() << "no exception thrown";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--output '" + jpg + "': unsupported image format (allowed: .png, .exr)");
  }
  expect_throw_containing<InputError>([&] { write_image(test_pattern(2, 2), jpg); },
                                      {jpg, "unsupported image format"});
  expect_throw_containing<InputError>([&] { check_output_path(path("noext"), "--diff"); },
                                      {"--diff", path("noext")});
  EXPECT_TRUE(listing().empty());
}

TEST_F(ImageIo, MissingDirectoryThrowsAndCreatesNothing) {
  const std::string target = path("missing/a.png");
  expect_throw_containing<InputError>([&] { check_output_path(target, "--output"); },
                                      {"--output", target, "does not exist"});
  expect_throw_containing<RuntimeError>([&] { write_image(test_pattern(2, 2), target); }, {target});
  EXPECT_TRUE(listing().empty());
}

TEST_F(ImageIo, ParentThatIsAFileIsRejected) {
  std::ofstream(path("file")) << "x";
  const std::string target = path("file/a.png");
  expect_throw_containing<InputError>([&] { check_output_path(target, "--output"); },
                                      {"--output", target, "not a directory"});
}

TEST_F(ImageIo, ExistingDirectoryIsRejectedAndWriteLeavesNoTemporary) {
  fs::create_directory(path("out.png"));
  expect_throw_containing<InputError>([&] { check_output_path(path("out.png"), "--output"); },
                                      {"--output", path("out.png"), "is a directory"});
  // The rename over the directory fails after the temporary file has been written.
  expect_throw_containing<RuntimeError>([&] { write_image(test_pattern(2, 2), path("out.png")); },
                                        {path("out.png")});
  EXPECT_EQ(listing(), (std::set<std::string>{"out.png"}));
  EXPECT_TRUE(fs::is_empty(path("out.png")));
}

TEST_F(ImageIo, NotWritableDirectoryIsRejected) {
  if (::geteuid() == 0) GTEST_SKIP() << "root may write anywhere";
  fs::create_directory(path("ro"));
  fs::permissions(path("ro"), fs::perms::owner_read | fs::perms::owner_exec);
  const std::string target = path("ro/a.png");
  expect_throw_containing<InputError>([&] { check_output_path(target, "--output"); },
                                      {"--output", target, "not writable"});
  fs::permissions(path("ro"), fs::perms::owner_all);
}

TEST_F(ImageIo, CheckOutputPathAcceptsAndWritesNothing) {
  EXPECT_NO_THROW(check_output_path(path("a.png"), "--output"));
  EXPECT_NO_THROW(check_output_path(path("a.exr"), "--output"));
  EXPECT_TRUE(listing().empty());
}

TEST_F(ImageIo, EmptyImageIsRejected) {
  expect_throw_containing<InputError>([&] { write_image(Image(), path("a.png")); },
                                      {path("a.png")});
  EXPECT_TRUE(listing().empty());
}

TEST_F(ImageIo, ReadFailuresNameThePath) {
  expect_throw_containing<InputError>([&] { read_image(path("none.png")); },
                                      {path("none.png"), "does not exist"});
  std::ofstream(path("text.png")) << "not an image";
  expect_throw_containing<InputError>([&] { read_image(path("text.png")); }, {path("text.png")});

  // A PNG and an EXR cut short.
  write_image(test_pattern(16, 16), path("a.png"));
  write_image(test_pattern(16, 16), path("a.exr"));
  for (const char* name : {"a.png", "a.exr"}) {
    fs::resize_file(path(name), fs::file_size(path(name)) / 2);
    expect_throw_containing<InputError>([&] { read_image(path(name)); }, {path(name)});
  }
}

// --- comparison --------------------------------------------------------------------------

constexpr CompareTolerance kTolerance{/*pixel_threshold=*/0.01f, /*max_failing_fraction=*/0.05f,
                                      /*max_pixel_diff=*/0.2f};

TEST(ImageCompare, IdenticalPasses) {
  const Image image = test_pattern(10, 10);
  const CompareResult r = compare_images(image, image, CompareTolerance{});
  EXPECT_TRUE(r.pass) << r.summary;
  EXPECT_EQ(r.max_diff, 0.0f);
  EXPECT_EQ(r.failing_fraction, 0.0f);
  EXPECT_EQ(r.mean_abs_diff, 0.0f);
  EXPECT_EQ(r.summary.rfind("PASS", 0), 0u) << r.summary;
  EXPECT_EQ(r.diff.width, 10);
  EXPECT_EQ(r.diff.at(3, 3), glm::vec4(0, 0, 0, 1));
}

TEST(ImageCompare, OnePixelBeyondMaxPixelDiffFails) {
  const Image reference = uniform(10, 10, glm::vec4(0.5f));
  Image actual = reference;
  actual.at(4, 7).g += 0.3f;  // one pixel in a hundred: within the failing fraction
  const CompareResult r = compare_images(actual, reference, kTolerance);
  EXPECT_FALSE(r.pass);
  EXPECT_NEAR(r.max_diff, 0.3f, 1e-6f);
  EXPECT_FLOAT_EQ(r.failing_fraction, 0.01f);
  EXPECT_EQ(r.summary.rfind("FAIL", 0), 0u) << r.summary;
  EXPECT_EQ(r.summary.find('\n'), std::string::npos);
  // The diff image shows the difference amplified and clamped.
  EXPECT_EQ(r.diff.at(4, 7), glm::vec4(0, 1, 0, 1));
}

TEST(ImageCompare, FailingFractionIsCounted) {
  const Image reference = uniform(10, 10, glm::vec4(0.5f));
  Image actual = reference;
  actual.at(0, 0).r += 0.1f;
  actual.at(1, 0).a -= 0.1f;
  actual.at(2, 5).b += 0.1f;
  actual.at(3, 3).r += 0.005f;  // under pixel_threshold: does not count
  CompareResult r = compare_images(actual, reference, kTolerance);
  EXPECT_TRUE(r.pass) << r.summary;
  EXPECT_FLOAT_EQ(r.failing_fraction, 0.03f);
  EXPECT_NEAR(r.mean_abs_diff, 0.305f / 400.0f, 1e-6f);
  EXPECT_NEAR(r.diff.at(3, 3).r, 0.05f, 1e-4f);
  EXPECT_NEAR(r.diff.at(1, 0).g, 1.0f, 1e-6f);  // alpha differences shown in grey

  CompareTolerance strict = kTolerance;
  strict.max_failing_fraction = 0.02f;
  r = compare_images(actual, reference, strict);
  EXPECT_FALSE(r.pass);
  EXPECT_NE(r.summary.find("3 of 100 pixels"), std::string::npos) << r.summary;
}

TEST(ImageCompare, SizeMismatchFails) {
  const CompareResult r =
      compare_images(uniform(4, 3, glm::vec4(0)), uniform(3, 4, glm::vec4(0)), kTolerance);
  EXPECT_FALSE(r.pass);
  EXPECT_NE(r.summary.find("size mismatch"), std::string::npos) << r.summary;
  EXPECT_NE(r.summary.find("4x3"), std::string::npos) << r.summary;
  EXPECT_NE(r.summary.find("3x4"), std::string::npos) << r.summary;
}

TEST(ImageCompare, NanFails) {
  const Image reference = uniform(4, 4, glm::vec4(0.5f));
  Image actual = reference;
  actual.at(1, 1).r = kNaN;
  const CompareResult r = compare_images(actual, reference, CompareTolerance{1, 1, 1e30f});
  EXPECT_FALSE(r.pass);
  EXPECT_EQ(r.max_diff, kInf);
}

class ImageTolerance : public ImageIo {
 protected:
  std::string write_json(const std::string& text) {
    std::ofstream(path("tol.json")) << text;
    return path("tol.json");
  }
};

TEST_F(ImageTolerance, LoadsAllThreeKeys) {
  const CompareTolerance tol =
      load_tolerance_json(write_json(R"({"pixel_threshold": 0.02, "max_failing_fraction": 0.001,
                     "max_pixel_diff": 1})"));
  EXPECT_FLOAT_EQ(tol.pixel_threshold, 0.02f);
  EXPECT_FLOAT_EQ(tol.max_failing_fraction, 0.001f);
  EXPECT_FLOAT_EQ(tol.max_pixel_diff, 1.0f);
}

TEST_F(ImageTolerance, BadFilesThrowInputError) {
  const std::string file = path("tol.json");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{", "invalid JSON"},
      {"[1, 2]", "object"},
      {R"({"pixel_threshold": 0.1, "max_failing_fraction": 0.1})", "max_pixel_diff"},
      {R"({"pixel_threshold": -1, "max_failing_fraction": 0, "max_pixel_diff": 0})",
       "pixel_threshold = -1"},
      {R"({"pixel_threshold": 0, "max_failing_fraction": 1.5, "max_pixel_diff": 0})",
       "must be in [0, 1]"},
      {R"({"pixel_threshold": "a", "max_failing_fraction": 0, "max_pixel_diff": 0})",
       "must be a number"},
      {R"({"pixel_treshold": 0, "max_failing_fraction": 0, "max_pixel_diff": 0})",
       "pixel_treshold"},
  };
  for (const auto& [text, expected] : cases) {
    write_json(text);
    expect_throw_containing<InputError>([&] { load_tolerance_json(file); }, {file, expected});
  }
  expect_throw_containing<InputError>([&] { load_tolerance_json(path("none.json")); },
                                      {path("none.json")});
}

}  // namespace
}  // namespace nephele

namespace {

nephele::Image filled(int w, int h, glm::vec4 value) {
  nephele::Image image(w, h);
  for (glm::vec4& p : image.pixels) p = value;
  return image;
}

// The blocks' luminance errors: a uniform 10% excess is 10% in every measure; one block of
// four off by 40% is 10% on average and 40% at worst; the reference's noise is its standard
// error per block over its luminance; a black reference counts a lit block as wholly wrong.
TEST(BlockLuminanceError, MeasuresTheBlocksMeansAgainstTheReference) {
  const nephele::Image reference = filled(16, 16, glm::vec4(1.0f));
  nephele::BlockLuminanceError e =
      nephele::block_luminance_error(filled(16, 16, glm::vec4(1.1f)), reference, {}, 8);
  EXPECT_NEAR(e.mean_error, 0.1, 1e-6);
  EXPECT_NEAR(e.mean_bias, 0.1, 1e-6);
  EXPECT_NEAR(e.p95_error, 0.1, 1e-6);
  EXPECT_EQ(e.map.width, 2);
  EXPECT_NEAR(e.map.at(1, 1).r, 0.1f, 1e-6f);
  EXPECT_EQ(e.reference_noise, 0.0);

  nephele::Image one_block = reference;
  for (int y = 8; y < 16; ++y)
    for (int x = 0; x < 8; ++x) one_block.at(x, y) = glm::vec4(0.6f, 0.6f, 0.6f, 1.0f);
  e = nephele::block_luminance_error(one_block, reference, {}, 8);
  EXPECT_NEAR(e.mean_error, 0.1, 1e-6);
  EXPECT_NEAR(e.mean_bias, -0.1, 1e-6);
  EXPECT_NEAR(e.max_error, 0.4, 1e-6);
  EXPECT_NEAR(e.max_lit_error, 0.4, 1e-6);
  EXPECT_NEAR(e.map.at(0, 1).r, 0.4f, 1e-6f);
  EXPECT_NEAR(e.map.at(1, 0).r, 0.0f, 1e-6f);

  // Variance 0.0064 per channel and pixel: a block of 64 has a standard error of 0.01.
  e = nephele::block_luminance_error(reference, reference, filled(16, 16, glm::vec4(0.0064f)), 8);
  EXPECT_NEAR(e.reference_noise, 0.01 * std::sqrt(0.2126 * 0.2126 + 0.7152 * 0.7152 + 0.0722 * 0.0722),
              1e-6);
  e = nephele::block_luminance_error(reference, filled(16, 16, glm::vec4(0.0f)), {}, 8);
  EXPECT_EQ(e.mean_error, 1.0);
  // A block of the reference under 1% of the mean block's (a black background, where the image
  // has a glimmer) counts in the largest error but not in the largest lit one.
  nephele::Image background = reference, glimmer = reference;
  for (int y = 0; y < 8; ++y)
    for (int x = 8; x < 16; ++x) {
      background.at(x, y) = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
      glimmer.at(x, y) = glm::vec4(0.001f, 0.001f, 0.001f, 1.0f);
    }
  glimmer.at(0, 0) =
      glm::vec4(1.0f + 64.0f * 0.05f, 1.0f + 64.0f * 0.05f, 1.0f + 64.0f * 0.05f, 1.0f);
  e = nephele::block_luminance_error(glimmer, background, {}, 8);
  EXPECT_EQ(e.max_error, 1.0);
  EXPECT_NEAR(e.max_lit_error, 0.05, 1e-5);
  EXPECT_NEAR(e.p95_error, 0.05, 1e-5);  // over the lit blocks too
  // The map marks the unlit block (a = 0), which the validation's error map draws grey.
  EXPECT_EQ(e.map.at(1, 0).a, 0.0f);
  EXPECT_EQ(e.map.at(0, 0).a, 1.0f);
  EXPECT_THROW(nephele::block_luminance_error(reference, filled(8, 8, glm::vec4(1.0f)), {}, 8),
               nephele::InputError);
}

}  // namespace

// Output files: only regular files, never two outputs in one file, names checked before any
// work, atomic replacement, and no temporary file left by a signal.
#include "nephele/output_file.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "nephele/error.h"
#include "nephele/image.h"

namespace nephele {
namespace {

namespace fs = std::filesystem;

class OutputFile : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("nephele-output-test-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::set<std::string> listing() const {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_))
      names.insert(entry.path().filename().string());
    return names;
  }

  static std::string read(const std::string& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }

  fs::path dir_;
};

std::string input_error(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

TEST_F(OutputFile, DevicesAndPipesAreRefused) {
  // As root, a rename over /dev/null would replace the device with a regular file.
  EXPECT_EQ(input_error([] { check_output_file("/dev/null", "--stats-json", true); }),
            "--stats-json '/dev/null': is not a regular file (a device, a pipe or a socket): only "
            "regular files, or - for standard output, are written");
  EXPECT_NE(input_error([] { check_output_path("/dev/null", "--output"); }).find("unsupported"),
            std::string::npos);  // no extension: the format is the first thing wrong
  ASSERT_EQ(::mkfifo(path("pipe.png").c_str(), 0600), 0);
  EXPECT_NE(input_error([&] { check_output_path(path("pipe.png"), "--output"); })
                .find("is not a regular file"),
            std::string::npos);
  EXPECT_NO_THROW(check_output_file("-", "--stats-json", true));
}

TEST_F(OutputFile, NamesTooLongForTheFileSystemAreRefusedBeforeAnyWork) {
  const std::string name = std::string(300, 'a') + ".png";
  const std::string message = input_error([&] { check_output_path(path(name), "--output"); });
  EXPECT_NE(message.find("the file name is 304 characters long; the file system allows 255"),
            std::string::npos)
      << message;
  // A name of 255 characters is fine, and so is its temporary file's.
  const std::string longest = std::string(251, 'b') + ".png";
  EXPECT_NO_THROW(check_output_path(path(longest), "--output"));
  write_image(Image(2, 2), path(longest));
  EXPECT_EQ(listing(), std::set<std::string>{longest});
}

TEST_F(OutputFile, TheSameFileCannotTakeTwoOutputs) {
  const std::string image = path("out.exr");
  EXPECT_EQ(input_error([&] {
              check_distinct_outputs({{"--output", image}, {"--stats-json", image}});
            }),
            "--stats-json '" + image + "': is the same file as --output (each output needs a "
            "file of its own)");
  // Also through another spelling of the path, and through a link.
  fs::create_directory(path("sub"));
  const std::string other = (dir_ / "sub" / ".." / "out.exr").string();
  EXPECT_THROW(check_distinct_outputs({{"--output", image}, {"--stats-json", other}}), InputError);
  std::ofstream(image) << "x";
  fs::create_symlink(image, path("link.exr"));
  EXPECT_THROW(check_distinct_outputs({{"--output", image}, {"--stats-json", path("link.exr")}}),
               InputError);
  EXPECT_NO_THROW(check_distinct_outputs(
      {{"--output", image}, {"--stats-json", path("s.json")}, {"--json", "-"}, {"--x", "-"}}));
}

// Issue 40: hard links are one file too, for two outputs and for an output and an input.
TEST_F(OutputFile, AnOutputIsNeverAnInputThroughAnyLink) {
  const std::string input = path("wm.png");
  std::ofstream(input) << "x";
  fs::create_hard_link(input, path("hard.png"));
  fs::create_symlink(input, path("soft.png"));
  EXPECT_THROW(check_distinct_outputs({{"--output", input}, {"--stats-json", path("hard.png")}}),
               InputError);
  for (const std::string& output : {input, path("hard.png"), path("soft.png")})
    EXPECT_EQ(input_error([&] {
                check_outputs_not_inputs({{"--output", output}},
                                         {{"terrain.file", path("none.exr")},
                                          {"clouds.weather_map", input}});
              }),
              "--output '" + output + "': is the same file as the input clouds.weather_map (an "
              "output may not replace a file the work reads)");
  EXPECT_NO_THROW(check_outputs_not_inputs({{"--output", path("new.png")}, {"--json", "-"}},
                                           {{"clouds.weather_map", input}, {"--scene", ""}}));
  EXPECT_EQ(read(input), "x");
}

// Issue 40: a folder that refuses new files whatever its permissions say (root ignores them).
TEST_F(OutputFile, AFolderThatTakesNoNewFileIsRefused) {
  if (!fs::is_directory("/proc/self")) GTEST_SKIP() << "no /proc";
  // As root only the file made and removed finds it (access() says yes).
  const std::string message = input_error([] { check_output_file("/proc/x.png", "--output"); });
  EXPECT_NE(message.find(::geteuid() == 0 ? "--output '/proc/x.png': directory '/proc' does not "
                                            "accept new files ("
                                          : "--output '/proc/x.png': directory '/proc' is not"),
            std::string::npos)
      << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_NO_THROW(check_output_file(path("fine.png"), "--output"));
  EXPECT_TRUE(listing().empty());  // the probe left nothing
}

TEST_F(OutputFile, WritesReplaceWholeAndFollowLinks) {
  write_file_atomically(path("a.json"), "old");
  write_file_atomically(path("a.json"), "new");
  EXPECT_EQ(read(path("a.json")), "new");
  fs::create_symlink("a.json", path("link.json"));
  write_file_atomically(path("link.json"), "through the link");
  EXPECT_TRUE(fs::is_symlink(path("link.json")));
  EXPECT_EQ(read(path("a.json")), "through the link");
  EXPECT_EQ(listing(), (std::set<std::string>{"a.json", "link.json"}));
}

TEST_F(OutputFile, ASignalDuringAWriteRemovesTheTemporaryFile) {
  // A child writes a large file; as soon as its temporary file appears, the test sends the
  // signal. The handler must remove the temporary file and end the process as the signal
  // would have, before the rename.
  for (int signal_number : {SIGINT, SIGTERM}) {
    SCOPED_TRACE(signal_number);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      install_temporary_file_cleanup();
      write_file_atomically(path("big.bin"), std::string(size_t(1) << 28, 'x'));
      ::_exit(0);
    }
    bool seen = false;
    for (int i = 0; i < 20000 && !seen; ++i) {
      for (const std::string& name : listing()) seen = seen || name.starts_with(".nephele-");
      if (!seen) ::usleep(500);
    }
    if (seen) ::kill(child, signal_number);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(seen) << "no temporary file appeared";
    if (WIFEXITED(status)) GTEST_SKIP() << "the write finished before the signal arrived";
    ASSERT_TRUE(WIFSIGNALED(status));
    EXPECT_EQ(WTERMSIG(status), signal_number);
    EXPECT_TRUE(listing().empty()) << *listing().begin();
  }
}

}  // namespace
}  // namespace nephele

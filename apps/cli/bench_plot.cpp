// Runs scripts/plot_bench.py for `nephele bench`.
//
// The script's text is embedded in the binary at build time (cmake/embed_files.cmake) and
// handed to the interpreter as the argument of `python3 -c`, so the benchmark draws its
// figures from any working directory, with or without a source tree beside the binary, and
// leaves no temporary script behind. An argument may hold up to 128 KiB on Linux
// (MAX_ARG_STRLEN); the script is a few KiB. The interpreter is started without a shell
// (posix_spawn), so no path is ever quoted.
#include "bench_plot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <sstream>
#include <string_view>

#include "nephele_embedded.h"

namespace nephele_scripts {
extern const EmbeddedFile kFiles[];
extern const size_t kFileCount;
}  // namespace nephele_scripts

extern char** environ;

namespace nephele::cli {
namespace {

constexpr int kExitNoMatplotlib = 3;          // plot_bench.py: matplotlib cannot be imported
constexpr size_t kMaxArgumentBytes = 131072;  // Linux's MAX_ARG_STRLEN

// The last non-empty line of `text` (a Python traceback ends with the exception).
std::string last_line(const std::string& text) {
  std::string last;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  return last;
}

struct ProcessResult {
  int spawn_error = 0;  // errno of posix_spawn; 0 when the interpreter started
  int status = -1;      // exit status, -1 when killed by a signal
  std::string output;   // standard output and error together
};

// Runs `argv` (argv[0] a path; no PATH search, no shell) with standard input from /dev/null
// and standard output and error into a pipe that is read to its end.
ProcessResult run_process(const std::vector<std::string>& argv) {
  ProcessResult result;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    result.spawn_error = errno;
    return result;
  }
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 1);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 2);
  pid_t pid = 0;
  result.spawn_error = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  if (result.spawn_error == 0) {
    char buffer[4096];
    for (;;) {
      const ssize_t n = read(fds[0], buffer, sizeof buffer);
      if (n > 0)
        result.output.append(buffer, size_t(n));
      else if (n == 0 || errno != EINTR)
        break;
    }
    int raw = 0;
    while (waitpid(pid, &raw, 0) < 0 && errno == EINTR) {
    }
    result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  }
  close(fds[0]);
  return result;
}

}  // namespace

BenchPlots draw_bench_plots(const std::string& bench_json, const std::string& out_dir,
                            const std::string& python) {
  BenchPlots plots;
  const EmbeddedFile* script =
      find_embedded(nephele_scripts::kFiles, nephele_scripts::kFileCount, "plot_bench.py");
  if (!script || script->size >= kMaxArgumentBytes) {
    plots.reason = "the plot script is missing from the binary or too long to pass";
    return plots;
  }
  const std::string text(reinterpret_cast<const char*>(script->data), script->size);
  const ProcessResult run = run_process({python, "-c", text, bench_json, out_dir});
  if (run.spawn_error != 0) {
    plots.outcome = BenchPlots::Outcome::kSkipped;
    plots.reason = "cannot run " + python + " (" + std::strerror(run.spawn_error) + ")";
    return plots;
  }
  if (run.status == kExitNoMatplotlib) {
    plots.outcome = BenchPlots::Outcome::kSkipped;
    plots.reason = python + " cannot import matplotlib (Debian: python3-matplotlib)";
    return plots;
  }
  if (run.status != 0) {
    const std::string why = last_line(run.output);
    plots.reason = "the plot script failed (" +
                   (run.status < 0 ? std::string("killed") : "exit " + std::to_string(run.status)) +
                   (why.empty() ? ")" : "): " + why);
    return plots;
  }
  plots.outcome = BenchPlots::Outcome::kDrawn;
  std::istringstream lines(run.output);
  constexpr std::string_view kWrote = "wrote ";
  for (std::string line; std::getline(lines, line);)
    if (line.starts_with(kWrote)) plots.files.push_back(line.substr(kWrote.size()));
  return plots;
}

}  // namespace nephele::cli

// Runs a command line in a shell for the tests that drive the built programs (nephele,
// nephele-view), capturing what it prints.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace nephele::test {

struct ProcessRun {
  int status;          // exit status; -1 when the process did not exit (a signal)
  std::string output;  // what it printed on the captured streams
};

// `redirect`: what the shell does with the streams; by default both are captured.
inline ProcessRun run_process(const std::string& command, const std::string& redirect = "2>&1") {
  FILE* pipe = popen((command + " " + redirect).c_str(), "r");
  std::string output;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) output.append(buffer.data(), n);
  const int raw = pclose(pipe);
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, output};
}

#ifdef NEPHELE_CLI_PATH
// The built `nephele` with `args`.
inline ProcessRun run_cli(const std::string& args, const std::string& redirect = "2>&1") {
  return run_process(std::string(NEPHELE_CLI_PATH) + " " + args, redirect);
}
#endif

}  // namespace nephele::test

// What the fuzz tests (tests/render/fuzz_test.cpp, fuzz_files_test.cpp) and the hostile-file
// unit tests (tests/unit/voxel_io_hostile_test.cpp) share: whether AddressSanitizer is on, a
// leak check through LeakSanitizer, helpers for their child processes, and their failure
// reports. Header-only, so that it serves the sanitizer build (which compiles only some of the
// tests) as it does the others.
#pragma once

#include <cxxabi.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <typeinfo>
#include <vector>

// NEPHELE_TEST_ASAN is defined where AddressSanitizer instruments the build: GCC says so with
// __SANITIZE_ADDRESS__, Clang with __has_feature (which GCC before 14 lacks, hence the nesting).
#if defined(__SANITIZE_ADDRESS__)
#define NEPHELE_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define NEPHELE_TEST_ASAN 1
#endif
#endif
#ifdef NEPHELE_TEST_ASAN
#include <sanitizer/lsan_interface.h>
#endif

namespace nephele::test {

#ifdef NEPHELE_TEST_ASAN
inline constexpr bool kAsan = true;
#else
inline constexpr bool kAsan = false;
#endif

// Under AddressSanitizer: whether LeakSanitizer finds memory leaked so far in this process (it
// prints what it finds). Always false without it.
inline bool leaks_found() {
#ifdef NEPHELE_TEST_ASAN
  return __lsan_do_recoverable_leak_check() != 0;
#else
  return false;
#endif
}

// The dynamic type of `e`, demangled ("std::out_of_range").
inline std::string demangled_type(const std::exception& e) {
  int status = 0;
  char* name = abi::__cxa_demangle(typeid(e).name(), nullptr, nullptr, &status);
  std::string text = status == 0 && name ? name : typeid(e).name();
  std::free(name);
  return text;
}

// Control characters and bytes beyond ASCII as \xNN, so that a report prints cleanly; at most
// `max_chars` of `text`, then how long it was.
inline std::string printable(std::string_view text, size_t max_chars = 3000) {
  std::string out;
  for (unsigned char c : text.substr(0, max_chars)) {
    if (c == '\n' || (c >= 0x20 && c < 0x7f)) {
      out += char(c);
    } else {
      char code[8];
      std::snprintf(code, sizeof code, "\\x%02x", c);
      out += code;
    }
  }
  if (text.size() > max_chars) out += "... (" + std::to_string(text.size()) + " bytes in all)";
  return out;
}

// "crashed: signal 11 (Segmentation fault)", "exit status 3", for a waitpid status.
inline std::string describe_death(int status) {
  if (WIFSIGNALED(status))
    return "crashed: signal " + std::to_string(WTERMSIG(status)) + " (" +
           strsignal(WTERMSIG(status)) + ")";
  return "exit status " + std::to_string(WEXITSTATUS(status));
}

// Restarts this process's peak resident memory (VmHWM) from its current resident memory (Linux
// 4.0 and later).
inline void reset_peak_memory() {
  std::ofstream("/proc/self/clear_refs") << "5";
}

// Writes all of `text` to `fd` (a child's pipe to its parent), as far as the pipe takes it.
inline void write_all(int fd, const std::string& text) {
  for (size_t done = 0; done < text.size();) {
    const ssize_t n = write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += size_t(n);
  }
}

struct Failure {
  std::string symptom;  // groups failures of one cause: "crashed: signal 11 (Segmentation fault)"
  std::string label;    // which case: "scene file case #1234"
  std::string detail;   // this case's particulars
  std::string input;    // what reproduces it
};

// `failures` grouped by symptom, each with its number of `noun`s ("case"): the first `examples`
// of each in full, the next 40 by label.
inline std::string failure_report(const std::vector<Failure>& failures, const std::string& noun,
                                  size_t examples) {
  std::map<std::string, std::vector<const Failure*>> by_symptom;
  for (const Failure& f : failures) by_symptom[f.symptom].push_back(&f);
  std::ostringstream out;
  out << failures.size() << " failing " << noun << "(s), " << by_symptom.size() << " symptom(s):\n";
  for (const auto& [symptom, list] : by_symptom) {
    out << "\n=== " << symptom << ": " << list.size() << " " << noun << "(s)\n";
    for (size_t i = 0; i < list.size() && i < examples; ++i)
      out << "--- " << list[i]->label << ": " << printable(list[i]->detail, 600) << "\n"
          << printable(list[i]->input) << "\n";
    if (list.size() > examples) {
      out << "... and " << list.size() - examples << " more:";
      for (size_t i = examples; i < list.size() && i < examples + 40; ++i)
        out << (i == examples ? " " : ", ") << list[i]->label;
      out << (list.size() > examples + 40 ? ", ..." : "") << "\n";
    }
  }
  return out.str();
}

}  // namespace nephele::test

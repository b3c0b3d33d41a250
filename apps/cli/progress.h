// nephele CLI — a progress bar with the time left, on standard error.
//
// On a terminal the bar is redrawn in place (\r) at most kRedrawIntervalS apart; elsewhere (a
// log file, a pipe) one plain line is written at most kLineIntervalS apart, and the last line
// when the work is done:
//
//   render [##########----------]  50%  3/6  0:04 elapsed  0:04 left
#pragma once

#include <functional>
#include <string>
#include <string_view>

namespace nephele::cli {

// Whether a command shows progress: never with --quiet, always with --progress, otherwise when
// standard error is a terminal and --verbose is not printing a line a step of its own.
bool progress_wanted(bool progress_flag, bool quiet, bool verbose = false);

class Progress {
 public:
  static constexpr double kRedrawIntervalS = 0.1;
  static constexpr double kLineIntervalS = 5.0;

  enum class Style {
    kBar,    // redrawn in place with \r, a newline at the end
    kLines,  // a line at a time
  };
  // Where a Progress writes, and its clock (seconds, monotonic); injected by tests.
  struct Output {
    Style style = Style::kLines;
    std::function<void(std::string_view)> write;
    std::function<double()> clock;
  };

  // Shows nothing unless `enabled`; a bar when standard error is a terminal, lines otherwise.
  Progress(std::string label, int total_steps, bool enabled);
  Progress(std::string label, int total_steps, Output output);
  ~Progress();  // finish()
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void step(int done);  // `done` of the total steps are done
  void advance();       // one more step is done
  void finish();        // the last state and a newline, once (nothing if nothing was shown)
  // Erases the bar from the terminal so that other output can be written on a clean line; the
  // next step draws it again. (Lines need no erasing.)
  void clear();

  // "label [####----]  50%  3/6  0:04 elapsed  0:04 left": the time left extrapolated from the
  // mean time of the steps done so far ("--:--" before the first).
  static std::string format_line(const std::string& label, int done, int total, double elapsed_s);
  // "0:07", "12:34", "1:02:03"; "--:--" for a negative or non-finite time.
  static std::string format_duration(double seconds);

 private:
  void show(bool force);

  std::string label_;
  int total_ = 0;
  int done_ = 0;
  bool enabled_ = false;
  Output output_;
  double start_s_ = 0.0;
  double last_shown_s_ = 0.0;
  int shown_done_ = -1;     // the step count last shown; -1 before the first
  size_t shown_width_ = 0;  // the bar's last width, to clear what a shorter one leaves
  bool finished_ = false;
};

}  // namespace nephele::cli

#include "progress.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace nephele::cli {

namespace {

constexpr int kBarWidth = 20;

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

bool stderr_is_terminal() {
  return isatty(STDERR_FILENO) == 1;
}

}  // namespace

bool progress_wanted(bool progress_flag, bool quiet, bool verbose) {
  if (quiet) return false;
  return progress_flag || (!verbose && stderr_is_terminal());
}

Progress::Progress(std::string label, int total_steps, bool enabled)
    : Progress(std::move(label), total_steps,
               enabled ? Output{stderr_is_terminal() ? Style::kBar : Style::kLines,
                                [](std::string_view text) {
                                  std::fwrite(text.data(), 1, text.size(), stderr);
                                  std::fflush(stderr);
                                },
                                steady_seconds}
                       : Output{}) {}

Progress::Progress(std::string label, int total_steps, Output output)
    : label_(std::move(label)),
      total_(std::max(total_steps, 0)),
      enabled_(output.write && output.clock && total_steps > 0),
      output_(std::move(output)) {
  if (enabled_) start_s_ = last_shown_s_ = output_.clock();
}

Progress::~Progress() {
  finish();
}

void Progress::step(int done) {
  if (!enabled_ || finished_) return;
  done_ = std::clamp(done, 0, total_);
  show(false);
}

void Progress::advance() {
  step(done_ + 1);
}

void Progress::finish() {
  if (!enabled_ || finished_) return;
  if (shown_done_ != done_) show(true);
  if (output_.style == Style::kBar && shown_done_ >= 0) output_.write("\n");
  finished_ = true;
}

void Progress::clear() {
  if (!enabled_ || finished_ || output_.style != Style::kBar || shown_done_ < 0) return;
  std::string blank(shown_width_ + 2, ' ');  // \r, blanks over the bar, \r
  blank.front() = blank.back() = '\r';
  output_.write(blank);
  shown_done_ = -1;  // drawn again at the next step, however soon
  shown_width_ = 0;
}

void Progress::show(bool force) {
  const double now_s = output_.clock();
  const double interval_s = output_.style == Style::kBar ? kRedrawIntervalS : kLineIntervalS;
  const bool due = now_s - last_shown_s_ >= interval_s || done_ == total_ ||
                   (output_.style == Style::kBar && shown_done_ < 0);
  if (!(force || due) || done_ == shown_done_) return;
  std::string line = format_line(label_, done_, total_, now_s - start_s_);
  if (output_.style == Style::kBar) {
    const size_t width = line.size();
    line.append(shown_width_ > width ? shown_width_ - width : 0, ' ');
    output_.write("\r" + line);
    shown_width_ = width;
  } else {
    output_.write(line + "\n");
  }
  last_shown_s_ = now_s;
  shown_done_ = done_;
}

std::string Progress::format_duration(double seconds) {
  if (!(seconds >= 0.0) || !std::isfinite(seconds) || seconds > 3.6e8) return "--:--";
  const long total = std::lround(seconds);
  const long h = total / 3600, m = total / 60 % 60, s = total % 60;
  char text[32];
  if (h > 0)
    std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", h, m, s);
  else
    std::snprintf(text, sizeof text, "%ld:%02ld", m, s);
  return text;
}

std::string Progress::format_line(const std::string& label, int done, int total, double elapsed_s) {
  const double fraction = total > 0 ? double(done) / double(total) : 0.0;
  const int filled = int(fraction * kBarWidth);
  const double left_s = done > 0 ? elapsed_s / double(done) * double(total - done) : -1.0;
  char numbers[128];
  std::snprintf(numbers, sizeof numbers, "] %3d%%  %d/%d  %s elapsed  %s left",
                int(fraction * 100.0), done, total, format_duration(elapsed_s).c_str(),
                format_duration(left_s).c_str());
  return label + " [" + std::string(size_t(filled), '#') +
         std::string(size_t(kBarWidth - filled), '-') + numbers;
}

}  // namespace nephele::cli

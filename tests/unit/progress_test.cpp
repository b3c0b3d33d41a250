// The CLI's progress bar: its line, its estimate of the time left, and how often it redraws,
// on a clock the test moves by hand.
#include "progress.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace nephele::cli {
namespace {

// A Progress writing into `text`, on a clock at `now_s`.
struct Recorder {
  std::string text;
  double now_s = 100.0;
  Progress::Output output(Progress::Style style) {
    return {style, [this](std::string_view s) { text += s; }, [this] { return now_s; }};
  }
  int count(std::string_view what) const {
    int n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  }
};

TEST(Progress, FormatsDurations) {
  EXPECT_EQ(Progress::format_duration(0.0), "0:00");
  EXPECT_EQ(Progress::format_duration(7.4), "0:07");
  EXPECT_EQ(Progress::format_duration(754.0), "12:34");
  EXPECT_EQ(Progress::format_duration(3723.0), "1:02:03");
  EXPECT_EQ(Progress::format_duration(-1.0), "--:--");
  EXPECT_EQ(Progress::format_duration(1.0 / 0.0), "--:--");
}

// The time left is the mean time a step took so far times the steps left.
TEST(Progress, LineShowsBarPercentCountElapsedAndTimeLeft) {
  EXPECT_EQ(Progress::format_line("render", 3, 6, 4.0),
            "render [##########----------]  50%  3/6  0:04 elapsed  0:04 left");
  EXPECT_EQ(Progress::format_line("render", 1, 4, 10.0),
            "render [#####---------------]  25%  1/4  0:10 elapsed  0:30 left");
  EXPECT_EQ(Progress::format_line("bench", 0, 50, 2.0),
            "bench [--------------------]   0%  0/50  0:02 elapsed  --:-- left");
  EXPECT_EQ(Progress::format_line("gallery", 9, 9, 125.0),
            "gallery [####################] 100%  9/9  2:05 elapsed  0:00 left");
}

// On a terminal: redrawn in place at most ten times a second, the last step always, then a
// newline; a shorter line clears what the longer one left.
TEST(Progress, BarRedrawsAtMostTenTimesASecond) {
  Recorder r;
  {
    Progress p("render", 200, r.output(Progress::Style::kBar));
    p.advance();  // the first step is drawn at once
    EXPECT_EQ(r.count("\r"), 1);
    for (int i = 2; i <= 199; ++i) {
      r.now_s += 0.01;  // 100 steps a second
      p.advance();
    }
    // 1.98 s of steps: a redraw each 0.1 s.
    EXPECT_GE(r.count("\r"), 19);
    EXPECT_LE(r.count("\r"), 21);
    EXPECT_EQ(r.count("\n"), 0);
    r.now_s += 0.001;
    p.advance();  // the last step, however soon
    EXPECT_NE(r.text.rfind("\rrender [####################] 100%  200/200"), std::string::npos);
    EXPECT_EQ(r.count("\n"), 0);
  }
  EXPECT_EQ(r.text.back(), '\n');  // finished by the destructor
  EXPECT_EQ(r.count("\n"), 1);
}

// Elsewhere (--progress into a file or pipe): a plain line at most every few seconds, and the
// last one.
TEST(Progress, LinesAtMostEveryFewSecondsAndTheLast) {
  Recorder r;
  Progress p("render", 10, r.output(Progress::Style::kLines));
  for (int i = 1; i <= 10; ++i) {
    r.now_s += 1.5;
    p.advance();
  }
  p.finish();
  EXPECT_EQ(r.count("\r"), 0);
  // 15 s: after 6 s (step 4), 12 s (step 8), and the last.
  EXPECT_EQ(r.count("\n"), 3) << r.text;
  EXPECT_NE(r.text.find("render [########------------]  40%  4/10  0:06 elapsed  0:09 left\n"),
            std::string::npos)
      << r.text;
  EXPECT_NE(r.text.find("100%  10/10  0:15 elapsed  0:00 left\n"), std::string::npos) << r.text;
}

TEST(Progress, ClearMakesWayForOtherOutput) {
  Recorder r;
  Progress p("bench", 4, r.output(Progress::Style::kBar));
  p.advance();
  const size_t drawn = r.text.size();
  p.clear();
  // Carriage return, blanks over the bar, carriage return.
  EXPECT_EQ(r.text.substr(drawn), "\r" + std::string(drawn - 1, ' ') + "\r");
  r.now_s += 0.001;
  p.advance();  // drawn again at once, though the last draw was a moment ago
  EXPECT_NE(r.text.rfind("\rbench [##########----------]  50%  2/4"), std::string::npos);
}

TEST(Progress, DisabledOrEmptyShowsNothing) {
  Recorder r;
  {
    Progress none("render", 0, r.output(Progress::Style::kBar));
    none.advance();
  }
  {
    Progress off("render", 5, Progress::Output{});
    off.advance();
  }
  {
    Progress quiet("render", 5, false);  // writes to stderr when enabled: not here
    quiet.advance();
  }
  EXPECT_EQ(r.text, "");
  EXPECT_FALSE(progress_wanted(true, true));  // --quiet wins over --progress
  EXPECT_TRUE(progress_wanted(true, false));
}

}  // namespace
}  // namespace nephele::cli

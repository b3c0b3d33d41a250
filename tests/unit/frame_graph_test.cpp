// The frame graph's order, culling and barriers, on passes that log what they record.
#include "render/frame_graph.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace nephele {
namespace {

struct Log {
  std::vector<std::string> lines;
  FrameGraph::Record pass(const std::string& name) {
    return [this, name](VkCommandBuffer) { lines.push_back(name); };
  }
  FrameGraph::Record barrier() {
    return [this](VkCommandBuffer) { lines.push_back("|"); };
  }
};

using Lines = std::vector<std::string>;

std::string error_of(FrameGraph& graph) {
  try {
    graph.compile();
  } catch (const std::logic_error& e) {
    return e.what();
  }
  return "";
}

// The frame's shape: a pass added before the one that makes its input still runs after it, and
// updates of the colour keep their order.
TEST(FrameGraph, OrdersPassesAfterWhatTheyRead) {
  Log log;
  FrameGraph graph;
  graph.import("noise");
  graph.output("display");
  graph.add_pass("march", {"weather", "noise"}, {"clouds"}, log.pass("march"));
  graph.add_pass("weather", {}, {"weather"}, log.pass("weather"));
  graph.add_pass("compose", {"clouds"}, {"color"}, log.pass("compose"));
  graph.add_pass("stars", {"color", "clouds"}, {"color"}, log.pass("stars"));
  graph.add_pass("post", {"color"}, {"color"}, log.pass("post"));
  graph.add_pass("tonemap", {"color"}, {"display"}, log.pass("tonemap"));
  graph.compile();
  graph.execute(VK_NULL_HANDLE, log.barrier());
  EXPECT_EQ(log.lines, (Lines{"weather", "|", "march", "|", "compose", "|", "stars", "|", "post",
                              "|", "tonemap"}));
  EXPECT_EQ(graph.dependencies_of("compose"), (Lines{"weather", "march"}));
  EXPECT_EQ(graph.dependencies_of("weather"), Lines{});
}

// Passes that share nothing run back to back; a barrier separates a write from a later read, a
// write from a later write, and a read from a later write (the reader must finish first).
TEST(FrameGraph, BarriersOnlyWhereAPassTouchesWhatAnotherWrote) {
  Log log;
  FrameGraph graph;
  graph.output("a");
  graph.output("b");
  graph.output("c");
  graph.add_pass("make_a", {}, {"a"}, log.pass("make_a"));
  graph.add_pass("make_b", {}, {"b"}, log.pass("make_b"));       // independent: no barrier
  graph.add_pass("read_a", {"a"}, {"c"}, log.pass("read_a"));    // reads a: barrier
  graph.add_pass("write_a", {}, {"a"}, log.pass("write_a"));     // a was read: barrier
  graph.compile();
  graph.execute(VK_NULL_HANDLE, log.barrier());
  EXPECT_EQ(log.lines, (Lines{"make_a", "make_b", "|", "read_a", "|", "write_a"}));
  ASSERT_EQ(graph.steps().size(), 4u);
  EXPECT_EQ(graph.steps()[2].hazards, Lines{"a"});
  EXPECT_EQ(graph.steps()[3].hazards, Lines{"a"});
  // The reader of the first version of a stays before the second writer.
  EXPECT_EQ(graph.dependencies_of("read_a"), Lines{"make_a"});
}

// A pass whose results reach no output and no kept resource is dropped; one that advances a
// resource kept across frames is not, nor anything it uses.
TEST(FrameGraph, DropsPassesWhoseResultsNobodyUses) {
  Log log;
  FrameGraph graph;
  graph.import("light_volume", true);
  graph.output("color");
  graph.add_pass("weather", {}, {"weather"}, log.pass("weather"));
  graph.add_pass("light_volume", {"weather"}, {"light_volume"}, log.pass("light_volume"));
  graph.add_pass("shafts", {"light_volume"}, {"shafts"}, log.pass("shafts"));  // unused
  graph.add_pass("compose", {}, {"color"}, log.pass("compose"));
  graph.compile();
  graph.execute(VK_NULL_HANDLE, log.barrier());
  EXPECT_EQ(log.lines, (Lines{"weather", "|", "light_volume", "compose"}));
}

TEST(FrameGraph, RefusesCyclesAndReadsOfNothing) {
  FrameGraph cycle;
  cycle.output("a");
  cycle.add_pass("p", {"b"}, {"a"}, {});
  cycle.add_pass("q", {"a"}, {"b"}, {});
  EXPECT_EQ(error_of(cycle), "frame graph: a cycle among the passes p, q");

  FrameGraph typo;
  typo.output("color");
  typo.add_pass("compose", {"clouds"}, {"color"}, {});
  EXPECT_EQ(error_of(typo),
            "frame graph: pass compose reads clouds, which no pass writes and the graph does not "
            "import");

  FrameGraph twice;
  twice.add_pass("p", {}, {"a"}, {});
  EXPECT_THROW(twice.add_pass("p", {}, {"b"}, {}), std::logic_error);
}

// A part of the graph (the passes the march needs, drawn before a still's bands) is recorded
// with the barriers among its own passes.
TEST(FrameGraph, RecordsThePartOnePassNeeds) {
  Log log;
  FrameGraph graph;
  graph.output("color");
  graph.add_pass("weather", {}, {"weather"}, log.pass("weather"));
  graph.add_pass("sky_view", {}, {"sky_view"}, log.pass("sky_view"));
  graph.add_pass("ground_light", {"weather"}, {"ground_light"}, log.pass("ground_light"));
  graph.add_pass("march", {"weather", "sky_view"}, {"clouds"}, log.pass("march"));
  graph.add_pass("compose", {"clouds", "ground_light"}, {"color"}, log.pass("compose"));
  graph.compile();
  EXPECT_EQ(graph.dependencies_of("march"), (Lines{"weather", "sky_view"}));
  graph.execute(VK_NULL_HANDLE, log.barrier(), graph.dependencies_of("march"));
  EXPECT_EQ(log.lines, (Lines{"weather", "sky_view"}));
  EXPECT_NE(graph.describe().find("  barrier (weather)\nground_light: reads weather; writes ground_light\n"),
            std::string::npos)
      << graph.describe();
}

// Several views of one eye point (display channels) share what does not depend on the view:
// a pass that reads it, and every pass that uses what such a pass wrote, is per view; the
// others are recorded once for all.
TEST(FrameGraph, TellsThePassesEachViewNeedsFromThoseTheyShare) {
  Log log;
  FrameGraph graph;
  graph.import(FrameGraph::kView);
  graph.import("noise");
  graph.import("history", true);
  graph.output("display");
  graph.add_pass("weather", {"noise"}, {"weather"}, log.pass("weather"));
  graph.add_pass("light_volume", {"weather", "noise"}, {"light_volume"}, log.pass("light_volume"));
  graph.add_pass("march", {"light_volume", FrameGraph::kView}, {"march"}, log.pass("march"));
  graph.add_pass("resolve", {"march", "history"}, {"history"}, log.pass("resolve"));
  graph.add_pass("compose", {"history", "light_volume"}, {"color"}, log.pass("compose"));
  graph.add_pass("tonemap", {"color"}, {"display"}, log.pass("tonemap"));
  EXPECT_THROW(graph.per_view("march"), std::logic_error);  // before compile
  graph.compile();
  EXPECT_FALSE(graph.per_view("weather"));
  EXPECT_FALSE(graph.per_view("light_volume"));
  for (const char* pass : {"march", "resolve", "compose", "tonemap"})
    EXPECT_TRUE(graph.per_view(pass)) << pass;
  EXPECT_EQ(graph.shared_passes(), (Lines{"weather", "light_volume"}));
  EXPECT_EQ(graph.per_view_resources(),
            (std::set<std::string>{"march", "history", "color", "display"}));
  EXPECT_NE(graph.describe().find("compose: reads history, light_volume; writes color [view]\n"),
            std::string::npos)
      << graph.describe();
  EXPECT_NE(graph.describe().find("weather: reads noise; writes weather\n"), std::string::npos);
  EXPECT_THROW(graph.per_view("no_such_pass"), std::logic_error);
}

}  // namespace
}  // namespace nephele

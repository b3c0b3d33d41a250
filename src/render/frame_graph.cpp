// nephele — the frame graph (frame_graph.h).
#include "render/frame_graph.h"

#include <algorithm>
#include <map>
#include <queue>
#include <stdexcept>

namespace nephele {
namespace {

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

std::string join(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

}  // namespace

void FrameGraph::import(const std::string& resource, bool kept) {
  imported_.insert(resource);
  if (kept) kept_.insert(resource);
}

void FrameGraph::output(const std::string& resource) {
  outputs_.insert(resource);
}

void FrameGraph::add_pass(const std::string& name, std::vector<std::string> reads,
                          std::vector<std::string> writes, Record record) {
  for (const Pass& p : passes_)
    if (p.name == name) throw std::logic_error("frame graph: two passes named " + name);
  passes_.push_back({name, std::move(reads), std::move(writes), std::move(record)});
}

const FrameGraph::Pass& FrameGraph::pass(const std::string& name) const {
  for (const Pass& p : passes_)
    if (p.name == name) return p;
  throw std::logic_error("frame graph: no pass named " + name);
}

void FrameGraph::compile() {
  const size_t n = passes_.size();
  // The writers of each resource, in the order added.
  std::map<std::string, std::vector<size_t>> writers;
  for (size_t i = 0; i < n; ++i)
    for (const std::string& r : passes_[i].writes) writers[r].push_back(i);

  // data[i]: the passes whose results pass i uses; after[i]: those it must also follow (a
  // writer follows the readers of the version it replaces).
  std::vector<std::set<size_t>> data(n), after(n);
  for (const auto& [resource, list] : writers)
    for (size_t k = 1; k < list.size(); ++k) data[list[k]].insert(list[k - 1]);
  for (size_t i = 0; i < n; ++i)
    for (const std::string& r : passes_[i].reads) {
      if (contains(passes_[i].writes, r)) continue;  // an update: ordered among the writers
      const auto found = writers.find(r);
      if (found == writers.end()) {
        if (!imported_.count(r))
          throw std::logic_error("frame graph: pass " + passes_[i].name + " reads " + r +
                                 ", which no pass writes and the graph does not import");
        continue;
      }
      const std::vector<size_t>& list = found->second;
      // The version written last before this pass was added; when none was, the final one.
      auto next = std::upper_bound(list.begin(), list.end(), i);
      data[i].insert(next == list.begin() ? list.back() : *std::prev(next));
      if (next != list.begin() && next != list.end()) after[*next].insert(i);
    }

  // Kahn's order, the earliest added first among the passes that are ready.
  std::vector<int> waiting(n, 0);
  std::vector<std::vector<size_t>> followers(n);
  for (size_t i = 0; i < n; ++i) {
    std::set<size_t> all = data[i];
    all.insert(after[i].begin(), after[i].end());
    waiting[i] = int(all.size());
    for (size_t j : all) followers[j].push_back(i);
  }
  std::priority_queue<size_t, std::vector<size_t>, std::greater<>> ready;
  for (size_t i = 0; i < n; ++i)
    if (waiting[i] == 0) ready.push(i);
  std::vector<size_t> sorted;
  while (!ready.empty()) {
    const size_t i = ready.top();
    ready.pop();
    sorted.push_back(i);
    for (size_t j : followers[i])
      if (--waiting[j] == 0) ready.push(j);
  }
  if (sorted.size() != n) {
    std::vector<std::string> stuck;
    for (size_t i = 0; i < n; ++i)
      if (waiting[i] > 0) stuck.push_back(passes_[i].name);
    throw std::logic_error("frame graph: a cycle among the passes " + join(stuck));
  }

  // Live: a pass that writes an output or a kept resource, and every pass a live one uses.
  std::vector<bool> live(n, false);
  for (auto it = sorted.rbegin(); it != sorted.rend(); ++it) {
    const size_t i = *it;
    for (const std::string& r : passes_[i].writes)
      if (outputs_.count(r) || kept_.count(r)) live[i] = true;
    if (live[i])
      for (size_t j : data[i]) live[j] = true;
  }
  // (Reverse order visits every user before the passes it uses: the sort put them after.)

  needs_.assign(n, {});
  for (size_t i = 0; i < n; ++i) needs_[i].assign(data[i].begin(), data[i].end());
  // In the sorted order every pass comes after those whose results it uses.
  per_view_.assign(n, false);
  for (size_t i : sorted) {
    per_view_[i] = contains(passes_[i].reads, kView);
    for (size_t j : data[i]) per_view_[i] = per_view_[i] || per_view_[j];
  }
  order_.clear();
  for (size_t i : sorted)
    if (live[i]) order_.push_back(i);
  steps_ = with_barriers(order_);
}

std::vector<FrameGraph::Step> FrameGraph::with_barriers(const std::vector<size_t>& order) const {
  std::vector<Step> steps;
  std::set<std::string> written, read;  // since the last barrier
  for (size_t i : order) {
    const Pass& p = passes_[i];
    Step step{p.name, false, {}};
    for (const std::string& r : p.reads)
      if (written.count(r) && !contains(step.hazards, r)) step.hazards.push_back(r);
    for (const std::string& r : p.writes)
      if ((written.count(r) || read.count(r)) && !contains(step.hazards, r))
        step.hazards.push_back(r);
    if (!step.hazards.empty()) {
      step.barrier_before = true;
      written.clear();
      read.clear();
    }
    read.insert(p.reads.begin(), p.reads.end());
    written.insert(p.writes.begin(), p.writes.end());
    steps.push_back(std::move(step));
  }
  return steps;
}

void FrameGraph::execute(VkCommandBuffer cmd, const Record& barrier) const {
  for (const Step& step : steps_) {
    if (step.barrier_before) barrier(cmd);
    pass(step.pass).record(cmd);
  }
}

void FrameGraph::execute(VkCommandBuffer cmd, const Record& barrier,
                         const std::vector<std::string>& passes) const {
  std::vector<size_t> subset;
  for (size_t i : order_)
    if (contains(passes, passes_[i].name)) subset.push_back(i);
  for (const Step& step : with_barriers(subset)) {
    if (step.barrier_before) barrier(cmd);
    pass(step.pass).record(cmd);
  }
}

std::vector<std::string> FrameGraph::dependencies_of(const std::string& name) const {
  size_t target = passes_.size();
  for (size_t i = 0; i < passes_.size(); ++i)
    if (passes_[i].name == name) target = i;
  if (target == passes_.size()) throw std::logic_error("frame graph: no pass named " + name);
  std::set<size_t> needed;
  std::vector<size_t> todo = needs_[target];
  while (!todo.empty()) {
    const size_t i = todo.back();
    todo.pop_back();
    if (needed.insert(i).second) todo.insert(todo.end(), needs_[i].begin(), needs_[i].end());
  }
  std::vector<std::string> names;
  for (size_t i : order_)
    if (needed.count(i)) names.push_back(passes_[i].name);
  return names;
}

std::string FrameGraph::describe() const {
  std::string text;
  for (const Step& step : steps_) {
    if (step.barrier_before) text += "  barrier (" + join(step.hazards) + ")\n";
    const Pass& p = pass(step.pass);
    text += p.name + ": reads " + (p.reads.empty() ? "-" : join(p.reads)) + "; writes " +
            join(p.writes) + (per_view(p.name) ? " [view]" : "") + "\n";
  }
  return text;
}

bool FrameGraph::per_view(const std::string& name) const {
  for (size_t i = 0; i < passes_.size(); ++i)
    if (passes_[i].name == name) {
      if (per_view_.size() != passes_.size())
        throw std::logic_error("frame graph: per_view before compile");
      return per_view_[i];
    }
  throw std::logic_error("frame graph: no pass named " + name);
}

std::vector<std::string> FrameGraph::shared_passes() const {
  std::vector<std::string> names;
  for (size_t i : order_)
    if (!per_view_[i]) names.push_back(passes_[i].name);
  return names;
}

std::set<std::string> FrameGraph::per_view_resources() const {
  std::set<std::string> resources;
  for (size_t i : order_)
    if (per_view_[i]) resources.insert(passes_[i].writes.begin(), passes_[i].writes.end());
  return resources;
}

}  // namespace nephele

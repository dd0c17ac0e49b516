#include "radiosity/transfer/receiver_tree.h"

#include "radiosity/transfer/parallel.h"

#include <algorithm>
#include <numeric>

namespace dynrad::rad {

ReceiverTree::ReceiverTree(const std::vector<Item>& items) {
  if (items.empty()) return;
  std::vector<Vec3d> centres(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) centres[i] = (items[i].bounds.lo + items[i].bounds.hi) * 0.5;
  std::vector<std::uint32_t> ids(items.size());
  std::iota(ids.begin(), ids.end(), 0u);
  nodes_.reserve(2 * items.size() / kLeafSize + 2);
  build(ids, 0, static_cast<std::uint32_t>(ids.size()), items, centres);
  order_ = std::move(ids);
  position_.resize(order_.size());
  for (std::uint32_t k = 0; k < order_.size(); ++k) position_[order_[k]] = k;
  for (Node& n : nodes_)
    if (n.count >= kMinTested) add_samples(n, items);
}

std::uint32_t ReceiverTree::build(std::vector<std::uint32_t>& ids, std::uint32_t begin, std::uint32_t end,
                                  const std::vector<Item>& items, const std::vector<Vec3d>& centres) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Node node;
  node.first = begin;
  node.count = end - begin;
  Bounds spread;
  for (std::uint32_t i = begin; i < end; ++i) {
    node.bounds.extend(items[ids[i]].bounds.lo);
    node.bounds.extend(items[ids[i]].bounds.hi);
    spread.extend(centres[ids[i]]);
  }
  const Vec3d extent = spread.extent();
  if (node.count > kLeafSize && extent.max() > 0) {
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (extent[a] > extent[axis]) axis = a;
    const std::uint32_t middle = begin + node.count / 2;
    std::nth_element(ids.begin() + begin, ids.begin() + middle, ids.begin() + end,
                     [&](std::uint32_t a, std::uint32_t b) {
                       return centres[a][axis] < centres[b][axis] || (centres[a][axis] == centres[b][axis] && a < b);
                     });
    node.children[0] = build(ids, begin, middle, items, centres);
    node.children[1] = build(ids, middle, end, items, centres);
  }
  nodes_[index] = node;
  return index;
}

void ReceiverTree::add_samples(Node& node, const std::vector<Item>& items) {
  // Stratified by area over the pieces of the node's items, each piece at most once.
  double total = 0;
  for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
    for (const Piece& p : items[order_[i]].pieces) total += p.area;
  node.first_sample = static_cast<std::uint32_t>(samples_.size());
  if (!(total > 0)) return;
  double running = 0;
  std::uint32_t next = 0;  // the next stratum's centre to reach
  for (std::uint32_t i = node.first; i < node.first + node.count && next < kSamples; ++i)
    for (const Piece& p : items[order_[i]].pieces) {
      running += p.area;
      if (running >= (next + 0.5) / kSamples * total) {
        samples_.push_back(p);
        while (next < kSamples && running >= (next + 0.5) / kSamples * total) ++next;
      }
    }
  node.sample_count = static_cast<std::uint32_t>(samples_.size()) - node.first_sample;
}

ReceiverTree::Visit ReceiverTree::visit(const std::function<bool(const Bounds&)>& near,
                                        const std::function<Seen(std::uint32_t)>& test,
                                        const std::vector<std::uint32_t>* kept) const {
  Visit out;
  if (nodes_.empty()) return out;
  std::vector<std::uint32_t> level{0}, next;
  std::vector<Seen> seen;
  while (!level.empty()) {
    seen.assign(level.size(), Seen::untested);
    parallel_for_index(level.size(), 4, [&](std::size_t k) {
      const Node& n = nodes_[level[k]];
      if (n.sample_count > 0 && !near(n.bounds)) seen[k] = test(level[k]);
      if (seen[k] == Seen::hidden && kept) {
        const auto at = std::lower_bound(kept->begin(), kept->end(), n.first);
        if (at != kept->end() && *at < n.first + n.count) seen[k] = Seen::partly;
      }
    });
    // In level order: the items come out in the same order for any number of threads.
    next.clear();
    for (std::size_t k = 0; k < level.size(); ++k) {
      const Node& n = nodes_[level[k]];
      if (seen[k] != Seen::untested) ++out.tests;
      if (seen[k] == Seen::hidden) {
        ++out.culled_nodes;
        out.culled_items += n.count;
      } else if (n.leaf() || n.sample_count == 0 || seen[k] == Seen::wholly) {
        // nothing below is worth a test, or it is all seen
        out.items.insert(out.items.end(), order_.begin() + n.first, order_.begin() + n.first + n.count);
      } else {
        next.push_back(n.children[0]);
        next.push_back(n.children[1]);
      }
    }
    level.swap(next);
  }
  return out;
}

}  // namespace dynrad::rad

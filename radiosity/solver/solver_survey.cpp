// The survey of unshot light: which sender is brightest, and the unshot power in
// total (see Solver::Survey in solver.h).
#include "radiosity/solver/solver.h"

#include "radiosity/transfer/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace dynrad::rad {

namespace {

double sum(const Rgb& c) { return c.r + c.g + c.b; }
double magnitude(const Rgb& c) { return std::abs(c.r) + std::abs(c.g) + std::abs(c.b); }

}  // namespace

Solver::Survey Solver::join(Survey left, const Survey& right) {
  left.unshot += right.unshot;
  left.staying += right.staying;
  left.magnitude += right.magnitude;
  if (right.best_power > left.best_power) {
    left.best = right.best;
    left.best_power = right.best_power;
  }
  return left;
}

std::uint32_t Solver::unit_of_sender(std::uint32_t id) const {
  return is_cluster(id) ? static_cast<std::uint32_t>(groups_.groups.size()) + cluster_index(id) : groups_.group_of[id];
}

std::uint32_t Solver::unit_of_receiver(std::uint32_t patch) const {
  const std::uint32_t part = clusters_.part_of_patch.empty() ? FaceClusters::kNone : clusters_.part_of_patch[patch];
  return part != FaceClusters::kNone ? static_cast<std::uint32_t>(groups_.groups.size()) + clusters_.parts[part].cluster
                                     : groups_.group_of[patch];
}

void Solver::mark_surveyed(std::uint32_t unit) {
  if (unit >= survey_marked_.size() || survey_marked_[unit]) return;
  survey_marked_[unit] = 1;
  survey_dirty_.push_back(unit);
}

Solver::Survey Solver::survey_unit(std::size_t n, bool open) const {
  Survey s;
  Rgb power;
  double lost = -1;
  const std::size_t standalone = groups_.groups.size();
  if (n < standalone) {
    const PlaneGroups::Group& g = groups_.groups[n];
    s.best = groups_.members[g.first];
    double area = 0;
    for (std::uint32_t m = g.first; m < g.first + g.count; ++m) {
      const Patch& patch = patches_[groups_.members[m]];
      power += patch.unshot * patch.area;
      s.magnitude += magnitude(patch.unshot) * patch.area;
      area += patch.area;
    }
    const Patch& leader = patches_[s.best];
    lost = leader.lost >= 0 ? leader.lost : leader.rough_lost;
    // (SolveOptions::whole_patch_senders: a small sender is chosen as a whole patch, or
    // as twice its size if that is less)
    s.best_power = s.magnitude;
    if (options_.whole_patch_senders && !leader.detail && area > 0 && area < patch_area_)
      s.best_power *= std::min(patch_area_ / area, 2.0);
  } else {
    const std::uint32_t c = static_cast<std::uint32_t>(n - standalone);
    const auto& cl = clusters_.clusters[c];
    for (std::uint32_t k = cl.first_part; k < cl.first_part + cl.part_count; ++k) {
      power += part_unshot_[k];
      s.magnitude += magnitude(part_unshot_[k]);
    }
    s.best = cluster_sender(c);
    lost = cluster_state_[c].lost >= 0 ? cluster_state_[c].lost : cluster_state_[c].rough_lost;
    s.best_power = s.magnitude;
  }
  s.unshot = power;
  s.staying = power * (open && lost >= 0 ? 1 - lost : 1.0);
  return s;
}

void Solver::survey_patches() {
  const bool open = sum(report_.energy.escaped) > 0;
  const std::size_t standalone = groups_.groups.size();
  const std::size_t count = standalone + clusters_.clusters.size();
  if (!survey_built_ || open != survey_open_) {
    // Every unit: the first survey, and when light first leaves (each unit's staying
    // share changes).
    survey_leaves_ = 1;
    while (survey_leaves_ < count) survey_leaves_ *= 2;
    survey_tree_.assign(2 * survey_leaves_, Survey{});
    survey_marked_.assign(count, 1);
    survey_dirty_.resize(count);
    for (std::size_t n = 0; n < count; ++n) survey_dirty_[n] = static_cast<std::uint32_t>(n);
    survey_built_ = true;
  }
  survey_open_ = open;
  std::sort(survey_dirty_.begin(), survey_dirty_.end());
  // An open scene (some light has left it): the senders holding unshot light need an
  // idea of what share of it will leave too, so that ambient() does not count light
  // that is on its way out. A rough one does (rough_lost_fraction(), 64 rays): the
  // ambient term is a sum over thousands of senders, and a sender's exact share
  // (lost_fraction(), 1,024 rays) is measured when it shoots. Measuring it exactly for
  // every sender that merely received light cost the IFC house 15% of its solve. A
  // sender gets light only in a shot that marks it, so the marked ones are all to ask.
  if (open) {
    std::vector<std::uint32_t> unknown;
    for (std::uint32_t n : survey_dirty_) {
      if (n < standalone) {
        const PlaneGroups::Group& g = groups_.groups[n];
        const std::uint32_t leader = groups_.members[g.first];
        if (patches_[leader].lost >= 0 || patches_[leader].rough_lost >= 0) continue;
        bool holds = false;
        for (std::uint32_t m = g.first; m < g.first + g.count && !holds; ++m)
          holds = !patches_[groups_.members[m]].unshot.is_zero();
        if (holds) unknown.push_back(leader);
      } else {
        const std::uint32_t c = static_cast<std::uint32_t>(n - standalone);
        if (cluster_state_[c].lost >= 0 || cluster_state_[c].rough_lost >= 0) continue;
        const auto& cl = clusters_.clusters[c];
        bool holds = false;
        for (std::uint32_t k = cl.first_part; k < cl.first_part + cl.part_count && !holds; ++k)
          holds = !part_unshot_[k].is_zero();
        if (holds) unknown.push_back(cluster_sender(c));
      }
    }
    tbb::parallel_for(std::size_t(0), unknown.size(), [&](std::size_t n) { rough_lost_fraction(unknown[n]); });
  }
  // The marked leaves, then their ancestors level by level (each parent once).
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, survey_dirty_.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k < range.end(); ++k) {
                        const std::uint32_t n = survey_dirty_[k];
                        survey_tree_[survey_leaves_ + n] = survey_unit(n, open);
                        survey_marked_[n] = 0;
                      }
                    });
  std::vector<std::size_t> level(survey_dirty_.size());
  for (std::size_t k = 0; k < survey_dirty_.size(); ++k) level[k] = survey_leaves_ + survey_dirty_[k];
  survey_dirty_.clear();
  while (!level.empty() && level.front() > 1) {
    std::size_t kept = 0;
    for (std::size_t node : level)
      if (kept == 0 || level[kept - 1] != node / 2) level[kept++] = node / 2;
    level.resize(kept);
    for (std::size_t node : level) survey_tree_[node] = join(survey_tree_[2 * node], survey_tree_[2 * node + 1]);
  }
  const Survey& total = survey_tree_[1];
#ifndef NDEBUG
  {  // the tree against a pass over every unit
    Survey all;
    for (std::size_t n = 0; n < count; ++n) all = join(all, survey_unit(n, open));
    assert(all.best == total.best && all.best_power == total.best_power);
    assert(std::abs(all.magnitude - total.magnitude) <= 1e-9 * std::max(1.0, all.magnitude));
  }
#endif
  report_.energy.unshot = total.unshot + luminaire_unshot_;
  unshot_staying_ = total.staying + luminaire_unshot_;
  unshot_magnitude_ = total.magnitude + magnitude(luminaire_unshot_);
  brightest_ = total.best;
}

}  // namespace dynrad::rad

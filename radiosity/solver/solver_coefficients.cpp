// Coefficient channels: one solve carrying the light of many skies (see
// Solver::carry_coefficients in solver.h).
#include "radiosity/solver/solver.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dynrad::rad {

namespace {
constexpr std::uint32_t kNoSlot = UINT32_MAX;
}

void Solver::carry_coefficients(CoefficientChannels channels) {
  if (channels.count == 0 || !channels.sky_mix) throw std::invalid_argument("coefficient channels: none asked for");
  if (luminaires_.size() != 1 || luminaires_[0].kind != Luminaire::Kind::sky)
    throw std::invalid_argument("coefficient channels: the only source must be one sky");
  for (const Patch& p : patches_) {
    if (!p.emission.is_zero()) throw std::invalid_argument("coefficient channels: no surface may emit");
    if (p.reflectance.max_channel() - p.reflectance.min_channel() > 1e-9 * p.reflectance.max_channel())
      throw std::invalid_argument("coefficient channels: materials must be grey");
  }
  const std::size_t n = channels.count;
  coefficients_ = std::move(channels);
  coefficient_unshot_.assign(patches_.size() * n, 0.0f);
  coefficient_total_.assign(patches_.size() * n, 0.0f);
  coefficient_direct_.assign(patches_.size() * (n - absolute_from()), 0.0f);
  coefficient_part_unshot_.assign(clusters_.parts.size() * n, 0.0f);
  coefficient_shot_.assign(n, 0.0f);
  coefficient_slot_.assign(patches_.size() + clusters_.parts.size(), kNoSlot);
}

void Solver::shoot_coefficients(std::uint32_t p, double factor, double weight) {
  const std::size_t n = coefficients_.count;
  float* u = coefficient_unshot_.data() + p * n;
  for (std::size_t j = 0; j < n; ++j) {
    const double shot = u[j] * factor;
    coefficient_shot_[j] += static_cast<float>(shot * weight);
    u[j] = static_cast<float>(u[j] - shot);
  }
}

void Solver::mix_sky(const std::vector<ElementId>& terminals, const std::vector<double>& reach) {
  const std::size_t n = coefficients_.count;
  std::vector<std::uint32_t> receivers;  // patch ids, then patches_.size() + part
  for (std::size_t t = 0; t < terminals.size(); ++t) {
    if (reach[t] <= 0) continue;
    const std::uint32_t p = hierarchy_.element(terminals[t]).patch;
    if (coefficient_slot_[p] != kNoSlot) continue;
    coefficient_slot_[p] = static_cast<std::uint32_t>(receivers.size());
    receivers.push_back(p);
  }
  for (std::uint32_t c : whole_clusters_) {
    const auto& cl = clusters_.clusters[c];
    for (std::uint32_t k = cl.first_part; k < cl.first_part + cl.part_count; ++k) {
      if (!(part_form_factor_[k] > 0)) continue;
      const std::size_t id = patches_.size() + k;
      coefficient_slot_[id] = static_cast<std::uint32_t>(receivers.size());
      receivers.push_back(static_cast<std::uint32_t>(id));
    }
  }
  coefficient_mix_.assign(receivers.size() * n, 0.0f);
  coefficient_booked_.assign(receivers.size(), 0);
  tbb::parallel_for(std::size_t(0), receivers.size(), [&](std::size_t s) {
    if (receivers[s] < patches_.size()) {
      const Patch& p = patches_[receivers[s]];
      coefficients_.sky_mix(p.corners, p.normal, coefficient_mix_.data() + s * n);
    } else {  // a cluster's part: its point
      const FaceClusters::Part& part = clusters_.parts[receivers[s] - patches_.size()];
      coefficients_.sky_mix({part.point, part.point, part.point}, part.normal, coefficient_mix_.data() + s * n);
    }
  });
}

void Solver::book_direct(std::uint32_t patch, const float* incident, float reflected) {
  const std::size_t n = coefficients_.count, from = absolute_from();
  float* direct = coefficient_direct_.data() + patch * (n - from);
  for (std::size_t j = from; j < n; ++j) direct[j - from] += reflected * incident[j];
}

// The loops below run once per receiver and shot over every channel: plain float
// multiply-adds over arrays that do not overlap, which the compiler vectorises.
void Solver::book_coefficients(std::uint32_t patch, const float* incident, float factor, bool from_sky) {
  const std::size_t n = coefficients_.count;
  const Patch& p = patches_[patch];
  const auto reflected = static_cast<float>(p.reflectance.luminance()) * factor;
  if (from_sky) book_direct(patch, incident, reflected);
  float* __restrict total = coefficient_total_.data() + patch * n;
  const float* __restrict in = incident;
  if (p.clustered) {
    float* __restrict to = coefficient_part_unshot_.data() + clusters_.part_of_patch[patch] * n;
    const auto power = reflected * static_cast<float>(p.area);  // a part holds power
    for (std::size_t j = 0; j < n; ++j) {
      total[j] += reflected * in[j];
      to[j] += power * in[j];
    }
  } else {
    float* __restrict to = coefficient_unshot_.data() + patch * n;
    for (std::size_t j = 0; j < n; ++j) {
      const float r = reflected * in[j];
      total[j] += r;
      to[j] += r;
    }
  }
}

void Solver::book_part_coefficients(std::uint32_t part, const float* incident, float factor, bool from_sky) {
  const std::size_t n = coefficients_.count;
  const auto& cl = clusters_.clusters[clusters_.parts[part].cluster];
  float* to = coefficient_part_unshot_.data() + part * n;
  for (std::uint32_t m = cl.first_member; m < cl.first_member + cl.member_count; ++m) {
    const std::uint32_t patch = clusters_.members[m];
    if (clusters_.part_of_patch[patch] != part) continue;
    const Patch& p = patches_[patch];
    const auto reflected = static_cast<float>(p.reflectance.luminance()) * factor;
    const auto power = reflected * static_cast<float>(p.area);
    if (from_sky) book_direct(patch, incident, reflected);
    float* total = coefficient_total_.data() + patch * n;
    for (std::size_t j = 0; j < n; ++j) {
      total[j] += reflected * incident[j];
      to[j] += power * incident[j];
    }
  }
}

void Solver::incident_coefficients(std::uint32_t slot, double factor, float* out) {
  const std::size_t n = coefficients_.count;
  const float* mix = coefficient_mix_.data() + slot * n;
  const std::size_t relative = std::min(n, coefficients_.relative);
  for (std::size_t j = 0; j < relative; ++j) out[j] = static_cast<float>(mix[j] * factor);
  const bool first = !coefficient_booked_[slot];
  coefficient_booked_[slot] = 1;
  for (std::size_t j = relative; j < n; ++j) out[j] = first ? mix[j] : 0.0f;
}

}  // namespace dynrad::rad

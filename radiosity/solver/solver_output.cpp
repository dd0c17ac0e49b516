// What the solve gives: the energy each shot delivers, booked (account_transfers), and
// the values per output vertex (output()).
#include "radiosity/solver/solver.h"

#include "radiosity/transfer/form_factor.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dynrad::rad {

// Energy of one shot, from the elements where it stopped. See shoot.cpp for why the
// element powers are normalised.
void Solver::account_transfers(const std::vector<ElementId>& terminals, const std::vector<double>& reach,
                               std::uint32_t sender_id, const Rgb& shot_radiosity) {
  const double lost = lost_fraction(sender_id);
  // What one unit of the shot carries: a patch's area, a luminaire's flux; a cluster
  // shoots its power itself.
  const bool from_luminaire = is_luminaire(sender_id);
  const bool from_cluster = is_cluster(sender_id);
  const double power = from_luminaire  ? luminaire_flux_[sender_id - patches_.size()]
                       : from_cluster ? 1.0
                                      : group_of(sender_id).area;
  const double escaped = from_luminaire  ? luminaire_escaped_[sender_id - patches_.size()]
                         : from_cluster ? cluster_state_[cluster_index(sender_id)].escaped
                                        : patches_[sender_id].escaped;
  double received = 0;
  for (double r : reach) received += r;  // in order: the same total for any number of threads
  for (std::uint32_t c : whole_clusters_) {
    const auto& cl = clusters_.clusters[c];
    for (std::uint32_t k = cl.first_part; k < cl.first_part + cl.part_count; ++k)
      received += clusters_.parts[k].area * part_form_factor_[k];
  }
  const double reachable = power * (1 - lost);
  double scale = 0;
  if (received > 0 && reachable > 0) {
    scale = reachable / received;
    form_factor_error_sum_ += std::abs(1 - received / reachable);
  }
  // Per receiving patch: a patch's terminal elements mostly come in runs (siblings have
  // neighbouring ids), so the reach of a run is summed before it is booked.
  Rgb incident_total;
  // Coefficient channels (solver_coefficients.cpp): the same transfer for each.
  const std::size_t channels = coefficients_.count;
  std::vector<float> channel_incident(channels);
  if (channels > 0 && from_luminaire) mix_sky(terminals, reach);
  const double shot_luminance = shot_radiosity.luminance();
  const bool direct = is_direct_sender(sender_id);  // its light stays out of the values (exact_direct.cpp)
  auto book = [&](std::uint32_t patch_id, double patch_reach) {
    if (patch_reach <= 0) return;
    Patch& receiver = patches_[patch_id];
    if (channels > 0 && from_luminaire) {
      incident_coefficients(coefficient_slot_[patch_id], shot_luminance * patch_reach * scale / receiver.area,
                            channel_incident.data());
      book_coefficients(patch_id, channel_incident.data(), 1.0f, true);
    } else if (channels > 0) {
      book_coefficients(patch_id, coefficient_shot_.data(), static_cast<float>(patch_reach * scale / receiver.area),
                        false);
    }
    mark_surveyed(unit_of_receiver(patch_id));
    const Rgb incident = shot_radiosity * (patch_reach * scale);
    const Rgb reflected = receiver.reflectance * incident;
    if (receiver.clustered)  // its cluster sends it, with its part
      part_unshot_[clusters_.part_of_patch[patch_id]] += reflected;
    else
      receiver.unshot += reflected * (1.0 / receiver.area);  // eq. 3: area-weighted pull-up
    if (direct) note_direct(patch_id, reflected * (1.0 / receiver.area));
    report_.energy.absorbed += incident - reflected;
    incident_total += incident;
  };
  std::uint32_t run_patch = 0;
  double run_reach = 0;
  for (std::size_t t = 0; t < terminals.size(); ++t) {
    if (reach[t] <= 0) continue;
    const std::uint32_t patch_id = hierarchy_.element(terminals[t]).patch;
    if (patch_id != run_patch) {
      book(run_patch, run_reach);
      run_patch = patch_id;
      run_reach = 0;
    }
    run_reach += reach[t];
  }
  book(run_patch, run_reach);
  // Clusters received as one: each part takes its share; its patches get the light when
  // the cluster is flushed (flush_cluster).
  for (std::uint32_t c : whole_clusters_) {
    const auto& cl = clusters_.clusters[c];
    mark_surveyed(static_cast<std::uint32_t>(groups_.groups.size()) + c);
    for (std::uint32_t k = cl.first_part; k < cl.first_part + cl.part_count; ++k) {
      const double f = part_form_factor_[k];
      if (!(f > 0)) continue;
      const Rgb incident = shot_radiosity * (clusters_.parts[k].area * f * scale);
      const Rgb reflected = part_reflectance_area_[k] * shot_radiosity * (f * scale);
      part_unshot_[k] += reflected;
      report_.energy.absorbed += incident - reflected;
      incident_total += incident;
      if (!direct) {
        part_pending_[k] += shot_radiosity * f;
        cluster_state_[c].dirty = true;
      }
      if (channels > 0 && from_luminaire) {
        incident_coefficients(coefficient_slot_[patches_.size() + k], shot_luminance * f * scale,
                              channel_incident.data());
        book_part_coefficients(k, channel_incident.data(), 1.0f, true);
      } else if (channels > 0) {
        book_part_coefficients(k, coefficient_shot_.data(), static_cast<float>(f * scale), false);
      }
    }
  }
  // A direct sender's light on the clusters received as one: each patch's mean.
  if (direct)
    for (std::uint32_t c : whole_clusters_) {
      const auto& cl = clusters_.clusters[c];
      for (std::uint32_t n = cl.first_member; n < cl.first_member + cl.member_count; ++n) {
        const std::uint32_t p = clusters_.members[n];
        const double f = part_form_factor_[clusters_.part_of_patch[p]];
        if (f > 0) note_direct(p, patches_[p].reflectance * shot_radiosity * (f * scale));
      }
    }
  if (channels > 0 && from_luminaire) std::fill(coefficient_slot_.begin(), coefficient_slot_.end(), UINT32_MAX);
  // What no front face received: out of the scene, or onto black back faces. In a
  // closed scene only rounding is left; it is booked as absorbed.
  const Rgb not_received = shot_radiosity * power - incident_total;
  const double escaped_share = lost > 0 ? escaped / lost : 0.0;
  report_.energy.escaped += not_received * escaped_share;
  report_.energy.absorbed += not_received * (1 - escaped_share);
  if (!from_luminaire) mark_surveyed(unit_of_sender(sender_id));
  survey_patches();
}

Solver::Output Solver::output(bool ambient_display) {
  flush_all();
  update_direct_gaps();
  build_direct_lists();
  Output out;
  out.split = split_vertices(scene_, options_.crease_angle);
  out.radiosity.assign(out.split.size(), Rgb());
  out.emitter.assign(out.split.size(), 0);
  out.irradiance.assign(out.split.size(), Rgb());
  std::vector<double> weight(out.split.size(), 0.0);
  std::vector<double> mesh_at(out.split.size(), 0.0), unshot_at(out.split.size(), 0.0);
  const Rgb unshot_error = unshot_error_radiosity();
  auto arriving = [](const Rgb& b, const Patch& p) {
    auto channel = [](double value, double e, double rho) { return rho > 0 ? (value - e) / rho : 0.0; };
    return Rgb(channel(b.r, p.emission.r, p.reflectance.r), channel(b.g, p.emission.g, p.reflectance.g),
               channel(b.b, p.emission.b, p.reflectance.b));
  };
  const TriMesh& mesh = scene_.mesh();
  const Rgb ambient_now = ambient_display ? ambient() : Rgb();
  // Beside the ambient term, the unshot light of each vertex's near patches (near_unshot()).
  std::vector<Rgb> near;
  if (ambient_display && options_.near_unshot) {
    std::vector<char> wanted(receivers_.size(), 0);
    for (auto f : mesh.faces()) {
      const ElementId e = hierarchy_.element_of(f);
      for (int j = 0; j < 3; ++j) wanted[corner_receiver_[e][j]] = 1;
    }
    near = near_unshot(wanted);
  }
  // Direct light at every receiver of a lit patch (exact_direct.cpp).
  if (!lit_luminaires_.empty()) {
    std::vector<std::uint32_t> wanted;
    for (auto f : mesh.faces()) {
      const ElementId e = hierarchy_.element_of(f);
      if (directly_lit(hierarchy_.element(e).patch))
        for (int j = 0; j < 3; ++j) wanted.push_back(corner_receiver_[e][j]);
    }
    compute_receiver_direct(std::move(wanted));
  }
  for (auto f : mesh.faces()) {
    const ElementId e = hierarchy_.element_of(f);
    const Element& el = hierarchy_.element(e);
    const Rgb extra = patches_[el.patch].reflectance * ambient_now;
    const double mesh_here = mesh_error(e);
    const double unshot_here = (patches_[el.patch].reflectance * unshot_error).luminance();
    int k = 0;
    for (auto v : mesh.fv_range(f)) {
      const auto node = out.split.corner[3 * f.idx() + k++];
      for (int j = 0; j < 3; ++j)
        if (el.corners[j] == v) {
          const std::uint32_t r = corner_receiver_[e][j];
          const Rgb b = value_[e][j] + extra + patches_[el.patch].reflectance * receiver_direct(r) +
                        (near.empty() ? Rgb() : patches_[el.patch].reflectance * near[r]);
          out.radiosity[node] += b * el.area;
          out.irradiance[node] += arriving(b, patches_[el.patch]) * el.area;
        }
      weight[node] += el.area;
      out.emitter[node] = scene_.material(f).emits();
      mesh_at[node] = std::max(mesh_at[node], mesh_here);
      unshot_at[node] = std::max(unshot_at[node], unshot_here);
    }
  }
  out.error.assign(out.split.size(), 0.0f);
  for (std::size_t i = 0; i < weight.size(); ++i)
    if (weight[i] > 0) {
      out.radiosity[i] = out.radiosity[i] * (1.0 / weight[i]);
      out.irradiance[i] = out.irradiance[i] * (1.0 / weight[i]);
      const double b = out.radiosity[i].luminance();
      if (b > 0) out.error[i] = static_cast<float>((mesh_at[i] + unshot_at[i]) / b);
    }
  return out;
}

void Solver::release_elements() {
  value_ = {};
  pending_ = {};
  gathered_in_ = {};
  corner_receiver_ = {};
  form_factor_ = {};
  form_factor_shot_ = {};
  std::vector<Receiver>().swap(receivers_);
  receiver_id_ = {};
  std::vector<DirectAt>().swap(receiver_direct_);
  std::vector<float>().swap(display_gap_);
  std::vector<float>().swap(direct_gap_);
  std::vector<float>().swap(receiver_seen_);
  held_.clear();
  std::vector<WalkChunk>().swap(walk_chunks_);
  visibility_.reset();
  initialised_ = 0;
}

}  // namespace dynrad::rad

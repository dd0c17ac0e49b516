// Values of elements: new elements start from their parent (gathered, or
// interpolated), push-down hands a shot on to the elements below where it stopped,
// and flush() delivers what is pending.
#include "radiosity/solver/solver.h"

#include "radiosity/transfer/form_factor.h"
#include "radiosity/transfer/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <unordered_map>

namespace dynrad::rad {

namespace {

// The near-field corrections' share and rays (Solver::near_seen_share).
constexpr double kNearFieldShare = 0.05;
constexpr int kNearRays = 4;

}  // namespace

void Solver::gather_new_elements(std::size_t first) {
  // Earlier shots, and the current one (the sender's unshot was moved to current_shot_).
  // Luminaires that have shot (the current one included) come first, as they shot.
  std::vector<std::uint32_t> shooters;
  for (std::size_t k = 0; k < next_luminaire_; ++k)  // (but direct senders: exact_direct.cpp)
    if (!is_direct_sender(static_cast<std::uint32_t>(patches_.size() + k)))
      shooters.push_back(static_cast<std::uint32_t>(patches_.size() + k));
  for (std::uint32_t j = 0; j < patches_.size(); ++j)
    if (!patches_[j].shot.is_zero() || j == sender_) shooters.push_back(j);
  auto shot_of = [this](std::uint32_t j) {
    if (is_luminaire(j)) return luminaire(j).colour;
    return j == sender_ ? patches_[j].shot + current_shot_ : patches_[j].shot;
  };
  // One gather per receiver of the new elements.
  std::unordered_map<std::uint32_t, std::size_t> index;
  std::vector<std::uint32_t> todo;
  for (ElementId e = static_cast<ElementId>(first); e < hierarchy_.element_count(); ++e)
    for (std::uint32_t r : corner_receiver_[e])
      if (index.emplace(r, todo.size()).second) todo.push_back(r);
  // Geometry only (sum of F times shot radiosity) is shared by the facing; emission
  // and reflectance are each element's own (a lamp and the ceiling around it share a
  // facing and the border vertices).
  // Each patch's shots were shaped (shape_of); what they shipped in all has the shape
  // of what its nodes shipped (Patch::shot_at_nodes), which the gather gives back: a
  // new vertex then gets the light its neighbours got, not that of even senders.
  std::vector<SenderShape> shipped(shooters.size());
  if (options_.shaped_senders)
    for (std::size_t i = 0; i < shooters.size(); ++i)
      if (!is_luminaire(shooters[i]) && !is_cluster(shooters[i]) && shooters[i] != sender_)
        shipped[i] = shipped_shape(shooters[i]);
  std::vector<Rgb> gathered(todo.size());
  tbb::parallel_for(std::size_t(0), todo.size(), [&](std::size_t n) {
    const Receiver& r = receivers_[todo[n]];
    const Patch& patch = patches_[r.patch];
    Rgb sum;
    for (std::size_t i = 0; i < shooters.size(); ++i) {
      const std::uint32_t j = shooters[i];
      if (j == r.patch) continue;
      double flat = 0;
      double f = point_form_factor(r.vertex, r.point, patch.normal, j, &flat);
      if (shipped[i].on && f > 0 && flat > 0) {
        const Patch& q = patches_[j];
        f *= shaped_closed_form(r.point, patch.normal, q.corners, q.centre, q.radius, q.area, q.normal, shipped[i]) /
             flat;
      }
      sum += shot_of(j) * f;
    }
    gathered[n] = sum;
  });
  for (ElementId e = static_cast<ElementId>(first); e < hierarchy_.element_count(); ++e) {
    const Element& el = hierarchy_.element(e);
    const Patch& patch = patches_[el.patch];
    for (int k = 0; k < 3; ++k)
      value_[e][k] = patch.emission + patch.reflectance * gathered[index.at(corner_receiver_[e][k])];
    gathered_in_[e] = report_.iterations + 1;
    report_.energy_transfers += shooters.size();  // shoot(j, e) for every earlier sender j
    if (el.generation > 0) report_.patch_element_transfers += shooters.size();
  }
}

std::array<double, 3> Solver::barycentric(ElementId e, const Vec3d& point) const {
  const Element& el = hierarchy_.element(e);
  const Vec3d& n = hierarchy_.normal(e);
  Vec3d c[3];
  for (int k = 0; k < 3; ++k) c[k] = hierarchy_.position(el.corners[k]);
  const double area = OpenMesh::dot(OpenMesh::cross(c[1] - c[0], c[2] - c[0]), n);
  std::array<double, 3> l;
  for (int k = 0; k < 3; ++k)
    l[k] = OpenMesh::dot(OpenMesh::cross(c[(k + 1) % 3] - point, c[(k + 2) % 3] - point), n) / area;
  return l;
}

Rgb Solver::quadratic(const std::array<Rgb, 6>& nodes, const std::array<double, 3>& l) {
  Rgb out;
  for (int k = 0; k < 3; ++k) {
    out += nodes[k] * (l[k] * (2 * l[k] - 1));
    out += nodes[3 + k] * (4 * l[k] * l[(k + 1) % 3]);
  }
  return out;
}

Rgb Solver::interpolate(ElementId e, const std::array<Rgb, 3>& at_corners, const Vec3d& point) const {
  const Element& el = hierarchy_.element(e);
  const Vec3d& n = hierarchy_.normal(e);
  Vec3d c[3];
  for (int k = 0; k < 3; ++k) c[k] = hierarchy_.position(el.corners[k]);
  const double area = OpenMesh::dot(OpenMesh::cross(c[1] - c[0], c[2] - c[0]), n);
  Rgb out;
  for (int k = 0; k < 3; ++k) {
    const double w = OpenMesh::dot(OpenMesh::cross(c[(k + 1) % 3] - point, c[(k + 2) % 3] - point), n) / area;
    out += at_corners[k] * w;
  }
  return out;
}

void Solver::initialise_new_elements() {
  const std::size_t count = hierarchy_.element_count();
  const ElementId first = static_cast<ElementId>(initialised_);
  if (count == first) return;
  // The new entries are written below, in parallel (their memory is touched first there).
  value_.resize_for_overwrite(count);
  // (none in the display's refinement, which follows the last shot: refine_for_display)
  if (!refining_for_display_) pending_.resize(count);
  gathered_in_.resize_for_overwrite(count);
  if (refine_.method == Method::adaptive || refine_.new_elements == RefineSettings::NewElements::gather) {
    register_receivers(first);
    for (ElementId e = first; e < count; ++e) gathered_in_[e] = 0;
    gather_new_elements(initialised_);
    initialised_ = count;
    direct_for_new_elements(first);
    return;
  }
  // In parallel. A new element's parent may be new too (a 1 -> 4 split bisects twice),
  // so each takes its values from its nearest ancestor that already had values: the
  // same as going through the new parents, since both rules reproduce a linear (or
  // constant) function on the flat ancestor.
  // Meanwhile another thread registers the new receivers (serial: a hash map); neither
  // reads what the other writes.
  if (count - first < 256) {  // too few to wake the other threads for
    register_receivers(first);
    initialise_values(first, count);
    initialised_ = count;
    direct_for_new_elements(first);
    return;
  }
  // Storage for the new receivers first, so that registering moves nothing the values
  // read meanwhile (near_field_start reads the source corners' receivers).
  corner_receiver_.resize(count);
  receivers_.reserve(receivers_.size() + 3 * (count - first));
  tbb::task_group registering;
  registering.run([this, first] { register_receivers(first); });
  try {
    initialise_values(first, count);
  } catch (...) {
    registering.wait();
    throw;
  }
  registering.wait();
  initialised_ = count;
  direct_for_new_elements(first);
}

void Solver::direct_for_new_elements(ElementId first) {
  if (!direct_lists_built_ || lit_luminaires_.empty()) return;
  std::vector<std::uint32_t> wanted;
  for (ElementId e = first; e < hierarchy_.element_count(); ++e)
    if (directly_lit(hierarchy_.element(e).patch))
      for (const std::uint32_t r : corner_receiver_[e]) wanted.push_back(r);
  compute_receiver_direct(std::move(wanted));
}

void Solver::initialise_values(ElementId first, std::size_t count) {
  parallel_for_index(count - first, 1024, [&](std::size_t n) {
    const ElementId e = first + static_cast<ElementId>(n);
    gathered_in_[e] = 0;
    const Element& el = hierarchy_.element(e);
    ElementId source = el.parent;
    while (source >= first) source = hierarchy_.element(source).parent;
    const auto& p = value_[source];
    // (not in the display's refinement: its vertices show the values between the solve's
    // corners as those corners' elements interpolate them; exact_direct.cpp)
    const bool bends = refine_.near_field_start && refine_.method == Method::dynamic && !refining_for_display_;
    // (see below: whether the source lacks push-down its ancestors still hold)
    const bool stale = bends && pending_above(source);
    if (refine_.new_elements == RefineSettings::NewElements::constant) {
      const Rgb mean = (p[0] + p[1] + p[2]) * (1.0 / 3);
      value_[e] = {mean, mean, mean};
    } else {
      const Element& src = hierarchy_.element(source);
      thread_local std::vector<std::uint32_t> scratch;
      for (int k = 0; k < 3; ++k) {
        const VertexHandle v = el.corners[k];
        const Vec3d position = hierarchy_.position(v);
        value_[e][k] = interpolate(source, p, position);
        const bool new_vertex = v != src.corners[0] && v != src.corners[1] && v != src.corners[2];
        // The bend is taken against the line through the source's corners, which it
        // takes to hold each nearby sender's light as F there. A source the walk did
        // not pass (the neighbour that conforming bisection splits too) may still lack
        // what its ancestors' push-down holds for it; that arrives later, interpolated
        // from the ancestor, and a bend on top of it counts the bend twice: at the
        // foot of the Cornell demo's short block one side of a new vertex started 40%
        // above the other and kept the difference, a vertex 10% above its ring. Such a
        // source bends only vertices on its plane's edge, where F jumps across the
        // edge and the ancestor's push-down cannot have it (without the bend there, a
        // furnace's edge vertex was 5% low).
        if (new_vertex && bends && (!stale || on_plane_edge(v, hierarchy_.normal(source))))
          value_[e][k] += near_field_start(e, source, position, value_[e][k].luminance(), scratch);
      }
    }
  });
}

bool Solver::pending_above(ElementId e) const {
  for (ElementId a = hierarchy_.element(e).parent; a != kNoElement; a = hierarchy_.element(a).parent)
    for (const Rgb& v : pending_[a])
      if (!v.is_zero()) return true;
  return false;
}

bool Solver::on_plane_edge(VertexHandle v, const Vec3d& normal) const {
  const TriMesh& mesh = scene_.mesh();
  if (mesh.is_boundary(v)) return true;
  for (auto f : mesh.vf_range(v))
    if (OpenMesh::dot(mesh.normal(f), normal) <= 1 - 1e-9) return true;
  return false;
}

Rgb Solver::near_field_start(ElementId e, ElementId source, const Vec3d& position, double line,
                             std::vector<std::uint32_t>& scratch) const {
  const Element& src = hierarchy_.element(source);
  const Patch& patch = patches_[src.patch];
  const Vec3d& n = hierarchy_.normal(source);
  const Vec3d centroid = hierarchy_.centroid(source);
  double radius = 0;
  Vec3d corner_point[3];
  for (int k = 0; k < 3; ++k) {
    radius = std::max(radius, (hierarchy_.position(src.corners[k]) - centroid).norm());
    // Where the corner's light was computed (the step into the element that registered
    // it), not a step into the source: at a patch's corner on an edge, F from that patch
    // jumps across the corner, and the bend taken from a point on the wrong side of it
    // was off by the whole jump (a furnace's edge vertex 4% too bright at high quality).
    corner_point[k] = receivers_[corner_receiver_[source][k]].point;
  }
  // The new corner's evaluation point, as register_receivers() places it.
  const Vec3d point = position + (hierarchy_.centroid(e) - position) * 1e-2;
  const std::array<double, 3> l = barycentric(source, position);
  scratch.clear();
  patch_index_.near(point, radius, scratch);  // (only patches that have shot are in it)
  // Only patches whose light could bend the start by kNearFieldShare of the value the
  // line gives (F's bend is at most 1), and only within one radius of the source: on
  // the IFC house, every patch within two radii of every new vertex cost a fifth of the
  // solve.
  Rgb add;
  for (std::uint32_t j : scratch) {
    const Patch& s = patches_[j];
    if (j == src.patch || s.plane == patch.plane) continue;
    if ((patch.reflectance * s.shot).luminance() < kNearFieldShare * line) continue;
    // F at each point times the share of the patch seen from there: a patch behind a
    // partition or a wall's thickness sends nothing, however near. (Without the rays,
    // the floor along the foot of the obstructed 1990 room's partition started each
    // new vertex with light from the back wall on the partition's lit side, and ended
    // up to 97% too bright.)
    auto f = [&](const Vec3d& x) {
      const double open = point_to_triangle(x, n, s.corners[0], s.corners[1], s.corners[2], s.normal);
      return open > 0 ? open * near_seen_share(x, n, s) : 0.0;
    };
    const double bend = f(point) - (l[0] * f(corner_point[0]) + l[1] * f(corner_point[1]) + l[2] * f(corner_point[2]));
    add += s.shot * bend;
  }
  return patch.reflectance * add;
}

double Solver::near_seen_share(const Vec3d& x, const Vec3d& n, const Patch& p) const {
  const Vec3d targets[kNearRays] = {p.centre, (p.corners[0] + p.centre) * 0.5, (p.corners[1] + p.centre) * 0.5,
                                    (p.corners[2] + p.centre) * 0.5};
  return static_cast<double>(visibility_->visible_count(x, n, targets, kNearRays, p.normal)) / kNearRays;
}

void Solver::restart_split_terminals(std::size_t first, std::vector<ElementId> terminals, const Rgb& shot) {
  const std::size_t count = hierarchy_.element_count();
  if (count == first || (terminals.empty() && held_.empty())) return;
  std::sort(terminals.begin(), terminals.end());
  auto holds = [&](ElementId s) {
    return std::binary_search(terminals.begin(), terminals.end(), s) || held_.count(s) > 0;
  };
  std::vector<ElementId> affected;
  std::vector<ElementId> source_of;
  for (ElementId e = static_cast<ElementId>(first); e < count; ++e) {
    ElementId source = hierarchy_.element(e).parent;
    while (source >= first) source = hierarchy_.element(source).parent;
    if (!holds(source)) continue;
    affected.push_back(e);
    source_of.push_back(source);
  }
  std::vector<HeldShot> now(affected.size());
  parallel_for_index(affected.size(), 64, [&](std::size_t n) {
    const ElementId e = affected[n], source = source_of[n];
    const Element& el = hierarchy_.element(e);
    const Element& src = hierarchy_.element(source);
    const Patch& patch = patches_[el.patch];
    // This shot's dB at the source's corners, as it was inherited, and the fractions of
    // the sender they see: a terminal's from its corners' form factors; an element split
    // from a terminal earlier in this shot (and split again since) as it was restarted.
    HeldShot at_source;
    if (const auto it = held_.find(source); it != held_.end()) {
      at_source = it->second;
    } else {
      for (int k = 0; k < 3; ++k) {
        at_source.dB[k] = patch.reflectance * shot * form_factor(source, k);
        at_source.seen[k] = corner_form_factor(source, k).visible_fraction();
      }
    }
    HeldShot& held = now[n];
    for (int k = 0; k < 3; ++k) {
      const VertexHandle v = el.corners[k];
      const Vec3d position = hierarchy_.position(v);
      const std::array<double, 3> l = barycentric(source, position);
      const Rgb line = interpolate(source, at_source.dB, position);
      held.seen[k] = l[0] * at_source.seen[0] + l[1] * at_source.seen[1] + l[2] * at_source.seen[2];
      held.dB[k] = line;
      if (v == src.corners[0] || v == src.corners[1] || v == src.corners[2]) continue;  // exact already
      // The sender's closed form at the new corner's evaluation point (the kernel, which
      // bends beside a neighbouring surface), times the visible fraction interpolated
      // from the source's corners (as at the push-down's midpoints: no rays, so no
      // vertex is left to two rays' say).
      const Vec3d point = receivers_[corner_receiver_[e][k]].point;
      held.dB[k] = patch.reflectance * shot * (held.seen[k] * sender_closed_form(point, hierarchy_.normal(e)));
      value_[e][k] = value_[e][k] - line + held.dB[k];
    }
  });
  for (std::size_t n = 0; n < affected.size(); ++n) held_[affected[n]] = now[n];
}

void Solver::push_down(ElementId q, const std::array<Rgb, 6>& delta) {
  if (hierarchy_.element(q).is_leaf()) return;
  for (int k = 0; k < 6; ++k) pending_[q][k] += delta[k];
}

void Solver::flush(ElementId q) {
  const Element& el = hierarchy_.element(q);
  if (el.is_leaf() || q >= pending_.size()) return;  // (none held: refine_for_display)
  std::array<Rgb, 6>& pending = pending_[q];
  bool zero = true;
  for (const Rgb& v : pending) zero = zero && v.is_zero();
  if (zero) return;
  // A bisection: each child has the corner opposite the split edge (the parent corner
  // both children have), one end of that edge, and its midpoint. The children's nodes
  // are then known in the parent's barycentric coordinates without any geometry: a
  // corner of the parent is a unit vector, the new point is half of each end, and a
  // child's edge midpoint is the mean of its ends' coordinates.
  const Element& first = hierarchy_.element(el.children[0]);
  const Element& second = hierarchy_.element(el.children[1]);
  auto has = [](const Element& e, VertexHandle v) {
    return e.corners[0] == v || e.corners[1] == v || e.corners[2] == v;
  };
  int opposite = 0;
  while (opposite < 2 && !(has(first, el.corners[opposite]) && has(second, el.corners[opposite]))) ++opposite;
  for (ElementId c : el.children) {
    const Element& child = hierarchy_.element(c);
    std::array<std::array<double, 3>, 3> at;  // barycentric coordinates of the child's corners
    for (int k = 0; k < 3; ++k) {
      int j = 0;
      while (j < 3 && child.corners[k] != el.corners[j]) ++j;
      if (j < 3) {
        at[k] = {0, 0, 0};
        at[k][j] = 1;
      } else {  // the midpoint of the split edge
        at[k] = {0.5, 0.5, 0.5};
        at[k][opposite] = 0;
      }
    }
    std::array<Rgb, 6> delta;
    for (int k = 0; k < 3; ++k) {
      const auto& a = at[k];
      const auto& b = at[(k + 1) % 3];
      // A corner is a node of the parent: a corner's or the split edge's midpoint's.
      int j = 0;
      while (j < 3 && a[j] != 1) ++j;
      delta[k] = j < 3 ? pending[j] : pending[3 + (opposite + 1) % 3];
      delta[3 + k] = quadratic(pending, {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])});
    }
    for (int k = 0; k < 3; ++k) value_[c][k] += delta[k];
    push_down(c, delta);
  }
  pending = {};
}

void Solver::flush_all() {
  flush_clusters();
  // Each patch's tree on its own: flush() writes only below the element it flushes.
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, static_cast<std::uint32_t>(patches_.size()), 64),
                    [this](const tbb::blocked_range<std::uint32_t>& range) {
                      std::vector<ElementId> stack;
                      for (std::uint32_t p = range.begin(); p < range.end(); ++p) {
                        stack.assign(1, hierarchy_.patch_root(p));
                        while (!stack.empty()) {
                          const ElementId e = stack.back();
                          stack.pop_back();
                          const Element& el = hierarchy_.element(e);
                          if (el.is_leaf()) continue;
                          flush(e);
                          stack.push_back(el.children[0]);
                          stack.push_back(el.children[1]);
                        }
                      }
                    });
}

}  // namespace dynrad::rad

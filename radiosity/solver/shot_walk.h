// The state of one shot's walk down the element hierarchy (radiosity/shoot.cpp, the
// paper's Figure 5): the rules the sender's shot follows, the walk's levels, and what
// each parallel chunk of a level found.
#pragma once

#include "mesh/core/refinement.h"
#include "mesh/core/types.h"
#include "radiosity/solver/oracle.h"

#include <cstddef>
#include <vector>

namespace dynrad::rad {

// A chunk of one level of a shot's walk: what its elements add to the shot's lists
// and counters, in level order (see shoot_once()). Kept between shots for their
// storage.
struct WalkChunk {
  std::vector<ElementId> passed;  // the shot goes on below
  std::vector<ElementId> subdivide, ready, terminals;
  std::vector<double> reach;  // per terminal
  std::size_t transfers = 0, patch_transfers = 0;
  void count(const Element& el) {  // a transfer, as the paper counts them
    ++transfers;
    if (el.generation > 0) ++patch_transfers;
  }
  void clear() {
    passed.clear();
    subdivide.clear();
    ready.clear();
    terminals.clear();
    reach.clear();
    transfers = patch_transfers = 0;
  }
};
// What decides refinement in this shot (a luminaire's and a primary patch's are
// sharper: see shot_rules()).
struct ShotRules {
  bool from_luminaire = false, primary = false, sharp = false;
  // A luminaire or the sun under RefineSettings::exact_direct: the shot stops at the
  // patches and leaves the element values alone (exact_direct.cpp).
  bool direct = false;
  int max_generation = 0, detail_generation = 0;  // how deep elements may go (detail: on Patch::detail)
  OracleThresholds oracle, detail_oracle;
  Rgb ambient_now;  // for the push-down oracle (OracleThresholds::pushdown_ambient)
};
// The walk's lists: this level's elements, what it passes on, where the shot stopped.
struct ShotWalk {
  std::vector<ElementId> level, next;
  std::vector<ElementId> passed;     // the shot goes on below them
  std::vector<ElementId> subdivide;  // leaves among them, to split
  std::vector<ElementId> ready;      // existing elements of the next level
  std::vector<ElementId> terminals;  // the shot stopped there
  std::vector<double> reach;         // per terminal
  // Adaptive: children of a leaf split in this shot, which the walk splits again to
  // complete the 1 -> 4 split (sorted), this level's and the next's.
  std::vector<ElementId> complete_split, complete_split_next;
};

}  // namespace dynrad::rad

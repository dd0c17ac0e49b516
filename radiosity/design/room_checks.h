// EN 12464-1:2021 per room: what a lighting designer signs off for a room whose task
// area is a calculation grid (grid.h; its "target" says which checks apply, RoomTargets).
//
//   task area     the grid's points (the polygon less its border): Em, U0
//   surrounding   a band just outside the task area inside the polygon (the immediate
//                 surrounding, at least 0.5 m wide): Em (by the standard's table from the
//                 task's, unless given) and U0 (0.40), at the grid's height
//   walls         the polygon's sides raised from the floor to the ceiling, points 1 cm
//                 inside facing in: Em (75 lx) and U0 (0.10)
//   ceiling       the polygon at the ceiling, points 1 cm below facing down: Em (50 lx)
//                 and U0 (0.10)
//   cylindrical   Ez over the task area's points at 1.2 m (seated) or 1.6 m (standing)
//                 above the floor: mean and U0 (0.10), and modelling, the mean of Ez / Eh
//                 at those points, within 0.30-0.60
//   UGR           the largest UGR of the observers whose eye lies over the polygon,
//                 against the limit UGR_L
//
// The floor and the ceiling are found by rays straight down and up from the polygon's
// middle at the grid's height. Wall, ceiling and band points are spaced by the automatic
// rule (grid.h) on the surface's longer side, and at most half the band's width
// apart across it (two rows at least). Points inside solids (furniture against a wall)
// are left out and counted, as for grids.
#pragma once

#include "radiosity/design/check.h"
#include "radiosity/analysis/grid.h"

#include <string>
#include <vector>

namespace dynrad::rad {

// An observer's UGR (design/glare.h), as the room check needs it.
struct ObserverGlare {
  std::string name;
  Vec3d eye{0, 0, 0};
  double ugr = 0;
  bool defined = false;
};

struct RoomResult {
  std::string name;              // the grid's
  double floor = 0, ceiling = 0;  // along up; ceiling 0 when none was found
  PointStatistics surrounding, walls, ceiling_surface, cylindrical;
  double modelling = 0, modelling_min = 0, modelling_max = 0;  // Ez / Eh over the task area
  std::vector<std::string> observers;  // those in the room
  std::vector<Check> checks;
  bool met() const { return all_met(checks); }
};

// The checks of `task`'s spec (a grid gathered by gather_grid). Empty checks when the
// spec asks for none (no target at all).
RoomResult check_room(const LitScene& scene, const GridResult& task, const std::vector<ObserverGlare>& observers,
                      const GatherOptions& options = {});

}  // namespace dynrad::rad

// Views of a lit scene for a report: cameras declared in the scene file, and automatic
// ones that work inside buildings: a plan of each storey cut at a height, and a camera
// in each room (radiosity/analysis/rooms.h finds both). Also the preview's camera: of all
// candidate views, the one that shows the most lit surface.
#pragma once

#include "radiosity/analysis/grid.h"
#include "radiosity/analysis/render.h"

#include <string>
#include <vector>

namespace dynrad::rad {

struct View {
  enum class Kind { declared, plan, room, overview };
  std::string name;   // names files: letters, digits, '-', '_', '.'
  Kind kind = Kind::declared;
  Camera camera;
  int width = 800, height = 600;
  std::string description;  // one line for people: where the camera is and what it shows
};

const char* kind_name(View::Kind kind);

// The "cameras" array of a JSON scene file (none for other files). Each entry:
//   "name"      names the view's files (default "camera1", ...)
//   "position"  [x, y, z], the eye
//   "look_at"   [x, y, z], a point in the middle of the picture
//   "fov"       vertical field of view in degrees, (0, 170) (default 60)
//   "up"        [x, y, z], the picture's up (default: the model's up axis, +z)
//   "width", "height"  pixels (default 800 x 600)
// Unknown keys and bad values are InputErrors naming the entry.
std::vector<View> read_cameras(const std::string& path);

struct ViewOptions {
  int width = 800;        // room views' width (height 3/4 of it); plans fit this width
  bool plans = true;      // a plan view per storey
  bool rooms = true;      // a view per room
  // The display exposure (radiosity to display white 0.9). When set, a room's camera
  // stands in whichever of its corners sees the most lit surface (as best_lit_view
  // scores); 0: in the corner farthest from the room's middle.
  double exposure = 0;
};

// Plans of each storey and a view of each room, named plan_storeyN and room_NAME (a
// room takes the name of a grid whose polygon holds its middle, else storeyN_roomK). A
// room's camera stands in a corner at 0.6 of the ceiling height, looking at the room's
// middle at 0.3 of it.
std::vector<View> automatic_views(const LitScene& scene, const std::vector<GridSpec>& grids,
                                  const ViewOptions& options = {});

// The declared views, then the automatic ones whose names none of them takes.
std::vector<View> merge_views(const std::vector<View>& declared, const std::vector<View>& automatic);

// Views from outside each side of the scene, from near each wall and from the middle,
// looking along the axes other than up.
std::vector<View> overview_candidates(const LitScene& scene, int width, int height);

// Of `candidates`, the one whose rays meet the most lit surface: the summed area of the
// distinct planes met by a 48 x 48 ray sample whose radiosity is at least 1% of the
// display white (0.9 / exposure). A view filled by one wall scores less than one that
// takes in the room; a view from outside a closed building (its walls unlit) scores
// nothing.
View best_lit_view(const LitScene& scene, const std::vector<View>& candidates, double exposure);

}  // namespace dynrad::rad

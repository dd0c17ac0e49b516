// Views of a lit scene as pictures: for each view, a true-colour PNG (the PLY colours'
// exposure and sRGB curve) and a false-colour PNG of luminance with a legend in the
// scene's units, PREFIX_view_NAME.png and PREFIX_view_NAME_luminance.png.
#pragma once

#include "mesh/io/export.h"
#include "radiosity/analysis/views.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace dynrad::report {

struct ViewPictures {
  rad::View view;
  rad::Image colour, luminance;
  double luminance_top = 0;   // the legend's top
  double lit_fraction = 0;    // of pixels showing a front face brighter than 1% of display white
  std::string colour_file, luminance_file;
};

// False colour of luminance (B / pi) over the view, linear from 0 to a round top at or
// above the 98th percentile of the lit, non-emitting pixels (brighter ones show the top
// colour), with a legend bar and the view's name and description printed above.
rad::Image luminance_picture(const rad::RenderedView& rendered, const rad::View& view, bool photometric, double* top);

// Before any work: the declared views' files, the automatic ones' directory (their
// names come from the model) and the HTML report (when not empty) can be written.
void check_view_outputs(const std::string& prefix, const std::vector<rad::View>& declared, bool automatic,
                        const std::string& html);

// Renders every view and writes its two pictures beside PREFIX.
std::vector<ViewPictures> write_views(const std::string& prefix, const rad::LitScene& scene,
                                      const std::vector<rad::View>& views, double exposure);

nlohmann::json views_json(const std::vector<ViewPictures>& views);

// The cameras a glTF file carries for a viewer: `start` first (where the viewer opens),
// then the other perspective views (plans, being orthographic, are left out).
std::vector<Viewpoint> viewpoints(const rad::View& start, const std::vector<rad::View>& others);

}  // namespace dynrad::report

// What the JSON result and the HTML report of a dock both write: a pose's score and its terms,
// and the options that change the poses.
#pragma once

#include "surfcomp/docking/dock.hpp"

namespace surfcomp::report::detail {

/// {score, contact, clash, esp, lp, deepest, intersects} of `pose`, in that order for an ordered
/// JSON type.
template <class Json>
Json dock_pose_terms(const docking::DockPose& pose) {
  return Json{{"score", pose.score.score},    {"contact", pose.score.contact},
              {"clash", pose.score.clash},    {"esp", pose.score.esp},
              {"lp", pose.score.lp},          {"deepest", pose.score.deepest},
              {"intersects", pose.intersects}};
}

/// The options that change a dock's poses, by their option names, in that order for an ordered
/// JSON type.
template <class Json>
Json dock_parameters(const docking::DockOptions& options) {
  const docking::ComplementarityOptions& c = options.complementarity;
  return Json{{"contact_gap", c.contact_gap},
              {"contact_width", c.contact_width},
              {"clash_tolerance", c.clash_tolerance},
              {"metal_allowance", c.metal_allowance},
              {"clash_weight", c.clash_weight},
              {"esp_weight", c.esp_weight},
              {"lp_weight", c.lp_weight},
              {"site_weight", c.site_weight},
              {"grid_spacing", c.spacing},
              {"grid_margin", c.margin},
              {"sample_spacing", c.sample_spacing},
              {"local_only", options.local_only},
              {"score_only", options.score_only},
              {"conformers", options.conformers},
              {"conformer_seed", options.conformer_seed},
              {"refine_top", options.refine_top},
              {"search_chains", options.search.chains},
              {"search_steps", options.search.steps},
              {"search_temperature", options.search.temperature},
              {"search_sample_spacing", options.search.sample_spacing},
              {"search_min_gain", options.search.min_gain}};
}

}  // namespace surfcomp::report::detail

// A dock pose's score and its terms, as the JSON result and the HTML report both write them.
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

}  // namespace surfcomp::report::detail

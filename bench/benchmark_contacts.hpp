// The contacts of the contact rows (inverse_dynamics_with_contacts, forward_dynamics_with_contacts):
// a floating talos on its two soles (surface), a floating solo12 on its four feet (point); other
// models have none and sit those rows out.
#pragma once

#include <string>
#include <vector>

#include "spatial_dynamics/model/contact_set.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace bench {

/// The benchmark's contact set for a model (empty when it has none).
template <class S>
spatial_dynamics::ContactSet<S> benchmark_contacts(const spatial_dynamics::Model<S>& model) {
  if (!model.floating_base) return {};
  const std::vector<std::string> soles = {"left_sole_link", "right_sole_link"};
  const std::vector<std::string> feet = {"FL_FOOT", "FR_FOOT", "HL_FOOT", "HR_FOOT"};
  auto has_all = [&](const std::vector<std::string>& frames) {
    for (const std::string& f : frames)
      if (!model.hasFrame(f)) return false;
    return true;
  };
  if (has_all(soles)) return spatial_dynamics::ContactSet<S>(model, soles, {"surface", "surface"});
  if (has_all(feet)) return spatial_dynamics::ContactSet<S>(model, feet, {"point", "point", "point", "point"});
  return {};
}

}  // namespace bench

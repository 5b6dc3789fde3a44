// Contacts in the services (doc/node.md, "Floating base"): which contacts a call uses (the node's,
// the request's own, or none), and the answer's contact wrenches, base wrench and contact
// violations from the library's λ (algorithms/contact_dynamics.hpp).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <geometry_msgs/Wrench.h>
#include <geometry_msgs/WrenchStamped.h>

#include "spatial_dynamics/model/contact_set.hpp"
#include "spatial_dynamics/ros/served_model.hpp"
#include "spatial_dynamics/ros/workspace_pool.hpp"

namespace spatial_dynamics {

/// The contacts of a call on `model` (the scene's, or its rigid-body twin, which has the same
/// frames): none with `ignore`; the request's own (built into ws.request_contacts, every bad entry
/// named) when it gives any of frames, kinds and frictions; else the scene's (refused with the
/// scene's contacts_error when they do not resolve on its model).
const ContactSet<double>& contacts_for_call(const ServedScene& scene, Workspace& ws, const Model<double>& model,
                                            const std::vector<std::string>& frames,
                                            const std::vector<std::string>& kinds,
                                            const std::vector<double>& frictions, bool ignore);

/// (n ; f) as a message.
geometry_msgs::Wrench to_wrench_message(const Eigen::Matrix<double, 6, 1>& wrench);

/// Each contact's wrench from the stacked λ, in its frame about its origin (a point contact's
/// moment zero), stamped `stamp`.
void contact_wrench_messages(const Model<double>& model, const ContactSet<double>& contacts,
                             const Eigen::VectorXd& lambda, const ros::Time& stamp,
                             std::vector<geometry_msgs::WrenchStamped>& out);

/// The contacts whose wrench pulls (normal force f_z < 0) or, with a friction coefficient μ > 0,
/// leaves its friction cone (|f_xy| > μ f_z), named in `violations` and described in `message`.
void check_contact_wrenches(const Model<double>& model, const ContactSet<double>& contacts,
                            const Eigen::VectorXd& lambda, std::vector<std::string>& violations, std::string& message);

}  // namespace spatial_dynamics

#include "spatial_dynamics/ros/contact_answers.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace spatial_dynamics {
namespace {

/// Contact k's (n ; f) from the stacked λ (a point contact has f only).
Eigen::Matrix<double, 6, 1> contact_wrench(const Contact<double>& contact, const Eigen::VectorXd& lambda) {
  Eigen::Matrix<double, 6, 1> w = Eigen::Matrix<double, 6, 1>::Zero();
  if (contact.kind == ContactKind::Point)
    w.tail<3>() = lambda.segment<3>(contact.row);
  else
    w = lambda.segment<6>(contact.row);
  return w;
}

}  // namespace

const ContactSet<double>& contacts_for_call(const ServedScene& scene, Workspace& ws, const Model<double>& model,
                                            const std::vector<std::string>& frames,
                                            const std::vector<std::string>& kinds,
                                            const std::vector<double>& frictions, bool ignore) {
  static const ContactSet<double> none;
  if (ignore) return none;
  if (!frames.empty() || !kinds.empty() || !frictions.empty()) {
    try {
      ws.request_contacts = ContactSet<double>(model, frames, kinds, frictions);
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string("contact_frames: ") + e.what());
    }
    return ws.request_contacts;
  }
  if (!scene.contacts_error.empty()) throw std::runtime_error(scene.contacts_error + " (ignore_contacts, or give contact_frames)");
  return scene.contacts;
}

geometry_msgs::Wrench to_wrench_message(const Eigen::Matrix<double, 6, 1>& wrench) {
  geometry_msgs::Wrench m;
  m.torque.x = wrench[0];
  m.torque.y = wrench[1];
  m.torque.z = wrench[2];
  m.force.x = wrench[3];
  m.force.y = wrench[4];
  m.force.z = wrench[5];
  return m;
}

void contact_wrench_messages(const Model<double>& model, const ContactSet<double>& contacts,
                             const Eigen::VectorXd& lambda, const ros::Time& stamp,
                             std::vector<geometry_msgs::WrenchStamped>& out) {
  out.resize(contacts.size());
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact<double>& contact = contacts.contacts[k];
    out[k].header.stamp = stamp;
    out[k].header.frame_id = model.frames[contact.frame].name;
    out[k].wrench = to_wrench_message(contact_wrench(contact, lambda));
  }
}

void check_contact_wrenches(const Model<double>& model, const ContactSet<double>& contacts,
                            const Eigen::VectorXd& lambda, std::vector<std::string>& violations, std::string& message) {
  violations.clear();
  for (const Contact<double>& contact : contacts.contacts) {
    const Eigen::Vector3d f = contact_wrench(contact, lambda).tail<3>();
    const double tangential = f.head<2>().norm();
    const std::string& name = model.frames[contact.frame].name;
    std::ostringstream why;
    if (f.z() < 0.0)
      why << "contact '" << name << "' pulls (normal force " << f.z() << " N)";
    else if (contact.friction > 0.0 && tangential > contact.friction * f.z())
      why << "contact '" << name << "' leaves its friction cone (tangential force " << tangential << " N > mu "
          << contact.friction << " x normal force " << f.z() << " N)";
    else
      continue;
    violations.push_back(name);
    if (!message.empty()) message += "; ";
    message += why.str();
  }
}

}  // namespace spatial_dynamics

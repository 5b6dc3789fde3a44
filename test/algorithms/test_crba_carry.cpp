// The two ways crba carries a column F = Iᶜ_i S_i to the ancestors — one force transform per
// ancestor, or once into base coordinates (Data::crba_in_base_coordinates, chosen for deep trees)
// — each against the float128 mass matrix, on every shared robot with fixed and floating base, a
// 200-body random chain, and a mobile manipulator with a prismatic torso and coupled mimic fingers.
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>

#include "spatial_dynamics/reduction/couple_mimic_joints.hpp"
#include "spatial_dynamics/reference/high_precision.hpp"
#include "spatial_dynamics/synthetic/random_robot.hpp"
#include "synthetic_robots.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;

namespace {

struct Case {
  std::string name;
  sd::Model<double> model;
  double bound;  // norm-wise relative error
};

std::vector<Case> cases() {
  // The bound for the robots (peers reach 3e-16 to 1e-15); on the long chain rounding
  // grows with the depth d: 4e-15 · d / 10.
  std::vector<Case> out;
  for (const std::string& file : sd_test::robot_files()) {
    for (const bool floating : {false, true}) {
      sd::ModelBuildOptions options;
      options.floating_base = floating;
      out.push_back({file + (floating ? " (floating)" : ""), sd::build_model_from_urdf_file(sd_test::robot_path(file), options), 4e-15});
    }
  }
  std::mt19937 rng(11);
  out.push_back({"random chain, 200 bodies",
                 sd::build_model_from_urdf_string(sd::synthetic::to_urdf("chain", sd::synthetic::random_chain(200, rng))), 8e-14});
  const sd::Model<double> manipulator = sd::build_model_from_urdf_string(sd_test::mobile_manipulator_urdf());
  out.push_back({"mobile manipulator", manipulator, 4e-15});
  out.push_back({"mobile manipulator, coupled mimic joints", sd::couple_mimic_joints(manipulator), 4e-15});
  return out;
}

}  // namespace

TEST(CrbaCarry, BothWaysMatchTheHighPrecisionMassMatrix) {
  for (const Case& c : cases()) {
    const sd::Model<sd::Quad> model_quad = c.model.cast<sd::Quad>();
    sd::Data<sd::Quad> data_quad(model_quad);
    sd::Data<double> per_ancestor(c.model), in_base(c.model);
    per_ancestor.crba_in_base_coordinates = false;
    in_base.crba_in_base_coordinates = true;
    std::mt19937 rng(3);
    double worst_per_ancestor = 0, worst_in_base = 0;
    for (int s = 0; s < 30; ++s) {
      const Eigen::VectorXd q = sd_test::random_configuration(c.model, rng);
      const sd::MatrixX<sd::Quad> reference = sd::crba(model_quad, data_quad, sd::to_quad(q));
      const Eigen::MatrixXd M_per_ancestor = sd::crba(c.model, per_ancestor, q);
      const Eigen::MatrixXd M_in_base = sd::crba(c.model, in_base, q);
      EXPECT_EQ(M_in_base, M_in_base.transpose()) << c.name;
      worst_per_ancestor = std::max(worst_per_ancestor, sd::relative_error_to(M_per_ancestor, reference));
      worst_in_base = std::max(worst_in_base, sd::relative_error_to(M_in_base, reference));
    }
    std::printf("[crba carry] %-45s per ancestor %.2e  in base coordinates %.2e  (bound %.0e)\n", c.name.c_str(),
                worst_per_ancestor, worst_in_base, c.bound);
    EXPECT_LE(worst_per_ancestor, c.bound) << c.name;
    EXPECT_LE(worst_in_base, c.bound) << c.name;
  }
}

TEST(CrbaCarry, DeepTreesAreCarriedInBaseCoordinates) {
  std::mt19937 rng(11);
  const sd::Model<double> chain =
      sd::build_model_from_urdf_string(sd::synthetic::to_urdf("chain", sd::synthetic::random_chain(50, rng)));
  EXPECT_TRUE(sd::Data<double>(chain).crba_in_base_coordinates);  // 24.5 ancestors per body
  const sd::Model<double> ur5 = sd::build_model_from_urdf_file(sd_test::robot_path("ur5.urdf"));
  EXPECT_FALSE(sd::Data<double>(ur5).crba_in_base_coordinates);   // 2.5 ancestors per body
}

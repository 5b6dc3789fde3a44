// The compiled library's two builds of the double instances (simd_backend.hpp): the one this
// process runs is chosen from the CPU unless SPATIAL_DYNAMICS_SIMD forces one, a bad request is
// named, and on every bundled robot (fixed and floating base) the two builds agree to rounding
// while the portable one equals, bit for bit, the header templates compiled in this file with the
// same (portable) flags.
#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "spatial_dynamics/algorithms/aba_refined.hpp"
#include "spatial_dynamics/algorithms/rnea_batch.hpp"
#include "spatial_dynamics/compiled/backend_table.hpp"
#include "spatial_dynamics/simd_backend.hpp"
#include "test_utils.hpp"

namespace sd = spatial_dynamics;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

bool cpu_has_avx2_fma() { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"); }

std::string invalid_request_message(const char* request) {
  try {
    sd::detail::simd_backend_table(request);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(SimdBackend, ChosenFromTheCpuUnlessForced) {
  const char* forced = std::getenv("SPATIAL_DYNAMICS_SIMD");
  const std::string best = cpu_has_avx2_fma() ? "avx2_fma" : "portable";
  EXPECT_EQ(sd::simd_backend(), forced != nullptr && *forced != '\0' ? std::string(forced) : best);
  EXPECT_EQ(sd::detail::simd_backend_table(nullptr).name, best);
  EXPECT_EQ(sd::detail::simd_backend_table("").name, best);
  EXPECT_STREQ(sd::detail::simd_backend_table("portable").name, "portable");
  std::printf("[simd backend] this process: %s; the CPU's best: %s\n", sd::simd_backend(), best.c_str());
}

TEST(SimdBackend, UnknownOrUnsupportedRequestIsNamed) {
  const std::string unknown = invalid_request_message("sse9");
  EXPECT_NE(unknown.find("SPATIAL_DYNAMICS_SIMD='sse9'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("portable"), std::string::npos) << unknown;
  if (cpu_has_avx2_fma()) {
    EXPECT_STREQ(sd::detail::simd_backend_table("avx2_fma").name, "avx2_fma");
  } else {
    EXPECT_NE(invalid_request_message("avx2_fma").find("no AVX2 and FMA"), std::string::npos);
  }
}

struct Robot {
  std::string file;
  bool floating;
};

class BackendsAgree : public ::testing::TestWithParam<Robot> {};

/// Every entry point of both builds on random states, against the templates of this file.
TEST_P(BackendsAgree, OnRandomStates) {
  if (!cpu_has_avx2_fma()) GTEST_SKIP() << "this CPU has no AVX2 and FMA: only the portable build runs";
  sd::ModelBuildOptions options;
  options.floating_base = GetParam().floating;
  const sd::Model<double> model = sd::build_model_from_urdf_file(sd_test::robot_path(GetParam().file), options);
  const sd::detail::BackendTable& portable = sd::detail::simd_backend_table("portable");
  const sd::detail::BackendTable& avx2 = sd::detail::simd_backend_table("avx2_fma");
  sd::Data<double> here(model), data_portable(model), data_avx2(model);
  sd::RefinementWorkspace<double> ws_here(model), ws_portable(model), ws_avx2(model);
  sd::BatchData<double> batch_here(model), batch_portable(model), batch_avx2(model);
  const int frame = static_cast<int>(model.frames.size()) - 1;
  const sd::ContactSet<double> contacts(model, {model.frames[frame].name}, {"point"});  // the last link's origin held
  sd::ContactData<double> contacts_here(model, contacts), contacts_portable(model, contacts), contacts_avx2(model, contacts);
  std::mt19937 rng(7), force_rng(8);
  double worst = 0;  // largest relative difference between the two builds
  const auto compare = [&](const auto& from_here, const auto& from_portable, const auto& from_avx2, const char* what) {
    EXPECT_TRUE(from_portable == from_here) << what << ": the portable build differs from the templates";
    const double difference = sd_test::relative_error(from_avx2, from_portable);
    EXPECT_LE(difference, 1e-13) << what;
    worst = std::max(worst, difference);
  };
  constexpr int kStates = 12;
  MatrixXd Q(model.nq, kStates), QD(model.nv, kStates), QDD(model.nv, kStates);
  for (int k = 0; k < kStates; ++k) {
    const VectorXd q = sd_test::random_configuration(model, rng);
    const VectorXd qd = sd_test::random_vector(model.nv, rng, 2.0), qdd = sd_test::random_vector(model.nv, rng, 2.0);
    Q.col(k) = q;
    QD.col(k) = qd;
    QDD.col(k) = qdd;
    const VectorXd tau = sd::rnea<double>(model, here, q, qd, qdd);
    compare(tau, VectorXd(portable.rnea(model, data_portable, q, qd, qdd)),
            VectorXd(avx2.rnea(model, data_avx2, q, qd, qdd)), "rnea");
    compare(VectorXd(sd::gravity_torques<double>(model, here, q)),
            VectorXd(portable.gravity_torques(model, data_portable, q)),
            VectorXd(avx2.gravity_torques(model, data_avx2, q)), "gravity_torques");
    compare(VectorXd(sd::nonlinear_effects<double>(model, here, q, qd)),
            VectorXd(portable.nonlinear_effects(model, data_portable, q, qd)),
            VectorXd(avx2.nonlinear_effects(model, data_avx2, q, qd)), "nonlinear_effects");
    compare(VectorXd(sd::aba<double>(model, here, q, qd, tau)),
            VectorXd(portable.aba(model, data_portable, q, qd, tau)),
            VectorXd(avx2.aba(model, data_avx2, q, qd, tau)), "aba");
    compare(VectorXd(sd::forward_dynamics<double>(model, here, q, qd, tau)),
            VectorXd(portable.forward_dynamics(model, data_portable, q, qd, tau)),
            VectorXd(avx2.forward_dynamics(model, data_avx2, q, qd, tau)), "forward_dynamics");
    compare(VectorXd(sd::aba_refined<double, sd::DoubleDouble>(model, here, ws_here, q, qd, tau)),
            VectorXd(portable.aba_refined(model, data_portable, ws_portable, q, qd, tau, 8)),
            VectorXd(avx2.aba_refined(model, data_avx2, ws_avx2, q, qd, tau, 8)), "aba_refined");
    compare(MatrixXd(sd::crba<double>(model, here, q)), MatrixXd(portable.crba(model, data_portable, q)),
            MatrixXd(avx2.crba(model, data_avx2, q)), "crba");
    compare(MatrixXd(sd::joint_torque_regressor<double>(model, here, q, qd, qdd)),
            MatrixXd(portable.joint_torque_regressor(model, data_portable, q, qd, qdd)),
            MatrixXd(avx2.joint_torque_regressor(model, data_avx2, q, qd, qdd)), "joint_torque_regressor");
    compare(MatrixXd(sd::payload_regressor<double>(model, here, q, qd, qdd, model.frames[frame].name)),
            MatrixXd(portable.payload_regressor(model, data_portable, q, qd, qdd, model.frames[frame].name)),
            MatrixXd(avx2.payload_regressor(model, data_avx2, q, qd, qdd, model.frames[frame].name)), "payload_regressor");
    compare(MatrixXd(sd::frame_jacobian<double>(model, here, q, frame, sd::ReferenceFrame::RootAligned)),
            MatrixXd(portable.frame_jacobian(model, data_portable, q, frame, sd::ReferenceFrame::RootAligned)),
            MatrixXd(avx2.frame_jacobian(model, data_avx2, q, frame, sd::ReferenceFrame::RootAligned)),
            "frame_jacobian");
    compare(VectorXd(sd::inverse_dynamics_with_contacts<double>(model, here, contacts, contacts_here, q, qd, qdd)),
            VectorXd(portable.inverse_dynamics_with_contacts(model, data_portable, contacts, contacts_portable, q, qd, qdd)),
            VectorXd(avx2.inverse_dynamics_with_contacts(model, data_avx2, contacts, contacts_avx2, q, qd, qdd)),
            "inverse_dynamics_with_contacts");
    compare(VectorXd(contacts_here.lambda), VectorXd(contacts_portable.lambda), VectorXd(contacts_avx2.lambda),
            "inverse_dynamics_with_contacts: λ");
    std::vector<sd::ForceVector<double>> f_ext(model.nbodies(), sd::ForceVector<double>::Zero());
    for (int i = 1; i < model.nbodies(); ++i)  // (their own generator: the states stay those of rng)
      f_ext[i] = sd::ForceVector<double>(sd::Vector6<double>(sd_test::random_vector(6, force_rng)));
    compare(VectorXd(sd::inverse_dynamics_with_contacts<double>(model, here, contacts, contacts_here, q, qd, qdd, f_ext)),
            VectorXd(portable.inverse_dynamics_with_contacts_f_ext(model, data_portable, contacts, contacts_portable, q, qd, qdd, f_ext)),
            VectorXd(avx2.inverse_dynamics_with_contacts_f_ext(model, data_avx2, contacts, contacts_avx2, q, qd, qdd, f_ext)),
            "inverse_dynamics_with_contacts with f_ext");
    // (q̈ ; λ) together: the contact can hold every joint (the double pendulum's), and q̈ is then zero but for rounding.
    const auto constrained = [&](const sd::ContactData<double>& cd) {
      VectorXd x(cd.qdd.size() + cd.lambda.size());
      x << cd.qdd, cd.lambda;
      return x;
    };
    sd::forward_dynamics_with_contacts<double>(model, here, contacts, contacts_here, q, qd, tau);
    portable.forward_dynamics_with_contacts(model, data_portable, contacts, contacts_portable, q, qd, tau);
    avx2.forward_dynamics_with_contacts(model, data_avx2, contacts, contacts_avx2, q, qd, tau);
    compare(constrained(contacts_here), constrained(contacts_portable), constrained(contacts_avx2),
            "forward_dynamics_with_contacts");
    sd::forward_dynamics_with_contacts<double>(model, here, contacts, contacts_here, q, qd, tau, f_ext);
    portable.forward_dynamics_with_contacts_f_ext(model, data_portable, contacts, contacts_portable, q, qd, tau, f_ext);
    avx2.forward_dynamics_with_contacts_f_ext(model, data_avx2, contacts, contacts_avx2, q, qd, tau, f_ext);
    compare(constrained(contacts_here), constrained(contacts_portable), constrained(contacts_avx2),
            "forward_dynamics_with_contacts with f_ext");
    compare(MatrixXd(sd::contact_jacobian<double>(model, here, contacts, contacts_here, q, qd)),
            MatrixXd(portable.contact_jacobian(model, data_portable, contacts, contacts_portable, q, qd)),
            MatrixXd(avx2.contact_jacobian(model, data_avx2, contacts, contacts_avx2, q, qd)), "contact_jacobian");
    compare(MatrixXd(sd::centroidal_momentum_matrix<double>(model, here, q)),
            MatrixXd(portable.centroidal_momentum_matrix(model, data_portable, q)),
            MatrixXd(avx2.centroidal_momentum_matrix(model, data_avx2, q)), "centroidal_momentum_matrix");
    compare(Eigen::Vector3d(sd::center_of_mass<double>(model, here, q)),
            Eigen::Vector3d(portable.center_of_mass(model, data_portable, q)),
            Eigen::Vector3d(avx2.center_of_mass(model, data_avx2, q)), "center_of_mass");
    // The library's own entry points run one of the two builds.
    const VectorXd chosen = sd::rnea(model, data_portable, q, qd, qdd);
    EXPECT_TRUE(chosen == VectorXd(std::string(sd::simd_backend()) == "portable"
                                       ? portable.rnea(model, data_avx2, q, qd, qdd)
                                       : avx2.rnea(model, data_avx2, q, qd, qdd)));
  }
  MatrixXd T_here(model.nv, kStates), T_portable(model.nv, kStates), T_avx2(model.nv, kStates);
  sd::rnea_batch<double, sd::kDefaultBatchLanes<double>>(model, batch_here, Q, QD, QDD, T_here);
  portable.rnea_batch(model, batch_portable, Q, QD, QDD, T_portable);
  avx2.rnea_batch(model, batch_avx2, Q, QD, QDD, T_avx2);
  compare(T_here, T_portable, T_avx2, "rnea_batch");
  std::printf("[simd backend] %s%s: avx2_fma against portable, largest relative difference %.2g\n",
              GetParam().file.c_str(), GetParam().floating ? " (floating)" : "", worst);
}

INSTANTIATE_TEST_SUITE_P(BundledRobots, BackendsAgree,
                         ::testing::Values(Robot{"double_pendulum.urdf", false}, Robot{"panda.urdf", false},
                                           Robot{"ur5.urdf", false}, Robot{"solo12.urdf", false},
                                           Robot{"talos.urdf", false}, Robot{"solo12.urdf", true},
                                           Robot{"talos.urdf", true}),
                         [](const ::testing::TestParamInfo<Robot>& info) {
                           return info.param.file.substr(0, info.param.file.find('.')) +
                                  (info.param.floating ? "_floating" : "");
                         });

}  // namespace

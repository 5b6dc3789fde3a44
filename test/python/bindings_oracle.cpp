// The C++ side of test_dynamics_bindings.py: the library's results for states read from stdin,
// printed as hex floats ("%a") so that the test compares the Python bindings' bit for bit.
//   bindings_oracle URDF FLOATING(0|1) FRAME [--time CALLS]
// stdin: the number of states, then per state q (nq), qd, qdd, tau (nv each) and a wrench
// (torque; force) on FRAME, in that frame, as decimal or hex floats. stdout, per state, one line
// per result: its name, then its entries (matrices row by row). With --time, also the median time
// of CALLS calls of rnea on the first state: "rnea_median_us X".
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "spatial_dynamics/algorithms.hpp"
#include "spatial_dynamics/algorithms/aba_refined.hpp"
#include "spatial_dynamics/urdf/model_builder.hpp"

using namespace spatial_dynamics;

namespace {

Eigen::VectorXd read_vector(int n) {
  Eigen::VectorXd v(n);
  std::string token;
  for (int k = 0; k < n; ++k) {
    if (!(std::cin >> token)) {
      std::fprintf(stderr, "bindings_oracle: input ended early\n");
      std::exit(2);
    }
    v[k] = std::strtod(token.c_str(), nullptr);
  }
  return v;
}

template <class Derived>
void print(const char* name, const Eigen::MatrixBase<Derived>& m) {
  std::printf("%s", name);
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) std::printf(" %a", m(r, c));
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: bindings_oracle URDF FLOATING(0|1) FRAME [--time CALLS]\n");
    return 2;
  }
  ModelBuildOptions options;
  options.floating_base = std::string(argv[2]) == "1";
  const Model<double> model = build_model_from_urdf_file(argv[1], options);
  const int frame = model.frameIndex(argv[3]);
  const int timed_calls = argc >= 6 && std::string(argv[4]) == "--time" ? std::atoi(argv[5]) : 0;
  Data<double> data(model);
  RefinementWorkspace<double> refinement(model);
  std::vector<ForceVector<double>> f_ext(model.nbodies(), ForceVector<double>::Zero());
  int states = 0;
  std::cin >> states;
  Eigen::VectorXd first_q, first_qd, first_qdd;
  for (int s = 0; s < states; ++s) {
    const Eigen::VectorXd q = read_vector(model.nq), qd = read_vector(model.nv), qdd = read_vector(model.nv),
                          tau = read_vector(model.nv), wrench = read_vector(6);
    if (s == 0) first_q = q, first_qd = qd, first_qdd = qdd;
    print("rnea", rnea(model, data, q, qd, qdd));
    std::fill(f_ext.begin(), f_ext.end(), ForceVector<double>::Zero());
    const Frame<double>& F = model.frames[frame];
    f_ext[F.body] += F.X_frame_body.applyInverse(ForceVector<double>(wrench));  // as the node maps a wrench
    print("rnea_ext", rnea(model, data, q, qd, qdd, f_ext));
    print("aba", aba(model, data, q, qd, tau));
    print("aba_refined", aba_refined(model, data, refinement, q, qd, tau));
    print("crba", crba(model, data, q));
    print("gravity_torques", gravity_torques(model, data, q));
    print("nonlinear_effects", nonlinear_effects(model, data, q, qd));
    print("jacobian_root_aligned", frame_jacobian(model, data, q, frame, ReferenceFrame::RootAligned));
    print("jacobian_local", frame_jacobian(model, data, q, frame, ReferenceFrame::Local));
  }
  if (timed_calls > 0 && states > 0) {
    std::vector<double> ns(timed_calls);
    for (int k = 0; k < timed_calls; ++k) {
      const auto start = std::chrono::steady_clock::now();
      rnea(model, data, first_q, first_qd, first_qdd);
      ns[k] = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
    }
    std::nth_element(ns.begin(), ns.begin() + timed_calls / 2, ns.end());
    std::printf("rnea_median_us %.4f\n", ns[timed_calls / 2] * 1e-3);
  }
  return 0;
}

// MuJoCo 2.2.2 (Debian's libmujoco) through its C API, loading the URDF with mj_loadXML. For a
// floating base the URDF gets a "world" link and a floating joint (MuJoCo's free joint). Contacts,
// constraints (limits, friction loss) and passive forces are disabled and damping and armature
// zeroed, so that MuJoCo computes the same rigid-body dynamics as the others. RNEA: mj_inverse;
// forward dynamics: mj_forward (composite rigid body + sparse LDLᵀ); M: mj_kinematics, mj_comPos,
// mj_crb (mj_fullM outside the timing); g: mj_rne at q̇ = 0; FK: mj_kinematics.
// The free joint's coordinates differ from ours: qpos (p, w x y z), q̇ = (ṗ in the world; ω in the
// body), so its inputs and results are converted (a rotation: a rounding of ε) outside the timing.
#pragma once

#include <memory>
#include <string>

#include "benchmark_types.hpp"
#include "spatial_dynamics/model/model.hpp"

namespace bench {

/// `urdf_path`: a URDF that MuJoCo can read (no meshes); `why` says why not when it returns null.
std::unique_ptr<Adapter> make_mujoco_adapter(const spatial_dynamics::Model<double>& model, const std::string& urdf_path,
                                             std::string& why);

}  // namespace bench

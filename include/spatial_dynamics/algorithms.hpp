// Every algorithm in one include.
#pragma once

#include "spatial_dynamics/algorithms/aba.hpp"
#include "spatial_dynamics/algorithms/actuator_dynamics.hpp"
#include "spatial_dynamics/algorithms/centroidal.hpp"
#include "spatial_dynamics/algorithms/contact_dynamics.hpp"
#include "spatial_dynamics/algorithms/coriolis.hpp"
#include "spatial_dynamics/algorithms/crba.hpp"
#include "spatial_dynamics/algorithms/energy.hpp"
#include "spatial_dynamics/algorithms/forward_dynamics.hpp"
#include "spatial_dynamics/algorithms/jacobian.hpp"
#include "spatial_dynamics/algorithms/kinematics.hpp"
#include "spatial_dynamics/algorithms/regressor.hpp"
#include "spatial_dynamics/algorithms/rnea.hpp"

// The spatial algebra of Featherstone 2010 ("A Beginner's Guide to 6-D Vectors") in one include.
#pragma once

#include "spatial_dynamics/spatial/articulated_inertia.hpp"
#include "spatial_dynamics/spatial/cross.hpp"
#include "spatial_dynamics/spatial/eigen_types.hpp"
#include "spatial_dynamics/spatial/force_vector.hpp"
#include "spatial_dynamics/spatial/motion_vector.hpp"
#include "spatial_dynamics/spatial/plucker_transform.hpp"
#include "spatial_dynamics/spatial/rigid_inertia.hpp"

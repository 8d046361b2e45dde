// Small vector types shared by every solver concept (Eigen, fixed size, SI units).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace asperity {
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;
}  // namespace asperity

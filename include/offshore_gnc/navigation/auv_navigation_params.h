#pragma once
// The AuvNavigation nodelet's own parameters around the filter (config/navigation/auv_<model>.yaml; the filter's
// are AuvNavigatorConfig's): its output rate, the velocity source, how a USBL fix's covariance is set, and the
// pressure -> depth conversion (geo::PressureDepth's). The nodelet and the ROS-free mission read them through this
// table.
#include <Eigen/Core>
#include <string>

#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/geo/pressure_depth.h"

namespace offshore_gnc {
namespace navigation {

struct AuvNavigationParams {
  double rate = 20.0;              // /auv/odom [Hz]: the simulator's INS estimate's rate (perception waits for TF at it)
  bool use_dvl = true;             // Girona500: the DVL; aColor (none): the commands' velocity (Control)
  double fix_min_sigma = 1.0;      // [m] a fix's sigma floor: the USV GPS's error and its pose at the fix time
  double fix_angle_sigma = 0.01;   // [rad] the fix's angle error: sigma = max(fix_min_sigma, range * this)
  geo::PressureDepth pressure;     // water_density, surface_pressure
  std::string base_frame = "auv/base_link";  // the nodelet's TF child frame
  static const ParamTable<AuvNavigationParams>& table();
  // A fix at this slant range: isotropic NED covariance.
  Eigen::Matrix3d fixCovariance(double range) const;
  double depthOf(double pressure_pa) const { return pressure.depthOf(pressure_pa); }  // [m]
};

}  // namespace navigation
}  // namespace offshore_gnc

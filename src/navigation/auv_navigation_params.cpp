#include "offshore_gnc/navigation/auv_navigation_params.h"

#include <algorithm>

namespace offshore_gnc {
namespace navigation {

const ParamTable<AuvNavigationParams>& AuvNavigationParams::table() {
  using P = AuvNavigationParams;
  static const ParamTable<P> t = ParamTable<P>()
      .number("rate", &P::rate, 0.1, 100.0, "Hz", "/auv/odom and its TF")
      .flag("use_dvl", &P::use_dvl, "velocity over ground from /auv/dvl; false: the commands' velocity (no DVL)")
      .number("fix_min_sigma", &P::fix_min_sigma, 0.001, 100.0, "m",
              "a USBL fix's position sigma at least this (the USV GPS's error and its pose at the fix time)")
      .number("fix_angle_sigma", &P::fix_angle_sigma, 0.0, 0.5, "rad", "and at least the slant range times this")
      .nest("", &P::pressure, geo::PressureDepth::table())
      .string("base_frame", &P::base_frame, "the AUV's body frame: /auv/odom's child frame, a DVL's expected frame");
  return t;
}

Eigen::Matrix3d AuvNavigationParams::fixCovariance(double range) const {
  const double sigma = std::max(fix_min_sigma, range * fix_angle_sigma);
  return Eigen::Matrix3d::Identity() * sigma * sigma;
}

}  // namespace navigation
}  // namespace offshore_gnc

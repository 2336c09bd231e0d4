#pragma once
// Depth from a pressure sensor: (p - surface_pressure) / (water_density g). One table for the conversion the AUV
// navigation and the USBL node (the AUV's depth against a fix's) both make, so the two never use different water.
#include "offshore_gnc/common/param_table.h"

namespace offshore_gnc {
namespace geo {

struct PressureDepth {
  double water_density = 1000.0;       // [kg/m^3] fresh water; 1025 at sea
  double surface_pressure = 101325.0;  // [Pa]
  double depthOf(double pressure_pa) const {  // [m]
    constexpr double kGravity = 9.80665;
    return (pressure_pa - surface_pressure) / (water_density * kGravity);
  }
  static const ParamTable<PressureDepth>& table() {
    using P = PressureDepth;
    static const ParamTable<P> t = ParamTable<P>()
        .number("water_density", &P::water_density, 990, 1050, "kg/m^3", "depth = (p - surface_pressure) / (density g)")
        .number("surface_pressure", &P::surface_pressure, 80000, 120000, "Pa", "the atmosphere over the water");
    return t;
  }
};

}  // namespace geo
}  // namespace offshore_gnc

// Throughput of the geodesy used on every GPS fix and USBL fix: LocalNed (GeographicLib::LocalCartesian)
// forward + reverse, against the flat-earth approximation a user might write instead (same run).
#include <chrono>
#include <cmath>
#include <cstdio>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/geo/geo.h"

using namespace offshore_gnc;

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 200000;
  geo::LocalNed f(geo::kPyhajarviOrigin);
  double sink = 0.0, max_flat_err = 0.0;
  auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < n; ++i) {
    geo::LatLonAlt p{geo::kPyhajarviOrigin.lat_deg + 1e-5 * (i % 1000), geo::kPyhajarviOrigin.lon_deg + 1e-5 * (i % 777), 0};
    Eigen::Vector3d ned = f.toNed(p);
    sink += f.toGeodetic(ned).lat_deg;
  }
  auto t1 = std::chrono::steady_clock::now();
  const double R = 6371000.0;
  for (int i = 0; i < n; ++i) {
    const double dlat = 1e-5 * (i % 1000), dlon = 1e-5 * (i % 777);
    const double x = R * deg2rad(dlat), y = R * std::cos(deg2rad(geo::kPyhajarviOrigin.lat_deg)) * deg2rad(dlon);
    sink += x + y;
    if (i % 1000 == 999) {
      Eigen::Vector3d ned = f.toNed({geo::kPyhajarviOrigin.lat_deg + dlat, geo::kPyhajarviOrigin.lon_deg + dlon, 0});
      max_flat_err = std::max(max_flat_err, std::hypot(ned.x() - x, ned.y() - y));
    }
  }
  auto t2 = std::chrono::steady_clock::now();
  const double us_geo = std::chrono::duration<double, std::micro>(t1 - t0).count() / n;
  const double us_flat = std::chrono::duration<double, std::micro>(t2 - t1).count() / n;
  std::printf("LocalNed round trip: %.3f us; flat-earth forward: %.4f us; flat-earth error at ~1 km: %.2f m (%g)\n",
              us_geo, us_flat, max_flat_err, sink > 0 ? 0.0 : 1.0);
  std::printf("{\"geo_roundtrip_us\": %.4f, \"flat_forward_us\": %.5f, \"flat_error_m\": %.3f, \"n\": %d}\n", us_geo,
              us_flat, max_flat_err, n);
  return 0;
}

// relay_bench: the two ends of bench/relay.sh. `pub` publishes sensor_msgs/PointCloud2 of a given size with
// the wall-clock send time in header.stamp; `sub` receives them (on the same master or through the relay on
// another) and prints one JSON line: latency percentiles, throughput, the wall time of the first message.
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {
double arg(int argc, char** argv, const char* name, double def) {
  for (int i = 1; i + 1 < argc; ++i)
    if (!std::strcmp(argv[i], name)) return std::atof(argv[i + 1]);
  return def;
}
std::string sarg(int argc, char** argv, const char* name, const char* def) {
  for (int i = 1; i + 1 < argc; ++i)
    if (!std::strcmp(argv[i], name)) return argv[i + 1];
  return def;
}
double pct(std::vector<double> v, double p) {
  if (v.empty()) return -1;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * (v.size() - 1) + 0.5))];
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || (std::strcmp(argv[1], "pub") && std::strcmp(argv[1], "sub"))) {
    std::fprintf(stderr, "usage: relay_bench pub --topic T --size BYTES --count N --rate HZ --subs K [--warmup W] [--settle S]\n"
                         "       relay_bench sub --topic T --count N --timeout S [--warmup W]  (W first messages: not in the stats)\n");
    return 2;
  }
  const bool pub_mode = !std::strcmp(argv[1], "pub");
  ros::init(argc, argv, pub_mode ? "bench_pub" : "bench_sub", ros::init_options::AnonymousName);
  ros::NodeHandle nh;
  const std::string topic = sarg(argc, argv, "--topic", "/bench/data");
  const int count = static_cast<int>(arg(argc, argv, "--count", 1000));
  if (pub_mode) {
    const auto size = static_cast<std::size_t>(arg(argc, argv, "--size", 100));
    const double rate = arg(argc, argv, "--rate", 100);
    const int subs = static_cast<int>(arg(argc, argv, "--subs", 1));
    ros::Publisher pub = nh.advertise<sensor_msgs::PointCloud2>(topic, 1000);
    const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(30);
    while (static_cast<int>(pub.getNumSubscribers()) < subs && ros::WallTime::now() < give_up && ros::ok())
      ros::WallDuration(0.01).sleep();
    const double settle = arg(argc, argv, "--settle", 0.2);  // after the subscribers connected [s]
    if (settle > 0) ros::WallDuration(settle).sleep();
    sensor_msgs::PointCloud2 m;
    m.height = 1;
    m.point_step = 1;
    m.width = static_cast<std::uint32_t>(size);
    m.row_step = m.width;
    m.data.assign(size, 0x5a);
    const int warmup = static_cast<int>(arg(argc, argv, "--warmup", 0));
    ros::WallRate r(rate > 0 ? rate : 1e6);
    for (int i = 0; i < count && ros::ok(); ++i) {
      if (i == warmup && warmup > 0) ros::WallDuration(1.0).sleep();  // connections settled before measuring
      const ros::WallTime now = ros::WallTime::now();
      m.header.seq = static_cast<std::uint32_t>(i);
      m.header.stamp = ros::Time(now.sec, now.nsec);
      pub.publish(m);
      if (rate > 0) r.sleep();
    }
    ros::WallDuration(1.0).sleep();
    return 0;
  }
  const double timeout = arg(argc, argv, "--timeout", 30);
  const int warmup = static_cast<int>(arg(argc, argv, "--warmup", 0));
  std::size_t received = 0;
  std::vector<double> lat;
  lat.reserve(static_cast<std::size_t>(count));
  double first = 0, t_first = 0, t_last = 0, bytes = 0;
  ros::Subscriber sub = nh.subscribe<sensor_msgs::PointCloud2>(
      topic, 1000,
      [&](const sensor_msgs::PointCloud2::ConstPtr& m) {
        const double now = ros::WallTime::now().toSec();
        if (received == 0) first = now;
        ++received;
        if (static_cast<int>(m->header.seq) < warmup) return;  // warm-up: neither latency nor throughput
        if (lat.empty()) t_first = now;
        t_last = now;
        bytes += static_cast<double>(m->data.size());
        lat.push_back((now - m->header.stamp.toSec()) * 1e3);
      },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(timeout);
  while (ros::ok() && static_cast<int>(received) < count && ros::WallTime::now() < give_up) {
    ros::spinOnce();
    ros::WallDuration(0.0002).sleep();
  }
  // Throughput from the second message on: the first one's time includes connection set-up.
  const double span = t_last - t_first;
  const double mbps = span > 0 && lat.size() > 1 ? bytes * (1.0 - 1.0 / lat.size()) / span / 1e6 : 0.0;
  std::printf("{\"received\": %zu, \"p50_ms\": %.4f, \"p99_ms\": %.4f, \"MBps\": %.2f, \"first_wall\": %.6f}\n",
              received, pct(lat, 0.5), pct(lat, 0.99), mbps, first);
  return 0;
}

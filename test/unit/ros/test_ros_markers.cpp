// NamespaceMarkers: one publisher's markers on a shared topic are replaced without DELETEALL (which Debian's
// rviz applies to every namespace of the display).
#include <gtest/gtest.h>

#include "offshore_gnc/ros/markers.h"

namespace {
using visualization_msgs::Marker;

std::vector<Marker> cubes(int n) { return std::vector<Marker>(n, Marker()); }

TEST(NamespaceMarkers, ReplacesOwnIdsAndDeletesOnlyStaleOnes) {
  offshore_gnc::ros_util::NamespaceMarkers m("sbb");
  std_msgs::Header h;
  h.frame_id = "map_ned";
  auto a = m.replace(cubes(3), h);
  ASSERT_EQ(a.markers.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(a.markers[i].ns, "sbb");
    EXPECT_EQ(a.markers[i].id, i);
    EXPECT_EQ(a.markers[i].action, Marker::ADD);
    EXPECT_EQ(a.markers[i].header.frame_id, "map_ned");
    EXPECT_EQ(a.markers[i].pose.orientation.w, 1.0);  // a zero quaternion makes rviz reject the marker
  }
  a = m.replace(cubes(1), h);  // two fewer: ids 1 and 2 deleted, nothing else
  ASSERT_EQ(a.markers.size(), 3u);
  EXPECT_EQ(a.markers[0].action, Marker::ADD);
  EXPECT_EQ(a.markers[1].action, Marker::DELETE);
  EXPECT_EQ(a.markers[1].id, 1);
  EXPECT_EQ(a.markers[2].action, Marker::DELETE);
  EXPECT_EQ(a.markers[2].id, 2);
  a = m.replace({}, h);  // none left: one DELETE, never a DELETEALL
  ASSERT_EQ(a.markers.size(), 1u);
  EXPECT_EQ(a.markers[0].action, Marker::DELETE);
  EXPECT_EQ(a.markers[0].ns, "sbb");
  a = m.replace({}, h);
  EXPECT_TRUE(a.markers.empty());
  for (const auto& mk : m.replace(cubes(2), h).markers) EXPECT_NE(mk.action, Marker::DELETEALL);
}

TEST(NamespaceMarkers, KeepsAGivenOrientation) {
  offshore_gnc::ros_util::NamespaceMarkers m("x");
  Marker k;
  k.pose.orientation.z = 1.0;
  k.pose.orientation.w = 0.0;
  const auto a = m.replace({k}, std_msgs::Header());
  EXPECT_EQ(a.markers[0].pose.orientation.z, 1.0);
  EXPECT_EQ(a.markers[0].pose.orientation.w, 0.0);
}
}  // namespace

#!/usr/bin/python3
"""Drives the perception nodelets with generated frames (ray-cast buoys, target, tank walls) from moving
vehicles and checks the published targets and wall path against the ground truth; that the wall detection takes
the sweeps the sonar targets assemble (never the beams) and plans from a sweep cloud alone; then feeds bad input and
checks the diagnostics counters. All subscribers are created up front (see the rostest pitfall in the notes)."""
import math
import struct
import threading
import time
import unittest

import numpy as np
import rosgraph
import rospy
import rostest
import tf2_ros
from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import Path
from sensor_msgs.msg import Image, PointCloud2, PointField
from visualization_msgs.msg import MarkerArray

from offshore_gnc.msg import SonarBeam, TargetArray, Track, TrackArray

# Ground truth, NED (x north, y east).
BUOYS = [(50.0, 30.0, 0.5), (35.0, -5.0, 0.8)]          # USV scene: (N, E, radius)
SONAR_TARGET = (8.0, 6.0, 0.6)                          # AUV scene
TANK = [((-10.0, -12.0), (20.0, -12.0)), ((20.0, -12.0), (20.0, 12.0)),
        ((20.0, 12.0), (-10.0, 12.0)), ((-10.0, 12.0), (-10.0, -12.0))]   # 30 x 24 m tank walls (NED)
WALL_DISTANCE = 2.0
BEAM_COUNTERS = ("empty_beam", "bad_bearing", "head_not_ready")   # what only a nodelet fed the beams counts


def quat_yaw(yaw):
    return (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))


def cast_circles(ox, oy, ang, circles):
    """Ray (ox, oy) + t (cos ang, sin ang) against circles [(x, y, r)]: nearest t or inf (any 2-D frame)."""
    best = math.inf
    dx, dy = math.cos(ang), math.sin(ang)
    for cx, cy, r in circles:
        px, py = cx - ox, cy - oy
        b = dx * px + dy * py
        disc = b * b - (px * px + py * py - r * r)
        if disc >= 0 and b > 0:
            best = min(best, b - math.sqrt(disc))
    return best


def cast_segments(ox, oy, ang, segs):
    best = math.inf
    dx, dy = math.cos(ang), math.sin(ang)
    for (px, py), (qx, qy) in segs:
        ex, ey = qx - px, qy - py
        den = dx * ey - dy * ex
        if abs(den) < 1e-12:
            continue
        wx, wy = px - ox, py - oy
        t = (wx * ey - wy * ex) / den
        s = (wx * dy - wy * dx) / den
        if t > 0 and 0 <= s <= 1:
            best = min(best, t)
    return best


class PerceptionTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("check_perception")
        cls.lock = threading.Lock()
        cls.obstacles, cls.sonar_targets, cls.paths, cls.images, cls.sweeps = [], [], [], [], []
        cls.markers, cls.diag, cls.tracks = [], {}, []
        cls.subs = [
            rospy.Subscriber("/usv/obstacles", TargetArray, cls._add(cls.obstacles)),
            rospy.Subscriber("/usv/tracks", TrackArray, cls._add(cls.tracks)),
            rospy.Subscriber("/auv/sonar/targets", TargetArray, cls._add(cls.sonar_targets)),
            rospy.Subscriber("/auv/sonar/wall_path", Path, cls._add(cls.paths)),
            rospy.Subscriber("/auv/sonar/image", Image, cls._add(cls.images)),
            rospy.Subscriber("/auv/sonar/sweep", PointCloud2, cls._add(cls.sweeps)),
            rospy.Subscriber("/usv/markers", MarkerArray, cls._add(cls.markers)),
            rospy.Subscriber("/diagnostics", DiagnosticArray, cls._on_diag),
        ]
        cls.tf = tf2_ros.TransformBroadcaster()
        cls.static_tf = tf2_ros.StaticTransformBroadcaster()
        cls.cloud_pub = rospy.Publisher("/usv/lidar/points", PointCloud2, queue_size=10)
        cls.beam_pub = rospy.Publisher("/auv/sonar/beam", SonarBeam, queue_size=1000)
        cls.sweep_pub = rospy.Publisher("/auv/sonar/sweep", PointCloud2, queue_size=10)   # sweeps of our own
        # Sensor mounts: LiDAR 1 m forward, 1.5 m up (ROS frame); sonar on top, x forward, y starboard, z down.
        lidar = cls._tf("usv/base_link", "usv/lidar", 1.0, 0.0, 1.5, (0, 0, 0, 1), rospy.Time(0))
        sonar = cls._tf("auv/base_link", "auv/sonar", 0.5, 0.0, 0.3, (1, 0, 0, 0), rospy.Time(0))
        cls.static_tf.sendTransform([lidar, sonar])
        deadline = time.time() + 30
        while time.time() < deadline and (cls.cloud_pub.get_num_connections() == 0 or
                                          cls.beam_pub.get_num_connections() == 0 or
                                          not cls._subscribers("/auv/sonar/sweep")):
            time.sleep(0.1)
        time.sleep(1.0)

    @classmethod
    def _add(cls, store):
        def cb(msg):
            with cls.lock:
                store.append(msg)
        return cb

    @classmethod
    def _on_diag(cls, msg):
        with cls.lock:
            for s in msg.status:
                cls.diag[s.name] = {kv.key: kv.value for kv in s.values}

    @staticmethod
    def _subscribers(topic):
        """The nodes (this checker left out) the master lists as subscribed to `topic`."""
        subs = rosgraph.Master(rospy.get_name()).getSystemState()[1]
        return sorted(n for t, nodes in subs if t == topic for n in nodes if n != rospy.get_name())

    @classmethod
    def _diag_of(cls, name):
        with cls.lock:
            return next((v for k, v in cls.diag.items() if name in k), {})

    @staticmethod
    def _tf(parent, child, x, y, z, q, stamp):
        t = TransformStamped()
        t.header.stamp = stamp
        t.header.frame_id = parent
        t.child_frame_id = child
        t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = x, y, z
        (t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z, t.transform.rotation.w) = q
        return t

    # ------------------------------------------------------------------ LiDAR
    def _cloud(self, stamp, frame, n_e, yaw_ned, layers=4, cols=1100, aperture=math.radians(275)):
        """MRS1000-like organised cloud seen from a USV at NED (n, e) with NED yaw; lidar 1 m ahead."""
        n, e = n_e
        ln, le = n + math.cos(yaw_ned), e + math.sin(yaw_ned)
        pts = bytearray()
        for layer in range(layers):
            el = math.radians(-2.5 + 2.5 * layer)
            for k in range(cols):
                a = -aperture / 2 + aperture * k / cols       # ROS frame: counter-clockwise from forward
                world = yaw_ned - a                            # NED yaw is clockwise
                r = cast_circles(ln, le, world, BUOYS)
                if r < 64:
                    pts += struct.pack("<ffff", r * math.cos(a), r * math.sin(a), r * math.tan(el), 50.0)
                else:
                    pts += struct.pack("<ffff", math.nan, math.nan, math.nan, 0.0)
        msg = PointCloud2()
        msg.header.stamp = stamp
        msg.header.frame_id = frame
        msg.height, msg.width = layers, cols
        msg.fields = [PointField(name=c, offset=4 * i, datatype=PointField.FLOAT32, count=1)
                      for i, c in enumerate(["x", "y", "z", "intensity"])]
        msg.point_step, msg.row_step = 16, 16 * cols
        msg.is_dense = False
        msg.data = bytes(pts)
        return msg

    def _usv_pose(self, stamp, n, e, yaw_ned):
        # map is ENU: x = east, y = north, ENU yaw = pi/2 - NED yaw.
        self.tf.sendTransform(self._tf("map", "usv/base_link", e, n, 0.0, quat_yaw(math.pi / 2 - yaw_ned), stamp))

    def test_1_lidar_targets_at_ground_truth(self):
        checked = 0
        for i in range(8):
            n, e, yaw = 2.0 * i, 1.0 * i, math.radians(20 + 5 * i)   # moving and turning
            stamp = rospy.Time.now()
            self._usv_pose(stamp, n, e, yaw)
            time.sleep(0.05)
            with self.lock:
                before = len(self.obstacles)
            self.cloud_pub.publish(self._cloud(stamp, "usv/lidar", (n, e), yaw))
            deadline = time.time() + 5
            while time.time() < deadline:
                with self.lock:
                    if len(self.obstacles) > before:
                        break
                time.sleep(0.02)
            with self.lock:
                self.assertGreater(len(self.obstacles), before, "no /usv/obstacles for frame %d" % i)
                msg = self.obstacles[-1]
            self.assertEqual(msg.header.frame_id, "map_ned")
            self.assertEqual(msg.header.stamp, stamp)
            self.assertEqual(len(msg.targets), len(BUOYS), [(t.centroid.x, t.centroid.y) for t in msg.targets])
            for bn, be, br in BUOYS:
                t = min(msg.targets, key=lambda t: math.hypot(t.centroid.x - bn, t.centroid.y - be))
                # Returns lie on the buoy's surface: centroid and eq. 4.3 origin within the radius (+5 cm).
                self.assertLess(math.hypot(t.centroid.x - bn, t.centroid.y - be), br + 0.05)
                self.assertLess(math.hypot(t.origin.x - bn, t.origin.y - be), br + 0.05)
                lidar_n, lidar_e = n + math.cos(yaw), e + math.sin(yaw)
                self.assertAlmostEqual(t.range, math.hypot(bn - lidar_n, be - lidar_e) - br, delta=0.05)
                self.assertEqual(t.source, t.SOURCE_LIDAR)
                # map_ned z is down, sensor 1.5 m up: returns between the min_z cut (-1.2 m in usv/lidar,
                # water surface) and the top layer (+5 deg).
                d = t.range + br
                self.assertLessEqual(t.centroid.z, -(1.5 - 1.2) + 0.05)
                self.assertGreaterEqual(t.centroid.z, -(1.5 + d * math.tan(math.radians(5.0))) - 0.05)
            checked += 1
        self.assertEqual(checked, 8)
        with self.lock:
            self.assertTrue(any(m.markers and m.markers[-1].ns == "lidar_targets" for m in self.markers))
        # the same frames as tracks: one per buoy from the first frame on, confirmed from the fourth, the ids kept
        deadline = time.time() + 5
        while time.time() < deadline:
            with self.lock:
                if len(self.tracks) >= 8:
                    break
            time.sleep(0.05)
        with self.lock:
            tracks = list(self.tracks[-8:])
            track_markers = [m for a in self.markers for m in a.markers if m.ns == "lidar_tracks"]
        self.assertEqual(len(tracks), 8)
        ids = sorted(t.id for t in tracks[0].tracks)
        self.assertEqual(len(ids), len(BUOYS))
        for i, msg in enumerate(tracks):
            self.assertEqual(msg.header.frame_id, "map_ned")
            self.assertEqual(sorted(t.id for t in msg.tracks), ids, "frame %d" % i)
            want = Track.CONFIRMED if i >= 3 else Track.TENTATIVE
            self.assertEqual([t.status for t in msg.tracks], [want] * len(BUOYS), "frame %d" % i)
        for bn, be, br in BUOYS:
            t = min(tracks[-1].tracks, key=lambda t: math.hypot(t.position.x - bn, t.position.y - be))
            self.assertLess(math.hypot(t.position.x - bn, t.position.y - be), br + 0.1)
            self.assertLess(math.hypot(t.velocity.x, t.velocity.y), 1.0)  # its returns move round it as the USV turns
            self.assertEqual(t.hits, 8)
            self.assertEqual(len(t.covariance), 16)
            self.assertGreater(t.covariance[0], 0.0)
        self.assertTrue(any(m.type == m.TEXT_VIEW_FACING and m.text.startswith("#%d " % ids[0]) for m in track_markers),
                        [m.text for m in track_markers])
        self.assertIn("tracks_born", self._diag_of("lidar_targets"))

    # ------------------------------------------------------------------ sonar
    def _beam(self, stamp, bearing, n, e, yaw_ned, status=SonarBeam.STATUS_HEAD_READY | SonarBeam.STATUS_MOTOR_ON,
              bins=300, res=0.1):
        sn, se = n + 0.5 * math.cos(yaw_ned), e + 0.5 * math.sin(yaw_ned)
        world = yaw_ned + bearing
        r = min(cast_circles(sn, se, world, [SONAR_TARGET]), cast_segments(sn, se, world, TANK))
        data = np.full(bins, 15, dtype=np.uint8)
        data[:5] = 250                                     # ringing inside the 1.5 m minimum range
        k = int(round(r / res)) if math.isfinite(r) else -1
        if 0 <= k < bins:
            data[k] = 200
        b = SonarBeam()
        b.header.stamp = stamp
        b.header.frame_id = "auv/sonar"
        b.bearing = bearing % (2 * math.pi)
        b.beam_width = math.radians(3)
        b.range_resolution = res
        b.range_offset = 0.0
        b.head_status = status
        b.intensities = data.tobytes()
        return b

    def _auv_pose(self, stamp, n, e, yaw_ned):
        self.tf.sendTransform(self._tf("map", "auv/base_link", e, n, -5.0, quat_yaw(math.pi / 2 - yaw_ned), stamp))

    def test_2_sonar_targets_and_wall_path(self):
        steps = 400
        t0 = rospy.Time.now()
        for k in range(2 * steps + 1):
            stamp = t0 + rospy.Duration(0.01 * k)
            s = 0.01 * k
            n, e, yaw = 0.2 * s, 0.0, math.radians(2.0 * s)   # moving north 0.2 m/s, turning (sim-time scale)
            self._auv_pose(stamp, n, e, yaw)
            self.beam_pub.publish(self._beam(stamp, 2 * math.pi * k / steps, n, e, yaw))
            time.sleep(0.004)
        deadline = time.time() + 10
        while time.time() < deadline:
            with self.lock:
                if len(self.sonar_targets) >= 2 and self.paths and self.images and self.sweeps:
                    break
            time.sleep(0.05)
        with self.lock:
            self.assertGreaterEqual(len(self.sonar_targets), 2, "sweeps with targets")
            self.assertTrue(self.images, "no /auv/sonar/image")
            self.assertTrue(self.sweeps, "no /auv/sonar/sweep")
            self.assertTrue(self.paths, "no /auv/sonar/wall_path")
            targets = self.sonar_targets[0]
            path = self.paths[-1]
            image = self.images[-1]
        self.assertEqual(image.encoding, "mono8")
        self.assertEqual(image.header.frame_id, "auv/sonar")
        # The small target is found where it is (on its surface, 0.1 m bins), at the AUV's depth.
        tn, te, tr = SONAR_TARGET
        near = [t for t in targets.targets if math.hypot(t.nearest.x - tn, t.nearest.y - te) < tr + 0.3]
        self.assertEqual(len(near), 1, [(t.nearest.x, t.nearest.y, t.num_points) for t in targets.targets])
        self.assertLess(abs(math.hypot(near[0].nearest.x - tn, near[0].nearest.y - te) - tr), 0.2)
        self.assertAlmostEqual(near[0].depth, 4.7, delta=0.05)   # sonar 0.3 m above base_link (5 m deep)
        self.assertEqual(near[0].source, near[0].SOURCE_SONAR)
        # Wall path: two waypoints 2 m apart, WALL_DISTANCE from one of the tank walls, inside the tank.
        self.assertEqual(path.header.frame_id, "map_ned")
        self.assertEqual(len(path.poses), 2)
        p1, p2 = path.poses[0].pose.position, path.poses[1].pose.position
        self.assertAlmostEqual(math.hypot(p2.x - p1.x, p2.y - p1.y), 2.0, delta=1e-6)
        d1 = min(abs(p1.x - 20.0), abs(p1.x + 10.0), abs(p1.y - 12.0), abs(p1.y + 12.0))
        self.assertAlmostEqual(d1, WALL_DISTANCE, delta=0.2)
        self.assertTrue(-10 < p1.x < 20 and -12 < p1.y < 12)
        self.assertAlmostEqual(p1.z, 5.0, delta=0.5)

    # ------------------------------------------------------------------ sweeps assembled once
    @staticmethod
    def _sweep(stamp, points, frame="map_ned"):
        """A sweep cloud as SonarTargets publishes it: x, y, z, intensity FLOAT32, one point per detection."""
        msg = PointCloud2()
        msg.header.stamp = stamp
        msg.header.frame_id = frame
        msg.height, msg.width = 1, len(points)
        msg.fields = [PointField(name=c, offset=4 * i, datatype=PointField.FLOAT32, count=1)
                      for i, c in enumerate(["x", "y", "z", "intensity"])]
        msg.point_step, msg.row_step = 16, 16 * len(points)
        msg.is_dense = True
        msg.data = b"".join(struct.pack("<ffff", x, y, z, 200.0) for x, y, z in points)
        return msg

    def _wall_path_from(self, sweep, stamp):
        """Publishes `sweep` (the AUV's pose at `stamp` already sent); the wall path it gives, or None."""
        with self.lock:
            before = len(self.paths)
        self.sweep_pub.publish(sweep)
        deadline = time.time() + 5
        while time.time() < deadline:
            with self.lock:
                fresh = [p for p in self.paths[before:] if p.header.stamp == stamp]
            if fresh:
                return fresh[0]
            time.sleep(0.02)
        return None

    def test_3_walls_from_the_sonar_targets_sweeps(self):
        # The beams go to the sonar targets only; the wall detection (same manager) takes the published sweeps:
        # every sweep the sonar targets assembled reached it (test_4: the bad beams reach the sonar targets only).
        self.assertTrue(self._subscribers("/auv/sonar/sweep"), "nothing but the checker takes /auv/sonar/sweep")
        sonar = wall = {}
        deadline = time.time() + 5
        while time.time() < deadline:
            sonar, wall = self._diag_of("sonar_targets"), self._diag_of("wall_detection")
            with self.lock:
                published = len(self.sweeps)
            if published > 0 and int(sonar.get("sweeps", -1)) == int(wall.get("sweeps", -1)) == published:
                break
            time.sleep(0.2)
        self.assertGreater(published, 0)
        self.assertEqual(int(sonar.get("sweeps", -1)), published, sonar)
        self.assertEqual(int(wall.get("sweeps", -1)), published, wall)
        # A sweep cloud alone, no beam: a straight wall 6 m north of an AUV heading east gives its path.
        stamp = rospy.Time.now()
        self._auv_pose(stamp, 0.0, 0.0, math.pi / 2)
        time.sleep(0.05)
        points = [(6.0, -8.0 + 0.1 * i, 5.0) for i in range(161)]
        path = self._wall_path_from(self._sweep(stamp, points), stamp)
        self.assertIsNotNone(path, "no /auv/sonar/wall_path from a published sweep")
        self.assertEqual(path.header.frame_id, "map_ned")
        p1, p2 = path.poses[0].pose.position, path.poses[1].pose.position
        self.assertAlmostEqual(p1.x, 6.0 - WALL_DISTANCE, delta=0.05)   # abeam, on the AUV's side
        self.assertAlmostEqual(p1.y, 0.0, delta=0.05)
        self.assertAlmostEqual(p2.x, 6.0 - WALL_DISTANCE, delta=0.05)
        self.assertAlmostEqual(p2.y, 2.0, delta=0.05)                    # ahead, eastwards
        self.assertAlmostEqual(p1.z, 5.0, delta=0.05)

    # ------------------------------------------------------------------ bad input
    def test_4_bad_input_is_counted(self):
        stamp = rospy.Time.now()
        self._usv_pose(stamp, 0.0, 0.0, 0.0)
        # no wait for the pose: the nodelet names a malformed cloud before it looks its pose up (counted no_transform
        # when it came in ahead of it, CI 2026-12-06)
        good = self._cloud(stamp, "usv/lidar", (0.0, 0.0), 0.0, cols=50)
        bad_size = self._cloud(stamp, "usv/lidar", (0.0, 0.0), 0.0, cols=50)
        bad_size.data = bad_size.data[:-7]
        no_xyz = self._cloud(stamp, "usv/lidar", (0.0, 0.0), 0.0, cols=50)
        no_xyz.fields = no_xyz.fields[1:]
        empty = self._cloud(stamp, "usv/lidar", (0.0, 0.0), 0.0, cols=50)
        empty.width, empty.height, empty.row_step, empty.data = 0, 0, 0, b""
        unknown_frame = self._cloud(stamp, "usv/nowhere", (0.0, 0.0), 0.0, cols=50)
        for m in (bad_size, no_xyz, empty, unknown_frame, good):
            self.cloud_pub.publish(m)
            time.sleep(0.2)
        s_stamp = rospy.Time.now()
        self._auv_pose(s_stamp, 0.0, 0.0, 0.0)
        zero_bins = self._beam(s_stamp, 0.0, 0.0, 0.0, 0.0)
        zero_bins.intensities = b""
        bad_bearing = self._beam(s_stamp, 0.0, 0.0, 0.0, 0.0)
        bad_bearing.bearing = 7.5
        fault = self._beam(s_stamp, 0.1, 0.0, 0.0, 0.0, status=SonarBeam.STATUS_FAULT)
        for m in (zero_bins, bad_bearing, fault):
            self.beam_pub.publish(m)
            time.sleep(0.1)
        # Bad sweeps, straight to the wall detection: no points over a buffer, no y, a short buffer, NaN points (the
        # wall still found from the rest), another frame; a sweep of no points is no error (nothing detected).
        w_stamp = rospy.Time.now()
        self._auv_pose(w_stamp, 0.0, 0.0, math.pi / 2)
        good_points = [(6.0, -8.0 + 0.1 * i, 5.0) for i in range(161)]
        no_points = self._sweep(w_stamp, good_points)
        no_points.width, no_points.row_step = 0, 0
        no_y = self._sweep(w_stamp, good_points)
        no_y.fields = [f for f in no_y.fields if f.name != "y"]
        short = self._sweep(w_stamp, good_points)
        short.data = short.data[:-5]
        elsewhere = self._sweep(w_stamp, good_points, frame="map")
        for m in (no_points, no_y, short, elsewhere, self._sweep(w_stamp, [])):
            self.sweep_pub.publish(m)
            time.sleep(0.1)
        nan_points = list(good_points)
        nan_points[40] = (math.nan, 0.0, 5.0)
        nan_points[90] = (6.0, math.inf, 5.0)
        path = self._wall_path_from(self._sweep(w_stamp, nan_points), w_stamp)
        self.assertIsNotNone(path, "no wall path from a sweep with two NaN points")
        self.assertAlmostEqual(path.poses[0].pose.position.x, 6.0 - WALL_DISTANCE, delta=0.05)
        lidar_want = {"size_mismatch": 1, "missing_xyz": 1, "empty_cloud": 1, "no_transform": 1}
        sonar_want = {"empty_beam": 1, "bad_bearing": 1, "head_not_ready": 1}
        wall_want = {"empty_cloud": 1, "missing_xyz": 1, "size_mismatch": 1, "wrong_frame": 1, "empty_sweep": 1,
                     "non_finite_point": 2}
        deadline = time.time() + 10
        lidar = sonar = wall = {}
        while time.time() < deadline:
            lidar, sonar, wall = (self._diag_of(n) for n in ("lidar_targets", "sonar_targets", "wall_detection"))
            if all(int(lidar.get(k, 0)) >= v for k, v in lidar_want.items()) and \
                    all(int(sonar.get(k, 0)) >= v for k, v in sonar_want.items()) and \
                    all(int(wall.get(k, 0)) >= v for k, v in wall_want.items()):
                break
            time.sleep(0.2)
        for k, v in lidar_want.items():
            self.assertGreaterEqual(int(lidar.get(k, 0)), v, "lidar counter %s: %s" % (k, lidar))
        for k, v in sonar_want.items():
            self.assertGreaterEqual(int(sonar.get(k, 0)), v, "sonar counter %s: %s" % (k, sonar))
        for k, v in wall_want.items():
            self.assertGreaterEqual(int(wall.get(k, 0)), v, "wall counter %s: %s" % (k, wall))
        # the bad beams reached the sonar targets only
        for k in BEAM_COUNTERS:
            self.assertNotIn(k, wall, "the wall detection saw a beam: %s" % wall)
        # Still alive and working after the bad input.
        with self.lock:
            before = len(self.obstacles)
        stamp = rospy.Time.now()
        self._usv_pose(stamp, 0.0, 0.0, math.radians(30))
        time.sleep(0.05)
        self.cloud_pub.publish(self._cloud(stamp, "usv/lidar", (0.0, 0.0), math.radians(30)))
        deadline = time.time() + 5
        while time.time() < deadline and len(self.obstacles) == before:
            time.sleep(0.05)
        self.assertGreater(len(self.obstacles), before)


if __name__ == "__main__":
    rostest.rosrun("offshore_gnc", "perception_nodelets", PerceptionTest)

"""The mission report's recordings (report.py): the bags' messages by topic, and the tracks and statuses in them
looked up at a time."""
import bisect
import os


def _interpolate(track, t):
    """(north, east) of a track [(t, north, east, ...)] at time t (linear), None outside its span."""
    import bisect
    times = [p[0] for p in track]
    if not times or t < times[0] or t > times[-1]:
        return None
    i = bisect.bisect_left(times, t)
    if times[i] == t:
        return track[i][1], track[i][2]
    (t0, n0, e0, *_), (t1, n1, e1, *_) = track[i - 1], track[i]
    w = (t - t0) / (t1 - t0)
    return n0 + w * (n1 - n0), e0 + w * (e1 - e0)


def read_bag(path, topics):
    """{topic: [(t, msg), ...]} for the topics present in a bag (missing bag -> empty)."""
    out = {t: [] for t in topics}
    if not path or not os.path.exists(path):
        return out
    import rosbag
    with rosbag.Bag(path) as bag:
        for topic, msg, t in bag.read_messages(topics=topics):
            out[topic].append((t.to_sec(), msg))
    return out


def odom_track_ned(msgs):
    """nav_msgs/Odometry in map (ENU) -> [(t, north, east, down)]."""
    return [(t, m.pose.pose.position.y, m.pose.pose.position.x, -m.pose.pose.position.z) for t, m in msgs]


def _stamp(t, m):
    """A message's header stamp [s], or its bag time when the stamp is unset."""
    s = m.header.stamp.to_sec()
    return s if s > 0.0 else t


def _interpolate3(track, t):
    """(north, east, down) of a track [(t, north, east, down)] at time t (linear), None outside its span."""
    times = [p[0] for p in track]
    if not times or t < times[0] or t > times[-1]:
        return None
    i = bisect.bisect_left(times, t)
    if times[i] == t:
        return track[i][1:4]
    a, b = track[i - 1], track[i]
    w = (t - a[0]) / (b[0] - a[0])
    return tuple(a[k] + w * (b[k] - a[k]) for k in (1, 2, 3))


def sim_counter(diagnostics, status, key):
    """A counter of a simulator's diagnostics (the last status whose name ends with `status`), None without one."""
    value = None
    for _, m in diagnostics:
        for st in m.status:
            if st.name.endswith(status):
                value = next((int(kv.value) for kv in st.values if kv.key == key), value)
    return value


def path_ned(path_msg):
    """nav_msgs/Path -> [(north, east)], whatever its frame (map_ned or map)."""
    ned = path_msg.header.frame_id.endswith("ned")
    pts = []
    for p in path_msg.poses:
        x, y = p.pose.position.x, p.pose.position.y
        pts.append((x, y) if ned else (y, x))
    return pts


def _phase_at(status, t):
    """The latest status at time t (status sorted by time), None before the first."""
    i = bisect.bisect_right([x for x, _ in status], t)
    return status[i - 1][1] if i else None


def _at(track, t):
    """The track sample nearest in time to t (track sorted by time)."""
    i = bisect.bisect_left([p[0] for p in track], t)
    return min(track[max(i - 1, 0):i + 1], key=lambda p: abs(p[0] - t))

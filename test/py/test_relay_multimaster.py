"""Multi-master relay tests: real rosmasters on free ports (MasterSet), real relay nodelets, real sockets.

Run as a script (`python3 test_relay_multimaster.py probe ...`) the file is also the probe node the tests start
against one master: a counting publisher or a recording subscriber.
"""
import os
import re
import signal
import socket
import subprocess
import sys
import time

import pytest
import yaml

from offshore_gnc import VEHICLES
from offshore_gnc.testing import MasterSet, free_port, wait_until

HERE = os.path.abspath(__file__)
REPO = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
KEY = "relay-test-key-0123456789"


# ------------------------------------------------------------------------------------------- probe node
def _probe(argv):
    import rospy
    from std_msgs.msg import String
    mode, topic = argv[0], argv[1]
    rospy.init_node("probe", anonymous=True, disable_signals=False)
    if mode == "pub":  # pub TOPIC N RATE
        n, rate = int(argv[2]), float(argv[3])
        pub = rospy.Publisher(topic, String, queue_size=1000)
        wait_until(lambda: pub.get_num_connections() >= 1, 20, step=0.02)  # the relay's subscriber
        r = rospy.Rate(rate)
        for i in range(n):
            pub.publish(String(data=str(i)))
            r.sleep()
        rospy.sleep(1.0)
    elif mode == "sub":  # sub TOPIC OUTFILE
        out = open(argv[2], "a", buffering=1)
        rospy.Subscriber(topic, String, lambda m: out.write(m.data + "\n"), queue_size=1000)
        rospy.spin()


# ------------------------------------------------------------------------------------------- helpers
def start_relay(master, cfg, name="relay", nodelet=False, origin="61.4507,23.7270"):
    """The relay_node executable (as launch/relay.launch), or the same code as the Relay nodelet, on a master
    whose site origin is `origin` (launch/site.launch's /site/origin)."""
    master.set_param("/site/origin", origin)
    path = os.path.join(master.log_dir, "%s-%s.yaml" % (master.name, name))
    with open(path, "w") as f:
        yaml.safe_dump(cfg, f)
    rc, out = master.call(["rosparam", "load", path, "/" + name])
    assert rc == 0, out
    cmd = ["rosrun", "nodelet", "nodelet", "standalone", "offshore_gnc/Relay"] if nodelet else \
        ["rosrun", "offshore_gnc", "relay_node"]
    return master.run(cmd + ["__name:=" + name], name=name)


def target_link(usv, auv, port, key=KEY, auv_origin="61.4507,23.7270"):
    """The AUV's relay dialling the USV's to send /target (std_msgs/String), with the AUV's own key and site."""
    start_relay(usv, cfg("usv", [{"name": "auv"}],
                         [{"topic": "/target", "type": "std_msgs/String", "direction": "in"}], listen_port=port))
    start_relay(auv, cfg("auv", [{"name": "usv", "address": "127.0.0.1:%d" % port}],
                         [{"topic": "/target", "type": "std_msgs/String", "direction": "out"}], key=key),
                origin=auv_origin)


def cfg(name, peers, topics, listen_port=0, key=KEY, **extra):
    c = {"name": name, "listen_port": listen_port, "peers": peers, "topics": topics,
         "heartbeat_period": 0.1, "link_timeout": 0.6, "backoff_max": 0.5, "sim": True}
    if key:
        c["key"] = key
    else:
        c["auth"] = "none"
    c.update(extra)
    return c


def probe(master, *args, name):
    return master.run(["/usr/bin/python3", HERE, "probe"] + [str(a) for a in args], name=name)


def read_lines(path):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return [l.strip() for l in f if l.strip()]


def log_text(master, name):
    try:
        with open(master.log_path(name), errors="replace") as f:
            return f.read()
    except FileNotFoundError:
        return ""


def link_status(master, timeout=30):  # generous: under the sanitizers a rostopic start alone takes seconds
    return master.wait_for_message("/relay/link_status", timeout=timeout)


# ------------------------------------------------------------------------------------------- tests
def test_shipped_configs_carry_the_thesis_topics_latched_target():
    """config/relay/{usv,auv}.yaml: /usv_gps + /usv_heading USV -> AUV, /target AUV -> USV (latched)."""
    port = free_port()
    with MasterSet(VEHICLES) as ms:
        usv, auv = ms["usv"], ms["auv"]
        key_file = os.path.join(usv.log_dir, "key")
        with open(key_file, "w") as f:
            f.write(KEY + "\n")
        for m, vehicle in ((usv, "usv"), (auv, "auv")):
            with open(os.path.join(REPO, "config", "relay", vehicle + ".yaml")) as f:
                c = yaml.safe_load(f)
            c["key_file"] = key_file
            c["sim"] = True  # KEY is no deployment key
            if vehicle == "usv":
                c["listen_port"] = port
            else:
                c["peers"][0]["address"] = "127.0.0.1:%d" % port
            start_relay(m, c)
        # latched /target published on the AUV before anyone on the USV listens
        auv.publish("/target", "offshore_gnc/Target", {"id": 7, "range": 12.5, "latitude": 61.45})
        usv.publish("/usv_gps", "sensor_msgs/NavSatFix", {"latitude": 61.45, "longitude": 23.85}, latch=False)
        usv.run(["rostopic", "pub", "-r", "5", "/usv_heading", "geometry_msgs/QuaternionStamped",
                 "{quaternion: {w: 1.0}}"], name="heading")
        assert usv.wait_for_topic("/target", timeout=15), usv.topics()
        time.sleep(1.0)  # a late subscriber, long after the message was sent
        t = usv.wait_for_message("/target", timeout=10)
        assert t["id"] == 7 and abs(t["range"] - 12.5) < 1e-9
        # 30 s: rostopic itself and the 5 Hz publisher start slowly on a loaded machine (10 s failed under the sanitizers)
        h = auv.wait_for_message("/usv_heading", timeout=30)
        assert abs(h["quaternion"]["w"] - 1.0) < 1e-9
        # direction: /usv_gps only goes USV -> AUV, /target never goes back to the AUV's master from the USV
        assert "/usv_heading" in auv.topics()
        st = link_status(usv)
        assert st["up"] and st["local_name"] == "usv" and st["peer_name"] == "auv"
        # best effort goes by UDP after its first message (which rides TCP behind the announce)
        time.sleep(1.5)  # a few more headings at 5 Hz
        rc, out = usv.call(["rostopic", "echo", "-n", "1", "/relay/link_status"], timeout=10)  # with the arrays
        st = yaml.safe_load(out.split("\n---")[0])
        heading = [t for t in st["topics"] if t["topic"] == "/usv_heading"][0]
        assert heading["transport"] == "udp+tcp" and heading["messages"] >= 3, heading
        target = [t for t in st["topics"] if t["topic"] == "/target"][0]
        assert target["transport"] == "tcp", target  # reliable


def test_renaming_direction_and_first_message():
    port = free_port()
    with MasterSet(VEHICLES) as ms:
        usv, auv = ms["usv"], ms["auv"]
        out = os.path.join(usv.log_dir, "renamed.txt")
        probe(usv, "sub", "/usv/from_auv", out, name="sub")
        start_relay(usv, cfg("usv", [{"name": "auv"}],
                             [{"topic": "/usv/from_auv", "type": "std_msgs/String", "direction": "in"}],
                             listen_port=port))
        start_relay(auv, cfg("auv", [{"name": "usv", "address": "127.0.0.1:%d" % port}],
                             [{"topic": "/chat", "type": "std_msgs/String", "direction": "out",
                               "remote": "/usv/from_auv"}]))
        probe(auv, "pub", "/chat", 20, 50, name="pub")
        assert wait_until(lambda: len(read_lines(out)) >= 20, 20), read_lines(out)
        assert read_lines(out) == [str(i) for i in range(20)]  # the first message too, in order
        # only the configured name crosses, and nothing goes the other way
        assert "/chat" not in usv.topics()
        assert "/usv/from_auv" not in auv.topics()


def test_type_mismatch_is_refused_naming_the_topic():
    port = free_port()
    with MasterSet(VEHICLES) as ms:
        usv, auv = ms["usv"], ms["auv"]
        start_relay(usv, cfg("usv", [{"name": "auv"}],
                             [{"topic": "/target", "type": "std_msgs/String", "direction": "in"}], listen_port=port))
        start_relay(auv, cfg("auv", [{"name": "usv", "address": "127.0.0.1:%d" % port}],
                             [{"topic": "/target", "type": "offshore_gnc/Target", "direction": "out"},
                              {"topic": "/other", "type": "offshore_gnc/Target", "direction": "out"}]))
        auv.publish("/target", "offshore_gnc/Target", {"id": 1})
        auv.publish("/other", "std_msgs/String", {"data": "x"})  # sender side: wrong local type
        assert wait_until(lambda: "refused" in log_text(usv, "relay"), 15), log_text(usv, "relay")
        usv_log, auv_log = log_text(usv, "relay"), log_text(auv, "relay")
        assert "/target" in usv_log and "offshore_gnc/Target" in usv_log
        assert wait_until(lambda: "/other" in log_text(auv, "relay") and "std_msgs/String" in log_text(auv, "relay"),
                          10), auv_log
        assert "/target" not in usv.topics()


def test_wrong_key_delivers_nothing_and_counts():
    port = free_port()
    with MasterSet(VEHICLES) as ms:
        usv, auv = ms["usv"], ms["auv"]
        target_link(usv, auv, port, key="not-the-same-key-at-all")
        auv.publish("/target", "std_msgs/String", {"data": "secret"})
        time.sleep(3.0)
        assert "/target" not in usv.topics()
        st = link_status(usv)
        assert not st["up"]
        assert "failed authentication" in log_text(usv, "relay")


def test_vehicles_on_different_site_origins_refuse_each_other_naming_both():
    """Two masters started on different origins (a USV at Pyhäjärvi, an AUV whose site file says Hobart): each relay
    refuses the other at link-up, /relay/link_status and the log name both origins, and no /target crosses, which
    the USV would otherwise have placed 14,000 km off."""
    port = free_port()
    with MasterSet(VEHICLES) as ms:
        usv, auv = ms["usv"], ms["auv"]
        target_link(usv, auv, port, auv_origin="-42.8821,147.3514")
        auv.publish("/target", "std_msgs/String", {"data": "a target in the wrong frame"})
        for master, other in ((usv, "auv"), (auv, "usv")):
            assert wait_until(lambda: link_status(master).get("refused"), 20), log_text(master, "relay")
            st = link_status(master)
            assert not st["up"]
            assert "refused %s" % other in st["refused"], st["refused"]
            assert "61.4507" in st["refused"] and "-42.8821" in st["refused"], st["refused"]
            assert "61.4507" in log_text(master, "relay") and "-42.8821" in log_text(master, "relay")
        assert "/target" not in usv.topics()


def test_receiver_restart_mid_stream_loses_nothing():
    port = free_port()
    n = 300
    with MasterSet(VEHICLES) as ms:
        usv, auv = ms["usv"], ms["auv"]
        out = os.path.join(usv.log_dir, "count.txt")
        probe(usv, "sub", "/count", out, name="sub")
        usv_cfg = cfg("usv", [{"name": "auv"}], [{"topic": "/count", "type": "std_msgs/String", "direction": "in"}],
                      listen_port=port)
        relay = start_relay(usv, usv_cfg)
        start_relay(auv, cfg("auv", [{"name": "usv", "address": "127.0.0.1:%d" % port}],
                             [{"topic": "/count", "type": "std_msgs/String", "direction": "out", "reliable": True}]))
        probe(auv, "pub", "/count", n, 100, name="pub")
        assert wait_until(lambda: len(read_lines(out)) >= 60, 20)
        os.killpg(relay.pid, signal.SIGKILL)  # the harshest restart: nothing flushed
        relay.wait(5)
        time.sleep(0.5)
        start_relay(usv, usv_cfg, name="relay")
        assert wait_until(lambda: set(read_lines(out)) >= {str(i) for i in range(n)}, 30), \
            sorted(set(str(i) for i in range(n)) - set(read_lines(out)), key=int)[:20]
        st = link_status(auv)
        assert st["up"]


def test_four_masters_several_peers():
    port = free_port()
    with MasterSet(["usv", "auv1", "auv2", "ground"]) as ms:
        usv = ms["usv"]
        gps_topic = {"topic": "/usv_gps", "type": "std_msgs/String", "direction": "out"}
        start_relay(usv, cfg("usv", [{"name": "auv1"}, {"name": "auv2"}, {"name": "ground"}],
                             [gps_topic,
                              {"topic": "/auv1/target", "type": "std_msgs/String", "direction": "in", "peers": ["auv1"]},
                              {"topic": "/auv2/target", "type": "std_msgs/String", "direction": "in", "peers": ["auv2"]}],
                             listen_port=port))
        dial = [{"name": "usv", "address": "127.0.0.1:%d" % port}]
        for n in ("auv1", "auv2"):
            start_relay(ms[n], nodelet=(n == "auv2"), cfg=cfg(n, dial, [
                {"topic": "/usv_gps", "type": "std_msgs/String", "direction": "in"},
                {"topic": "/target", "type": "std_msgs/String", "direction": "out", "remote": "/%s/target" % n,
                 "latched": True},
                # auv2 also tries to speak for auv1: refused by the USV (peers: [auv1])
                {"topic": "/fake", "type": "std_msgs/String", "direction": "out", "remote": "/auv1/target"}]))
        start_relay(ms["ground"], cfg("ground", dial, [{"topic": "/usv_gps", "type": "std_msgs/String",
                                                        "direction": "in"}]))
        usv.run(["rostopic", "pub", "-r", "5", "/usv_gps", "std_msgs/String", "data: fix"], name="gps")
        for n in ("auv1", "auv2"):
            ms[n].publish("/target", "std_msgs/String", {"data": "target of " + n})
        ms["auv2"].publish("/fake", "std_msgs/String", {"data": "forged"}, name="fake")
        for n in ("auv1", "auv2", "ground"):
            assert ms[n].wait_for_message("/usv_gps", timeout=15)["data"] == "fix"
        assert usv.wait_for_message("/auv1/target", timeout=15)["data"] == "target of auv1"
        assert usv.wait_for_message("/auv2/target", timeout=15)["data"] == "target of auv2"
        assert wait_until(lambda: "not configured" in log_text(usv, "relay"), 10)
        time.sleep(0.5)
        assert usv.wait_for_message("/auv1/target", timeout=5)["data"] == "target of auv1"


def _rss_kb(pid):
    """Resident memory of the relay process (relay_node, exec'd by rosrun, or a nodelet child)."""
    children = []  # from /proc, not pgrep: under the sanitizer run's LD_PRELOAD, procps tools can hang
    for d in os.listdir("/proc"):
        try:
            if d.isdigit() and int(open("/proc/%s/stat" % d).read().rsplit(")", 1)[1].split()[1]) == pid:
                children.append(int(d))
        except (FileNotFoundError, ProcessLookupError, IndexError, ValueError):
            pass
    for pid_ in [pid] + children:
        try:
            cmdline = open("/proc/%d/cmdline" % pid_).read()
            if "relay_node" not in cmdline and "nodelet" not in cmdline:
                continue
            with open("/proc/%d/status" % pid_) as f:
                for line in f:
                    if line.startswith("VmRSS"):
                        return int(line.split()[1])
        except FileNotFoundError:
            pass
    raise AssertionError("no relay process under pid %d" % pid)


def diagnostics_counters(master, timeout=10):
    """The relay's counters from /diagnostics (key -> int)."""
    deadline = time.time() + timeout
    while time.time() < deadline:
        rc, out = master.call(["rostopic", "echo", "-n", "1", "/diagnostics"], timeout=timeout)
        for st in (yaml.safe_load(out.split("\n---")[0]) or {}).get("status", []):
            if st["name"].endswith("link"):
                return {v["key"]: int(v["value"]) for v in st["values"] if v["value"].isdigit()}
    raise AssertionError("no relay diagnostics on " + master.name)


def test_bad_frames_and_floods_are_dropped_counted_bounded():
    port = free_port()
    with MasterSet(VEHICLES) as ms:
        usv, auv = ms["usv"], ms["auv"]
        out = os.path.join(usv.log_dir, "count.txt")
        probe(usv, "sub", "/count", out, name="sub")
        relay = start_relay(usv, cfg("usv", [{"name": "auv"}],
                                     [{"topic": "/count", "type": "std_msgs/String", "direction": "in"}],
                                     listen_port=port))
        start_relay(auv, cfg("auv", [{"name": "usv", "address": "127.0.0.1:%d" % port}],
                             [{"topic": "/count", "type": "std_msgs/String", "direction": "out"}]))
        assert wait_until(lambda: link_status(usv)["up"], 15)
        rss0 = _rss_kb(relay.pid)
        # half-open connections that never say anything (held open), then garbage, an oversized length field,
        # and a 64 MB flood of random bytes over many connections
        half_open = [socket.create_connection(("127.0.0.1", port)) for _ in range(40)]
        blob = os.urandom(1 << 20)
        for i in range(64):
            with socket.create_connection(("127.0.0.1", port)) as s:
                try:
                    if i == 0:
                        s.sendall(b"OGR1" + b"\x03\x00\x00\x00" + b"\x00" * 16 + b"\xff\xff\xff\x7f" + b"\x00" * 4)
                    else:
                        s.sendall(blob)
                except (BrokenPipeError, ConnectionResetError):
                    pass
        probe(auv, "pub", "/count", 50, 50, name="pub")
        assert wait_until(lambda: len(read_lines(out)) >= 50, 20), len(read_lines(out))
        assert relay.poll() is None  # still running
        rss1 = _rss_kb(relay.pid)
        assert rss0 > 0 and rss1 - rss0 < 80 * 1024, (rss0, rss1)
        log = log_text(usv, "relay")
        assert "oversized" in log or "bad magic" in log
        counters = diagnostics_counters(usv)
        assert counters.get("connections_evicted", 0) >= 40 - 12, counters  # the cap: 4 per peer + 8
        assert counters.get("frames_oversized", 0) >= 1 and counters.get("frames_malformed", 0) >= 1, counters
        for s_ in half_open:
            s_.close()


def _relay_key(path):
    """A deployment key made with the documented command; returns its fingerprint."""
    r = subprocess.run([os.path.join(REPO, "scripts", "relay-key"), path], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, timeout=30)
    assert r.returncode == 0, r.stdout
    assert oct(os.stat(path).st_mode & 0o777) == "0o600"
    return r.stdout.decode().split("(")[-1].rstrip(")\n")


def test_hardware_launch_with_the_simulation_key_stops_and_says_how_to_make_one():
    """roslaunch offshore_gnc usv.launch sim:=false with the default key: nothing starts, the message names the
    published simulation key and the command that makes a deployment key; with such a key the check passes."""
    with MasterSet(["usv"]) as ms:
        usv = ms["usv"]
        launch = usv.roslaunch(os.path.join(REPO, "launch", "usv.launch"), {"sim": "false"}, name="usv_hw")
        assert launch.wait(60) != 0
        out = log_text(usv, "usv_hw")
        assert "simulation key" in out and "scripts/relay-key FILE" in out, out
        rc, nodes = usv.call(["rosnode", "list"])
        assert "/relay" not in nodes and "/usv_manager" not in nodes, nodes
        for vehicle in VEHICLES:  # the AUV's launch file includes the same check
            rc, out = usv.call(["roslaunch", "--dump-params", os.path.join(REPO, "launch", vehicle + ".launch"),
                                "sim:=false"], timeout=60)
            assert "simulation key" in out and "key_fingerprint:" not in out, out  # (--dump-params exits 0)
        key = os.path.join(usv.log_dir, "deploy.key")
        fingerprint = _relay_key(key)
        rc, out = usv.call(["roslaunch", "--dump-params", os.path.join(REPO, "launch", "usv.launch"), "sim:=false",
                            "key_file:=" + key], timeout=60)
        assert re.search(r"key_fingerprint: '?%s" % fingerprint, out) and fingerprint.startswith("sha256:"), out


def test_relay_on_hardware_refuses_weak_keys_and_links_with_a_deployment_key():
    port = free_port()
    with MasterSet(VEHICLES) as ms:
        usv, auv = ms["usv"], ms["auv"]
        in_cfg = cfg("usv", [{"name": "auv"}], [{"topic": "/chat", "type": "std_msgs/String", "direction": "in"}],
                     listen_port=port, sim=False)  # KEY: 25 bytes of text, no deployment key
        weak = start_relay(usv, in_cfg, name="weak")
        assert weak.wait(20) == 1
        assert "refusing to start on hardware" in log_text(usv, "weak") and "relay-key" in log_text(usv, "weak")
        key = os.path.join(usv.log_dir, "deploy.key")
        _relay_key(key)
        out_cfg = cfg("auv", [{"name": "usv", "address": "127.0.0.1:%d" % port}],
                      [{"topic": "/chat", "type": "std_msgs/String", "direction": "out", "latched": True}], sim=False)
        for c in (in_cfg, out_cfg):
            del c["key"]
            c["key_file"] = key
        start_relay(usv, in_cfg)
        start_relay(auv, out_cfg)
        auv.publish("/chat", "std_msgs/String", {"data": "on hardware"})
        assert usv.wait_for_message("/chat", timeout=15)["data"] == "on hardware"
        assert link_status(usv)["up"]


if __name__ == "__main__" and len(sys.argv) > 2 and sys.argv[1] == "probe":
    _probe(sys.argv[2:])

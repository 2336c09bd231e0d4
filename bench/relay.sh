# Relay vs one master: added latency (100 B), throughput (1 MB clouds), first-message time; two real masters.
set -euo pipefail
export PATH="/usr/bin:$PATH"
SMALL_N="${SMALL_N:-2000}" LARGE_N="${LARGE_N:-150}" BENCH="$WS/devel/lib/offshore_gnc/relay_bench" \
exec /usr/bin/python3 - "$@" <<'PY'
import json, os, subprocess, sys, time
import yaml
from offshore_gnc.testing.masters import MasterSet, free_port

bench, small_n, large_n = os.environ["BENCH"], int(os.environ["SMALL_N"]), int(os.environ["LARGE_N"])
key = "bench-key-0123456789abcdef"

def relay(m, cfg):
    path = os.path.join(m.log_dir, m.name + "-relay.yaml")
    yaml.safe_dump(cfg, open(path, "w"))
    m.call(["rosparam", "load", path, "/relay"])
    # relay_node started as roslaunch starts it (by path: rosrun's own start-up is not the relay's); line-buffered
    # output: the link-up line is read while the relay runs
    return m.run(["stdbuf", "-oL", os.path.join(os.environ["WS"], "devel/lib/offshore_gnc/relay_node"), "__name:=relay"],
                 name="relay")

WARMUP = 20  # messages before the measured ones: the relayed path advertises on its first message

def sub(m, topic, n, name, timeout=60, warmup=WARMUP):
    return subprocess.Popen([bench, "sub", "--topic", topic, "--count", str(n), "--timeout", str(timeout),
                             "--warmup", str(warmup)],
                            env=m.env(), stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, start_new_session=True)

def result(p):
    out = p.communicate(timeout=120)[0].decode().strip().splitlines()
    return json.loads(out[-1])

def pub(m, topic, size, n, rate, subs):
    return subprocess.run([bench, "pub", "--topic", topic, "--size", str(size), "--count", str(n), "--rate",
                           str(rate), "--subs", str(subs), "--warmup", str(WARMUP)], env=m.env(), stdout=subprocess.DEVNULL,
                          stderr=subprocess.DEVNULL, timeout=300)

port = free_port()
topics = [{"topic": t, "type": "sensor_msgs/PointCloud2"}
          for t in ("/bench/small", "/bench/large", "/bench/first")]
with MasterSet(["a", "b"]) as ms:
    a, b = ms["a"], ms["b"]
    relay(a, {"name": "a", "listen_port": port, "key": key, "sim": True, "peers": [{"name": "b"}],
              "topics": [dict(t, direction="out") for t in topics]})
    b_cfg = {"name": "b", "key": key, "sim": True, "peers": [{"name": "a", "address": "127.0.0.1:%d" % port}],
             "topics": [dict(t, direction="in") for t in topics]}
    rb = relay(b, b_cfg)
    # small: the same messages to a subscriber on the publisher's master and one through the relay
    s_direct, s_relay = sub(a, "/bench/small", small_n, "d"), sub(b, "/bench/small", small_n, "r")
    pub(a, "/bench/small", 100, small_n, 500, 2)
    d, r = result(s_direct), result(s_relay)
    # large: 1 MB point clouds as fast as they go
    l_direct, l_relay = sub(a, "/bench/large", large_n, "ld"), sub(b, "/bench/large", large_n, "lr")
    pub(a, "/bench/large", 1 << 20, large_n, 0, 2)
    ld, lr = result(l_direct), result(l_relay)
    # first message on one master, for comparison: a subscriber waits, a publisher process starts at t0d and
    # publishes as soon as the subscriber is connected (what ROS itself needs for a first message)
    d_sub = sub(a, "/bench/first_direct", 1, "fd", timeout=20, warmup=0)
    time.sleep(1.0)
    t0d = time.time()
    d_pub = subprocess.Popen([bench, "pub", "--topic", "/bench/first_direct", "--size", "100", "--count", "2000",
                              "--rate", "100", "--subs", "1", "--settle", "0"], env=a.env(), stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL, start_new_session=True)
    fd = result(d_sub)
    d_pub.kill()
    first_direct_s = fd["first_wall"] - t0d if fd["received"] else -1
    # first message through the relay: a publisher and a subscriber wait; the far relay starts at t0
    rb.send_signal(2); rb.wait(10)
    f_sub = sub(b, "/bench/first", 1, "f", timeout=20, warmup=0)
    f_pub = subprocess.Popen([bench, "pub", "--topic", "/bench/first", "--size", "100", "--count", "2000",
                              "--rate", "100", "--subs", "1"], env=a.env(), stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL, start_new_session=True)
    time.sleep(2.0)
    t0 = time.time()
    relay(b, b_cfg)
    f = result(f_sub)
    time.sleep(0.3)
    f_pub.kill()
    first_s = f["first_wall"] - t0 if f["received"] else -1
    # the same from the moment the link came up (the far relay's log line, ROS time = wall time here)
    import re
    ups = re.findall(r"\[(\d+\.\d+)\]: link to a up", open(b.log_path("relay"), errors="replace").read())
    link_s = f["first_wall"] - max(map(float, ups)) if ups and f["received"] else -1
print("small 100 B x %d @500 Hz: one master p50 %.3f ms p99 %.3f ms; relayed p50 %.3f ms p99 %.3f ms (%d/%d received)"
      % (small_n, d["p50_ms"], d["p99_ms"], r["p50_ms"], r["p99_ms"], r["received"], small_n))
print("large 1 MB x %d: one master %.1f MB/s (%d received); relayed %.1f MB/s (%d received), HMAC-SHA256 on"
      % (large_n, ld["MBps"], ld["received"], lr["MBps"], lr["received"]))
print("first message %.3f s after starting the far relay process (includes its start-up), %.3f s after link-up;"
      " one master: %.3f s after starting the publisher process" % (first_s, link_s, first_direct_s))
print(json.dumps({
    "added_p50_ms_small": round(r["p50_ms"] - d["p50_ms"], 4), "added_p99_ms_small": round(r["p99_ms"] - d["p99_ms"], 4),
    "direct_p50_ms_small": d["p50_ms"], "direct_p99_ms_small": d["p99_ms"],
    "warmup_messages": WARMUP, "relay_p50_ms_small": r["p50_ms"], "relay_p99_ms_small": r["p99_ms"], "small_received": r["received"],
    "throughput_MBps_large": lr["MBps"], "direct_MBps_large": ld["MBps"], "large_received": lr["received"],
    "first_message_s": round(first_s, 3), "first_message_after_link_up_s": round(link_s, 3),
    "first_message_direct_s": round(first_direct_s, 3)}))
PY

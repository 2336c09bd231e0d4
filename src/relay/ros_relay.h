#pragma once
// The ROS side of the multi-master relay, shared by the Relay nodelet and the relay_node executable: loads the
// configuration (a YAML file loaded as parameters), subscribes to the out-topics with topic_tools::ShapeShifter
// (any type), hands serialized messages to the ROS-free relay::Engine, publishes what arrives from the peers
// (latched where configured) and reports link health on /relay/link_status and /diagnostics.
#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <topic_tools/shape_shifter.h>

#include <map>
#include <memory>
#include <mutex>
#include <sstream>

#include "offshore_gnc/LinkStatus.h"
#include "offshore_gnc/relay/engine.h"
#include "offshore_gnc/relay/key.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/ros/site.h"

namespace offshore_gnc {

namespace relay_ros {

inline std::string member(XmlRpc::XmlRpcValue& v, const std::string& key, const std::string& where, bool required,
                   const std::string& def = "") {
  if (!v.hasMember(key)) {
    if (required) throw ConfigError("relay config: " + where + " needs '" + key + "'");
    return def;
  }
  if (v[key].getType() != XmlRpc::XmlRpcValue::TypeString)
    throw ConfigError("relay config: " + where + "/" + key + " must be a string");
  return static_cast<std::string>(v[key]);
}

inline double number(XmlRpc::XmlRpcValue& v, const std::string& key, double def, const std::string& where) {
  if (!v.hasMember(key)) return def;
  XmlRpc::XmlRpcValue& x = v[key];
  if (x.getType() == XmlRpc::XmlRpcValue::TypeInt) return static_cast<int>(x);
  if (x.getType() == XmlRpc::XmlRpcValue::TypeDouble) return static_cast<double>(x);
  throw ConfigError("relay config: " + where + "/" + key + " must be a number");
}

inline bool flag(XmlRpc::XmlRpcValue& v, const std::string& key, bool def, const std::string& where) {
  if (!v.hasMember(key)) return def;
  if (v[key].getType() != XmlRpc::XmlRpcValue::TypeBoolean)
    throw ConfigError("relay config: " + where + "/" + key + " must be true or false");
  return static_cast<bool>(v[key]);
}

// Calls f(entry, "key[i]") for each entry of the list parameter `key` (entries must be maps).
template <class F>
inline void forEachEntry(const ros::NodeHandle& pnh, const std::string& key, F f) {
  XmlRpc::XmlRpcValue list;
  if (!pnh.getParam(key, list)) return;
  if (list.getType() != XmlRpc::XmlRpcValue::TypeArray) throw ConfigError("relay config: '" + key + "' must be a list");
  for (int i = 0; i < list.size(); ++i) {
    const std::string where = key + "[" + std::to_string(i) + "]";
    if (list[i].getType() != XmlRpc::XmlRpcValue::TypeStruct)
      throw ConfigError("relay config: " + where + " must be a map");
    f(list[i], where);
  }
}

inline relay::RelayConfig loadConfig(const ros::NodeHandle& pnh) {
  ros_util::ParamReader p(pnh);
  relay::RelayConfig c;
  c.name = p.text("name", "");
  c.listen_host = p.text("listen_host", "127.0.0.1");
  c.listen_port = p.integer("listen_port", 0, -1, 65535);
  c.auth = p.choice("auth", "hmac-sha256", {"hmac-sha256", "none"}) == "hmac-sha256";
  c.key = p.text("key", "");
  const std::string key_file = p.text("key_file", "");
  if (c.auth && c.key.empty() && !key_file.empty()) c.key = relay::readKeyFile(key_file);
  c.sim = p.flag("sim", false);
  c.heartbeat_period = p.number("heartbeat_period", 0.2, 0.01, 10.0);
  c.link_timeout = p.number("link_timeout", 1.0, 0.02, 60.0);
  c.ack_delay = p.number("ack_delay", 0.5, 0.0, 10.0);
  c.backoff_min = p.number("backoff_min", 0.1, 0.01, 10.0);
  c.backoff_max = p.number("backoff_max", 2.0, 0.01, 60.0);
  c.queue_messages = static_cast<std::size_t>(p.integer("queue/max_messages", 1000, 1, 1000000));
  c.queue_bytes = static_cast<std::size_t>(p.number("queue/max_bytes", 64.0 * (1 << 20), 1024, 4e9));
  c.max_frame_bytes = static_cast<std::size_t>(p.number("max_frame_bytes", 32.0 * (1 << 20), 1024, 1 << 30));
  c.udp = p.flag("udp", true);
  c.max_datagram_bytes = static_cast<std::size_t>(p.number("max_datagram_bytes", 60000, 512, 65000));
  c.origin = ros_util::readOrigin();  // announced at link-up: the peer vehicle must run on the same site
  c.origin_tolerance = p.number("origin_tolerance", c.origin_tolerance, 0.0, 1e4);
  forEachEntry(pnh, "peers", [&c](XmlRpc::XmlRpcValue& e, const std::string& where) {
    relay::PeerConfig pc;
    pc.name = member(e, "name", where, true);
    const std::string addr = member(e, "address", where, false);
    if (!addr.empty()) {
      const auto colon = addr.rfind(':');
      if (colon == std::string::npos) throw ConfigError("relay config: " + where + "/address must be host:port");
      pc.host = addr.substr(0, colon);
      try {
        pc.port = std::stoi(addr.substr(colon + 1));
      } catch (const std::exception&) {
        throw ConfigError("relay config: " + where + "/address '" + addr + "' has no valid port");
      }
    }
    c.peers.push_back(pc);
  });
  forEachEntry(pnh, "topics", [&c](XmlRpc::XmlRpcValue& e, const std::string& where) {
    relay::TopicConfig t;
    t.topic = member(e, "topic", where, true);
    t.type = member(e, "type", where, true);
    t.direction = member(e, "direction", where, true);
    t.remote = member(e, "remote", where, false);
    t.reliable = flag(e, "reliable", true, where);
    t.latched = flag(e, "latched", false, where);
    t.compress = flag(e, "compress", false, where);
    t.rate_hz = number(e, "rate_hz", 0.0, where);
    if (e.hasMember("peers")) {
      XmlRpc::XmlRpcValue& l = e["peers"];
      if (l.getType() != XmlRpc::XmlRpcValue::TypeArray) throw ConfigError("relay config: " + where + "/peers must be a list");
      for (int j = 0; j < l.size(); ++j) {
        if (l[j].getType() != XmlRpc::XmlRpcValue::TypeString)
          throw ConfigError("relay config: " + where + "/peers must be a list of names");
        t.peers.push_back(static_cast<std::string>(l[j]));
      }
    }
    c.topics.push_back(t);
  });
  relay::validate(c);
  return c;
}

// Number of subscribers the master knows for `topic` (so that the first relayed message reaches them).
inline int masterSubscribers(const std::string& topic) {
  XmlRpc::XmlRpcValue req, res, payload;
  req[0] = ros::this_node::getName();
  if (!ros::master::execute("getSystemState", req, res, payload, false)) return 0;
  if (payload.getType() != XmlRpc::XmlRpcValue::TypeArray || payload.size() < 2) return 0;
  XmlRpc::XmlRpcValue& subs = payload[1];
  for (int i = 0; i < subs.size(); ++i)
    if (static_cast<std::string>(subs[i][0]) == topic) return subs[i][1].size();
  return 0;
}

}  // namespace relay_ros

class RelayRos {
 public:
  ~RelayRos() {
    if (engine_) engine_->stop();
  }

  // Loads the configuration from pnh (a ConfigError names the bad key), subscribes, advertises and starts
  // the engine; `name` is the node's (or nodelet's) name for diagnostics.
  void start(ros::NodeHandle nh, ros::NodeHandle pnh, const std::string& name) {
    nh_ = nh;
    relay::RelayConfig cfg;
    double status_period = 1.0;
    try {
      cfg = relay_ros::loadConfig(pnh);
      status_period = ros_util::ParamReader(pnh).number("status_period", 1.0, 0.05, 60.0);
    } catch (const ConfigError& e) {
      ROS_FATAL("%s", e.what());
      throw;
    }
    in_.clear();
    for (std::size_t i = 0; i < cfg.topics.size(); ++i) in_.push_back(std::make_unique<InTopic>());
    relay::Callbacks cb;
    cb.on_announce = [this](std::size_t i, const std::string& peer, const relay::Announce& a) {
      return onAnnounce(i, peer, a);
    };
    cb.on_message = [this](std::size_t i, const std::string&, const std::vector<std::uint8_t>& d) { onMessage(i, d); };
    cb.on_log = [this](int level, const std::string& s) {
      // Throttled per text (not per call site): one refusal must not hide another topic's.
      {
        std::lock_guard<std::mutex> lock(log_mutex_);
        const ros::WallTime now = ros::WallTime::now();
        auto it = last_logged_.find(s);
        if (it != last_logged_.end() && (now - it->second).toSec() < 1.0) return;
        if (last_logged_.size() > 1000) last_logged_.clear();  // bounded
        last_logged_[s] = now;
      }
      if (level >= 2)
        ROS_ERROR("%s", s.c_str());
      else if (level == 1)
        ROS_WARN("%s", s.c_str());
      else
        ROS_INFO("%s", s.c_str());
    };
    if (cfg.auth) key_fingerprint_ = relay::keyFingerprint(cfg.key);
    if (!cfg.auth && !cfg.sim) ROS_WARN("relay '%s': authentication is off (auth: none) on hardware", cfg.name.c_str());
    engine_ = std::make_unique<relay::Engine>(cfg, cb, counters_);
    for (std::size_t i = 0; i < cfg.topics.size(); ++i) {
      const auto& t = cfg.topics[i];
      if (t.direction != "out") continue;
      subs_.push_back(nh.subscribe<topic_tools::ShapeShifter>(
          t.topic, 100, [this, i](const ros::MessageEvent<topic_tools::ShapeShifter const>& ev) { onLocal(i, ev); },
          ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay()));
    }
    link_pub_ = nh.advertise<LinkStatus>("/relay/link_status", 10);
    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, pnh, name);
    updater_->setHardwareID("relay/" + cfg.name);
    updater_->add("link", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      int up = 0;
      for (const auto& l : last_status_) up += l.up;
      if (up == static_cast<int>(last_status_.size()))
        s.summary(diagnostic_msgs::DiagnosticStatus::OK, "all links up");
      else
        s.summary(diagnostic_msgs::DiagnosticStatus::WARN, std::to_string(last_status_.size() - up) + " link(s) down");
      for (const auto& l : last_status_)
        if (!l.refused.empty()) s.mergeSummary(diagnostic_msgs::DiagnosticStatus::ERROR, l.refused);
      ros_util::addCounters(s, counters_, {"origin_mismatch", "frames_bad_auth", "frames_malformed", "frames_oversized", "frames_replayed",
                                           "unknown_topic", "queue_overflow", "refused_type_mismatch", "udp_datagrams",
                                           "udp_lost", "udp_malformed", "udp_unknown_source", "connections_refused",
                                           "connections_evicted", "announces_over_limit", "announces_repeated",
                                           "replies_dropped"});
      if (!key_fingerprint_.empty()) s.add("key", key_fingerprint_);
    });
    try {
      engine_->start();
    } catch (const std::exception& e) {
      ROS_FATAL("%s", e.what());
      throw;
    }
    if (cfg.listen_port != 0) {
      ROS_INFO("relay '%s' listening on %s:%d", cfg.name.c_str(), cfg.listen_host.c_str(), engine_->listenPort());
      pnh.setParam("bound_port", engine_->listenPort());
    }
    timer_ = nh.createWallTimer(ros::WallDuration(status_period), [this](const ros::WallTimerEvent&) { publishStatus(); });
  }

 private:
  struct InTopic {
    std::mutex mutex;
    ros::Publisher pub;
    relay::TypeInfo info;
    bool latched = false;
  };

  void onLocal(std::size_t i, const ros::MessageEvent<topic_tools::ShapeShifter const>& ev) {
    const auto& msg = ev.getConstMessage();
    relay::TypeInfo ti{msg->getDataType(), msg->getMD5Sum(), msg->getMessageDefinition()};
    auto buf = std::make_shared<std::vector<std::uint8_t>>(msg->size());
    ros::serialization::OStream s(buf->data(), static_cast<std::uint32_t>(buf->size()));
    msg->write(s);
    engine_->publish(i, ti, buf);
  }

  std::string onAnnounce(std::size_t i, const std::string& peer, const relay::Announce& a) {
    const auto& t = engine_->config().topics[i];
    if (a.info.type != t.type)
      return "topic " + t.topic + " from " + peer + ": type " + a.info.type + " differs from the configured " + t.type +
             "; refused";
    InTopic& in = *in_[i];
    std::lock_guard<std::mutex> lock(in.mutex);
    if (!in.info.md5.empty()) {
      if (in.info.md5 != a.info.md5)
        return "topic " + t.topic + " from " + peer + ": md5sum " + a.info.md5 + " of " + a.info.type +
               " differs from " + in.info.md5 + " (different message definitions); refused";
      return "";
    }
    in.info = a.info;
    in.latched = t.latched || a.latched;
    topic_tools::ShapeShifter ss;
    ss.morph(a.info.md5, a.info.type, a.info.definition, in.latched ? "1" : "0");
    in.pub = ss.advertise(nh_, t.topic, 10000, in.latched);  // room for a resend burst after a reconnect
    // The first message is never lost: wait until the subscribers the master knows have connected.
    const int want = relay_ros::masterSubscribers(t.topic);
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(1.0);
    while (static_cast<int>(in.pub.getNumSubscribers()) < want && ros::WallTime::now() < deadline && ros::ok())
      ros::WallDuration(0.002).sleep();
    if (static_cast<int>(in.pub.getNumSubscribers()) < want)
      ROS_WARN("%s: %u of %d subscribers connected after 1 s; relaying anyway", t.topic.c_str(),
                   in.pub.getNumSubscribers(), want);
    ROS_INFO("relaying %s (%s) from %s%s", t.topic.c_str(), a.info.type.c_str(), peer.c_str(),
                 in.latched ? ", latched" : "");
    return "";
  }

  void onMessage(std::size_t i, const std::vector<std::uint8_t>& d) {
    InTopic& in = *in_[i];
    std::lock_guard<std::mutex> lock(in.mutex);
    topic_tools::ShapeShifter ss;
    ss.morph(in.info.md5, in.info.type, in.info.definition, in.latched ? "1" : "0");
    ros::serialization::IStream s(const_cast<std::uint8_t*>(d.data()), static_cast<std::uint32_t>(d.size()));
    ss.read(s);
    in.pub.publish(ss);
  }

  void publishStatus() {
    last_status_ = engine_->status();
    const std::string& me = engine_->config().name;
    for (const auto& ps : last_status_) {
      LinkStatus m;
      m.header.stamp = ros::Time::now();
      m.local_name = me;
      m.peer_name = ps.name;
      m.peer_address = ps.address;
      m.up = ps.up;
      m.rtt = ps.rtt;
      m.loss = ps.loss;
      m.reconnects = ps.reconnects;
      m.frames_rejected = ps.frames_rejected;
      m.refused = ps.refused;
      for (const auto& t : ps.topics) {
        TopicStats ts;
        ts.topic = t.topic;
        ts.remote_topic = t.remote;
        ts.direction = t.direction;
        ts.transport = t.transport;
        ts.messages = t.messages;
        ts.bytes = t.bytes;
        ts.dropped = t.dropped;
        ts.rate_hz = t.rate_hz;
        ts.bandwidth_bps = t.bandwidth_bps;
        m.topics.push_back(ts);
      }
      link_pub_.publish(m);
    }
    updater_->force_update();
  }

  ros::NodeHandle nh_;
  Counters counters_;
  std::unique_ptr<relay::Engine> engine_;
  std::vector<std::unique_ptr<InTopic>> in_;
  std::vector<ros::Subscriber> subs_;
  ros::Publisher link_pub_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  std::vector<relay::PeerStatus> last_status_;
  std::mutex log_mutex_;
  std::map<std::string, ros::WallTime> last_logged_;
  std::string key_fingerprint_;  // diagnostics: both ends show the same one when their keys match
  ros::WallTimer timer_;
};

}  // namespace offshore_gnc

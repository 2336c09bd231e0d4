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

// The configuration from the private parameters, every value through relay/config.h's tables.
inline relay::RelayConfig loadConfig(const ros::NodeHandle& pnh) {
  relay::RelayConfig c;
  ros_util::readParams(ros_util::ParamReader(pnh), relay::RelayConfig::table(), c);
  if (c.authenticated() && c.key.empty() && !c.key_file.empty()) c.key = relay::readKeyFile(c.key_file);
  c.origin = ros_util::readOrigin();  // announced at link-up: the peer vehicle must run on the same site
  auto entries = [&pnh](const std::string& key, auto f) {
    XmlRpc::XmlRpcValue list;
    if (!pnh.getParam(key, list)) return;
    if (list.getType() != XmlRpc::XmlRpcValue::TypeArray) throw ConfigError("relay config: '" + key + "' must be a list");
    for (int i = 0; i < list.size(); ++i) f(list[i], key + "[" + std::to_string(i) + "]");
  };
  entries("peers", [&c](XmlRpc::XmlRpcValue& e, const std::string& where) {
    relay::PeerEntry pe;
    ros_util::readEntry(e, relay::PeerEntry::table(), pe, where);
    c.peers.push_back(pe.toConfig(where));
  });
  entries("topics", [&c](XmlRpc::XmlRpcValue& e, const std::string& where) {
    relay::TopicConfig t;
    ros_util::readEntry(e, relay::TopicConfig::table(), t, where);
    if (e.hasMember("peers")) {  // a list of names: beside the table
      XmlRpc::XmlRpcValue& l = e["peers"];
      if (l.getType() != XmlRpc::XmlRpcValue::TypeArray) throw ConfigError("relay config: " + where + "/peers must be a list");
      for (int j = 0; j < l.size(); ++j) t.peers.push_back(ros_util::entryText(l[j], where + "/peers"));
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
    try {
      cfg = relay_ros::loadConfig(pnh);
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
    if (cfg.authenticated()) key_fingerprint_ = relay::keyFingerprint(cfg.key);
    if (!cfg.authenticated() && !cfg.sim) ROS_WARN("relay '%s': authentication is off (auth: none) on hardware", cfg.name.c_str());
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
    timer_ = nh.createWallTimer(ros::WallDuration(cfg.status_period), [this](const ros::WallTimerEvent&) { publishStatus(); });
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

// The relay against what anyone on the radio link can send: deployment keys (no published or weak key on
// hardware), the fuzz entry points over random scripts, and floods (half-open connections, oversized frames before
// authentication, an authenticated peer announcing thousands of topics and pinging without reading).
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <openssl/evp.h>
#include <openssl/rand.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <fstream>
#include <mutex>
#include <random>
#include <thread>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/relay/engine.h"
#include "relay/fuzz_check.h"
#include "offshore_gnc/relay/key.h"

using namespace offshore_gnc;
using namespace offshore_gnc::relay;

namespace {

std::string randomBase64(int bytes) {
  std::vector<unsigned char> raw(bytes), out(4 * ((bytes + 2) / 3) + 1);
  EXPECT_EQ(RAND_bytes(raw.data(), bytes), 1);
  const int n = EVP_EncodeBlock(out.data(), raw.data(), bytes);
  return std::string(reinterpret_cast<char*>(out.data()), n);
}

int connectTo(int port) {
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  inet_pton(AF_INET, "127.0.0.1", &a.sin_addr);
  if (connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0) {
    close(fd);
    return -1;
  }
  return fd;
}

template <class F>
bool eventually(F f, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (f()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return f();
}

const TypeInfo kString{"std_msgs/String", "992ce8a1687cec8c8bd883ec73ca41d1", "string data"};

struct Inbox {
  std::mutex m;
  std::vector<std::string> msgs;
  std::size_t size() {
    std::lock_guard<std::mutex> l(m);
    return msgs.size();
  }
};

Callbacks inboxCallbacks(Inbox& in) {
  Callbacks cb;
  cb.on_announce = [](std::size_t, const std::string&, const Announce&) { return std::string(); };
  cb.on_message = [&in](std::size_t, const std::string&, const std::vector<std::uint8_t>& d) {
    std::lock_guard<std::mutex> l(in.m);
    in.msgs.emplace_back(d.begin(), d.end());
  };
  return cb;
}

// The USV side: listens, accepts /chat from auv; "rogue" is a configured peer that holds the key (an insider or
// a stolen key) and misbehaves.
RelayConfig listener(const std::string& key) {
  RelayConfig c;
  c.name = "usv";
  c.key = key;
  c.listen_port = -1;
  c.heartbeat_period = 0.05;
  c.link_timeout = 0.5;
  c.ack_delay = 0.05;
  c.peers = {{"auv", "", 0}, {"rogue", "", 0}};
  c.topics = {{"/chat", "std_msgs/String", "in", "", {"auv"}, true, 0.0, false, false}};
  return c;
}

RelayConfig dialler(const std::string& key, int port) {
  RelayConfig c;
  c.name = "auv";
  c.key = key;
  c.heartbeat_period = 0.05;
  c.link_timeout = 0.5;
  c.backoff_min = 0.02;
  c.backoff_max = 0.1;
  c.peers = {{"usv", "127.0.0.1", port}};
  c.topics = {{"/chat", "std_msgs/String", "out", "", {}, true, 0.0, false, false}};
  return c;
}

}  // namespace

TEST(RelayKey, TheShippedSimulationKeyIsRefusedOnHardware) {
  const std::string sim = readKeyFile("config/relay/sim.key");  // gtests run in the package folder
  EXPECT_NE(deploymentKeyProblem(sim).find("simulation key"), std::string::npos) << deploymentKeyProblem(sim);
  RelayConfig c = listener(sim);
  c.sim = false;
  try {
    validate(c);
    FAIL() << "the published simulation key was accepted on hardware";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("simulation key"), std::string::npos) << what;
    EXPECT_NE(what.find("scripts/relay-key"), std::string::npos) << what;  // says how to make a key
  }
  c.sim = true;
  EXPECT_NO_THROW(validate(c));
}

TEST(RelayKey, OnlyThirtyTwoRandomBytesOrMorePass) {
  EXPECT_EQ(deploymentKeyProblem(randomBase64(32)), "");  // what scripts/relay-key writes
  EXPECT_EQ(deploymentKeyProblem(randomBase64(48)), "");
  std::string hex;
  for (unsigned char ch : randomBase64(48).substr(0, 32)) hex += "0123456789abcdef"[ch % 16], hex += "fedcba9876543210"[ch / 16 % 16];
  EXPECT_EQ(deploymentKeyProblem(hex), "") << hex;  // 64 hex digits
  EXPECT_NE(deploymentKeyProblem(randomBase64(24)).find("24 bytes"), std::string::npos);  // as long as sim.key
  EXPECT_NE(deploymentKeyProblem("correct horse battery staple, a long passphrase").find("hex or base64"),
            std::string::npos);
  EXPECT_NE(deploymentKeyProblem(std::string(64, '0')).find("pattern"), std::string::npos);
  EXPECT_NE(deploymentKeyProblem(std::string(44, 'Q')).find("pattern"), std::string::npos);  // base64 of 3 values
  EXPECT_NE(deploymentKeyProblem("").find("hex or base64"), std::string::npos);
  // the relay's own validation uses the same rule
  RelayConfig c = listener("0123456789abcdef-long-enough-for-sim");
  c.sim = false;
  EXPECT_THROW(validate(c), ConfigError);
  c.key = randomBase64(32);
  EXPECT_NO_THROW(validate(c));
  // fingerprints: what scripts/relay-key prints (SHA-256 of the key text), never the key
  EXPECT_EQ(keyFingerprint("abc"), "sha256:ba7816bf8f01cfea");
}

TEST(RelayKey, KeyFileFirstLineTrimmedAndErrorsNameTheFile) {
  const std::string path = ::testing::TempDir() + "relay_key_test.key";
  std::ofstream(path) << "  " << "k3y-text\r\nsecond line\n";
  EXPECT_EQ(readKeyFile(path), "k3y-text");
  std::ofstream(path) << "\n";
  EXPECT_THROW(readKeyFile(path), ConfigError);
  try {
    readKeyFile(path + ".missing");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(".missing"), std::string::npos);
  }
}

// The libFuzzer targets' entry points over random and mutated inputs (the long runs: scripts/fuzz).
TEST(RelayFuzz, WireInvariantsOnRandomAndMutatedFrames) {
  std::mt19937 rng(11);
  std::vector<std::uint8_t> valid;
  FrameHeader h;
  h.type = FrameType::Data;
  const std::uint8_t p[5] = {1, 2, 3, 4, 5};
  for (int i = 0; i < 4; ++i) encodeFrame(h, p, 5, Authenticator(), valid);
  for (int i = 0; i < 3000; ++i) {
    std::vector<std::uint8_t> in = valid;
    if (i % 3 == 0) in.resize(rng() % 300);
    for (auto& b : in) {
      if (i % 3 == 0 || rng() % 40 == 0) b = static_cast<std::uint8_t>(rng());
    }
    ASSERT_EQ(fuzzWireOnce(in.data(), in.size()), "") << i;
  }
}

TEST(RelayFuzz, SessionInvariantsOnRandomScripts) {
  // A script that authenticates, announces, sends data and replays it, then random variations of it.
  const std::vector<std::uint8_t> hello = {1, 0, 0, 1, 0, 0, 0};
  std::vector<std::uint8_t> base = hello;
  const std::vector<std::uint8_t> tail = {4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 1, 2, 3, 4,  // ping
                                          2, 0, 0, 0, 0,                                       // announce /target
                                          3, 0, 2, 0, 0, 3, 'a', 'b', 'c',                     // reliable data
                                          5, 3, 0, 8, 0};                                      // replay, reconnect
  base.insert(base.end(), tail.begin(), tail.end());
  ASSERT_EQ(fuzzSessionOnce(base.data(), base.size()), "");
  std::mt19937 rng(5);
  for (int i = 0; i < 600; ++i) {
    std::vector<std::uint8_t> in = base;
    const int edits = 1 + static_cast<int>(rng() % 6);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = rng() % in.size();
      switch (rng() % 3) {
        case 0: in[at] = static_cast<std::uint8_t>(rng()); break;
        case 1: in.insert(in.begin() + static_cast<long>(at), static_cast<std::uint8_t>(rng())); break;
        default: in.insert(in.end(), in.begin(), in.begin() + static_cast<long>(at)); break;
      }
    }
    ASSERT_EQ(fuzzSessionOnce(in.data(), in.size()), "") << "script " << i;
  }
}

TEST(RelayLimits, HalfOpenAndOversizedConnectionsStayBoundedAndARealPeerStillGetsIn) {
  const std::string key = randomBase64(32);
  Counters cu, ca;
  Inbox in, unused;
  RelayConfig lc = listener(key);
  lc.link_timeout = 2.0;  // half-open connections live 4 s: longer than this test needs
  Engine usv(lc, inboxCallbacks(in), cu);
  usv.start();
  const std::size_t cap = 4 * lc.peers.size() + 8;
  // 60 connections that never say anything
  std::vector<int> half_open;
  for (int i = 0; i < 60; ++i) half_open.push_back(connectTo(usv.listenPort()));
  ASSERT_TRUE(eventually([&] { return cu.get("connections_evicted") >= 60 - cap; }, 10.0)) << cu.get("connections_evicted");
  EXPECT_LE(usv.memoryUse().connections, cap);
  // a frame header promising 1 MiB before any hello: refused at the header, never buffered
  const int big = connectTo(usv.listenPort());
  std::vector<std::uint8_t> hdr(kHeaderSize, 0);
  hdr[0] = 0x4F, hdr[1] = 0x47, hdr[2] = 0x52, hdr[3] = 0x31, hdr[4] = 1;
  hdr[26] = 0x10;  // length 1 MiB
  ASSERT_EQ(send(big, hdr.data(), hdr.size(), MSG_NOSIGNAL), static_cast<ssize_t>(hdr.size()));
  const std::vector<std::uint8_t> filler(256 << 10, 0x55);
  (void)!send(big, filler.data(), filler.size(), MSG_NOSIGNAL);
  ASSERT_TRUE(eventually([&] { return cu.get("frames_oversized") >= 1; }, 5.0));
  EXPECT_LT(usv.memoryUse().input_bytes, 64u << 10);
  close(big);
  // the real peer connects through the flood (it evicts the oldest connection without a link) and delivers
  Engine auv(dialler(key, usv.listenPort()), inboxCallbacks(unused), ca);
  auv.start();
  for (int i = 0; i < 20; ++i) auv.publish(0, kString, std::make_shared<const std::vector<std::uint8_t>>(4, 'a' + i));
  EXPECT_TRUE(eventually([&] { return in.size() >= 20; }, 10.0)) << in.size();
  EXPECT_LE(usv.memoryUse().connections, cap);
  for (int fd : half_open)
    if (fd >= 0) close(fd);
}

TEST(RelayLimits, AnInsiderFloodingAnnouncesAndPingsStaysBounded) {
  const std::string key = randomBase64(32);
  Counters cu;
  Inbox in;
  std::vector<std::string> logs;
  std::mutex log_m;
  Callbacks cb = inboxCallbacks(in);
  cb.on_log = [&](int, const std::string& s) {
    std::lock_guard<std::mutex> l(log_m);
    logs.push_back(s);
  };
  RelayConfig lc = listener(key);
  lc.link_timeout = 60.0;  // the rogue never answers heartbeats; the link must stay up through the test
  Engine usv(lc, cb, cu);
  usv.start();
  ScriptedPeer rogue(connectTo(usv.listenPort()), key);
  ASSERT_EQ(rogue.receive(2.0), "");
  ASSERT_TRUE(rogue.haveEngineHello());
  rogue.hello(ScriptedPeer::helloPayload(kWireVersion, "rogue", 99, rogue.nonce()));
  FrameHeader ping;
  ping.type = FrameType::Ping;
  rogue.frame(ping, std::vector<std::uint8_t>(16, 0));
  ASSERT_TRUE(eventually([&] { return usv.status()[1].up; }, 5.0));
  // 3000 topics (distinct ids and names, 2 KiB definitions each): 1024 are remembered, the rest counted
  const std::string def(2048, 'd');
  for (int i = 0; i < 3000; ++i) {
    FrameHeader h;
    h.type = FrameType::Announce;
    h.topic_id = static_cast<std::uint16_t>(i);
    rogue.frame(h, ScriptedPeer::announcePayload("/flood/" + std::to_string(i), "std_msgs/String", "x", def, false, true));
    if (i % 500 == 0) {
      ASSERT_EQ(rogue.receive(), "");
    }
  }
  // the same announce again and again: nothing new, nothing logged
  for (int i = 0; i < 500; ++i) {
    FrameHeader h;
    h.type = FrameType::Announce;
    rogue.frame(h, ScriptedPeer::announcePayload("/flood/0", "std_msgs/String", "x", def, false, true));
  }
  ASSERT_TRUE(eventually([&] { return cu.get("announces_over_limit") + cu.get("announces_repeated") >= 2476; }, 20.0))
      << cu.get("announces_over_limit") << " " << cu.get("announces_repeated");
  EXPECT_EQ(cu.get("announces_over_limit"), 3000u - 1024u);
  EXPECT_EQ(usv.memoryUse().remote_topics, 1024u);
  EXPECT_EQ(cu.get("refused_not_configured"), 1024u);
  {
    std::lock_guard<std::mutex> l(log_m);
    EXPECT_LT(logs.size(), 60u) << "refusals are logged at about 1 Hz, not per frame";
  }
  // pings without ever reading the pongs: the replies stop once 8 MiB wait, and memory stays there. How many pongs
  // the kernel's socket buffers take first depends on the machine (a fixed 250,000 pings, 20 MB of pongs, left the
  // engine under its 8 MiB on one): ping until the engine drops replies, up to 4,000,000 (320 MB of pongs).
  std::size_t pings = 0;
  for (; pings < 4000000 && cu.get("replies_dropped") == 0; pings += 1000)
    for (int i = 0; i < 1000; ++i) rogue.frame(ping, std::vector<std::uint8_t>(16, 1));
  ASSERT_TRUE(eventually([&] { return cu.get("replies_dropped") > 0; }, 30.0))
      << pings << " pings, " << usv.memoryUse().output_bytes << " bytes waiting";
  const MemoryUse m = usv.memoryUse();
  EXPECT_LE(m.output_bytes, 17u << 20);  // at most 8 MiB waiting, in a buffer of at most twice that
  EXPECT_LE(m.input_bytes, 4u << 20);
  // the engine still serves: everything the rogue was sent authenticates, and the link is up
  EXPECT_EQ(rogue.receive(1.0), "");
  std::string log_text;
  {
    std::lock_guard<std::mutex> l(log_m);
    for (const auto& s : logs) log_text += s + "\n";
  }
  EXPECT_GT(rogue.framesReceived(FrameType::Pong), 1000u) << log_text;
  EXPECT_TRUE(usv.status()[1].up) << log_text;
}

// The relay engine's stages on their own: the handshake's hello and session keys, the receiving end of reliable
// delivery, the redial backoff, heartbeats, what a peer has announced, the link statistics.
#include <gtest/gtest.h>

#include <cmath>

#include "offshore_gnc/relay/handshake.h"
#include "offshore_gnc/relay/policy.h"
#include "offshore_gnc/relay/reliable.h"
#include "offshore_gnc/relay/routing.h"
#include "offshore_gnc/relay/stats.h"

using namespace offshore_gnc;
using namespace offshore_gnc::relay;

TEST(RelayHandshake, HelloRoundTripAndRefusals) {
  Hello h;
  h.name = "auv";
  h.session = 0x1234567890abcdefull;
  h.nonce = freshNonce();
  h.ack_session = 7;
  h.ack_seq = 42;
  h.udp_port = 11411;
  h.origin = geo::LatLonAlt{61.5, 24.2, 80.0};
  const auto b = encodeHello(h);
  Hello back;
  ASSERT_TRUE(decodeHello(b, back));
  EXPECT_EQ(back.name, "auv");
  EXPECT_EQ(back.session, h.session);
  EXPECT_EQ(back.nonce, h.nonce);
  EXPECT_EQ(back.ack_seq, 42u);
  EXPECT_EQ(back.udp_port, 11411);
  ASSERT_TRUE(back.origin);
  EXPECT_DOUBLE_EQ(back.origin->lon_deg, 24.2);
  h.origin.reset();
  ASSERT_TRUE(decodeHello(encodeHello(h), back));
  EXPECT_FALSE(back.origin);
  auto cut = b;
  cut.resize(b.size() - 3);
  EXPECT_FALSE(decodeHello(cut, back));  // truncated
  h.version = kWireVersion + 1;
  EXPECT_FALSE(decodeHello(encodeHello(h), back));  // another protocol
}

TEST(RelayHandshake, SessionKeysPairUpAndDependOnBothNonces) {
  const Authenticator psk("a-pre-shared-key-of-32-bytes-....");
  const std::string a = freshNonce(), b = freshNonce(), c = freshNonce();
  const SessionKeys ours = sessionKeys(psk, a, b), theirs = sessionKeys(psk, b, a);
  const std::uint8_t data[] = {1, 2, 3};
  std::uint8_t tag[kTagSize];
  ours.tx.tag(data, sizeof data, tag);
  EXPECT_TRUE(theirs.rx.verify(data, sizeof data, tag));
  EXPECT_FALSE(ours.rx.verify(data, sizeof data, tag));  // one key per direction
  EXPECT_FALSE(sessionKeys(psk, b, c).rx.verify(data, sizeof data, tag));  // another connection's nonce
}

TEST(RelayHandshake, SiteMismatchOnlyBeyondTheTolerance) {
  const geo::LatLonAlt ours{61.5, 24.2, 80.0};
  EXPECT_EQ(siteMismatch(ours, geo::LatLonAlt{61.5, 24.2, 80.5}, 1.0, "usv"), "");
  EXPECT_EQ(siteMismatch(ours, std::nullopt, 1.0, "usv"), "");  // a peer without an origin: not checked
  const std::string why = siteMismatch(ours, geo::LatLonAlt{61.51, 24.2, 80.0}, 1.0, "usv");
  EXPECT_NE(why.find("usv's"), std::string::npos) << why;
  EXPECT_NE(siteMismatch(ours, geo::LatLonAlt{NAN, 24.2, 80.0}, 1.0, "usv"), "");
}

TEST(RelayReliable, ReceiverDropsDuplicatesCountsGapsAndAcksAfterTheDelay) {
  ReliableReceiver r;
  r.startSession(5);
  std::uint64_t skipped = 0;
  EXPECT_TRUE(r.accept(1, skipped));
  EXPECT_TRUE(r.accept(4, skipped));
  EXPECT_EQ(skipped, 2u);
  EXPECT_FALSE(r.accept(3, skipped));  // already past it: a resend
  EXPECT_EQ(r.due(10.0, 0.5), 0u);     // delivered at 10 s: not acknowledged before 10.5 s
  EXPECT_TRUE(r.pending());
  EXPECT_EQ(r.due(10.6, 0.5), 4u);
  r.sent(4);
  EXPECT_EQ(r.due(11.0, 0.5), 0u);  // nothing new
  r.startSession(5);                // the same peer process: kept
  EXPECT_EQ(r.lastSeq(), 4u);
  r.startSession(6);  // it restarted: its numbers start again
  EXPECT_EQ(r.lastSeq(), 0u);
  EXPECT_TRUE(r.accept(1, skipped));
}

TEST(RelayPolicy, RedialBacksOffToTheMaximumAndResetsOnALink) {
  Redial d(0.1, 0.35);
  EXPECT_TRUE(d.due(0.0));
  d.dialing();
  EXPECT_FALSE(d.due(100.0));  // one attempt at a time
  d.failed(1.0);
  EXPECT_FALSE(d.due(1.05));
  EXPECT_TRUE(d.due(1.1));
  d.failed(2.0);
  EXPECT_NEAR(d.untilDue(2.0), 0.2, 1e-12);
  d.failed(3.0);
  EXPECT_NEAR(d.untilDue(3.0), 0.35, 1e-12);
  d.failed(4.0);
  EXPECT_NEAR(d.untilDue(4.0), 0.35, 1e-12);
  d.succeeded();
  d.failed(5.0);
  EXPECT_NEAR(d.untilDue(5.0), 0.1, 1e-12);
}

TEST(RelayPolicy, HeartbeatsAreDueEveryPeriodFromTheLinkUp) {
  LinkMonitor m;
  m.restart(10.0);
  EXPECT_TRUE(m.pingDue(10.0));
  const std::uint64_t first = m.ping(10.0, 0.2);
  EXPECT_FALSE(m.pingDue(10.1));
  EXPECT_TRUE(m.pingDue(10.2));
  EXPECT_EQ(m.ping(10.2, 0.2), first + 1);
  EXPECT_TRUE(m.pongReceived(first, 0.05));
  EXPECT_FALSE(m.pongReceived(first, 0.05));  // answered once
}

TEST(RelayRouting, AnnouncesRoundTripAndRemoteTopicsAreBounded) {
  TopicConfig t;
  t.topic = "/target";
  t.remote = "/auv/target";
  t.latched = true;
  const auto payload = encodeAnnounce(t, {"offshore_gnc/Target", "0123", "float64 x"});
  Announce a;
  ASSERT_TRUE(decodeAnnounce(payload, a));
  EXPECT_EQ(a.topic, "/auv/target");
  EXPECT_TRUE(a.latched && a.reliable);
  EXPECT_FALSE(decodeAnnounce({payload.begin(), payload.end() - 1}, a));
  ASSERT_TRUE(decodeAnnounce(payload, a));
  RemoteTopics r;
  const std::uint64_t digest = announceDigest(a);
  EXPECT_EQ(r.check(1, digest), RemoteTopics::Verdict::New);
  r.remember(1, digest);
  EXPECT_EQ(r.indexOf(1), -1);  // undecided: nothing delivered
  r.decide(1, 3);
  EXPECT_EQ(r.indexOf(1), 3);
  EXPECT_EQ(r.check(1, digest), RemoteTopics::Verdict::Repeat);
  EXPECT_EQ(r.check(1, digest + 1), RemoteTopics::Verdict::New);  // a changed announce is decided again
  for (std::uint16_t i = 2; r.size() < kMaxRemoteTopics; ++i) r.remember(i, i);
  EXPECT_EQ(r.check(60000, 1), RemoteTopics::Verdict::OverLimit);
  TopicConfig in;
  in.topic = "/auv/target";
  in.direction = "in";
  in.peers = {"usv"};
  EXPECT_EQ(inTopicFor({t, in}, "/auv/target", "usv"), 1);
  EXPECT_EQ(inTopicFor({t, in}, "/auv/target", "other"), -1);  // not from that peer
}

TEST(RelayStats, TransportAndRatesSinceTheLastReport) {
  TopicTraffic t;
  TopicStatus s;
  t.carried(100);
  t.report(0.0, s);
  EXPECT_EQ(s.transport, "tcp");
  EXPECT_EQ(s.rate_hz, 0.0);
  t.carried(100, true);
  t.carried(300, true);
  t.dropped();
  t.report(2.0, s);
  EXPECT_EQ(s.transport, "udp+tcp");
  EXPECT_EQ(s.messages, 3u);
  EXPECT_EQ(s.dropped, 1u);
  EXPECT_DOUBLE_EQ(s.rate_hz, 1.0);
  EXPECT_DOUBLE_EQ(s.bandwidth_bps, 200.0);
}

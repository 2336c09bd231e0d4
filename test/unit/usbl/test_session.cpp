// usbl::TransceiverSession: the ping schedule, one transaction at a time, a reply that never comes, the data
// channel between pings, fed decoded events and the time as the Usbl nodelet's I/O thread does.
#include <gtest/gtest.h>

#include "offshore_gnc/usbl/session.h"

using namespace offshore_gnc;
using namespace offshore_gnc::usbl;

namespace {
StreamDecoder::Event fixFrom(std::uint8_t src) {
  AcoFix f;
  f.src_id = src;
  f.dest_id = 1;
  f.flags = AcoFix::RANGE;
  StreamDecoder::Event e;
  e.message = Message{false, FixMessage{CID_PING_RESP, f}};
  return e;
}
StreamDecoder::Event status(std::uint8_t cid, std::uint8_t st) {
  StreamDecoder::Event e;
  e.message = Message{false, StatusReply{cid, st}};
  return e;
}
bool isPing(const std::optional<Message>& m) { return m && std::get_if<PingSend>(&m->body); }
bool isData(const std::optional<Message>& m) { return m && std::get_if<DatSend>(&m->body); }
}  // namespace

TEST(TransceiverSession, PingsOnItsScheduleOneTransactionAtATime) {
  SessionParams p;
  p.ping_rate = 0.5;  // every 2 s
  TransceiverSession s(p);
  EXPECT_FALSE(s.due(0.0));  // the first ping one period after the start
  auto m = s.due(2.0);
  ASSERT_TRUE(isPing(m));
  EXPECT_EQ(std::get<PingSend>(m->body).dest_id, 2);
  EXPECT_EQ(std::get<PingSend>(m->body).msg_type, MSG_REQU);
  s.sent(*m, 2.0);
  EXPECT_TRUE(s.awaiting());
  EXPECT_FALSE(s.due(4.5));  // still waiting for the reply (timeout 3 s)
  const SessionEvent ev = s.handle(fixFrom(2), 4.6);
  EXPECT_EQ(ev.kind, SessionEvent::kFix);
  EXPECT_FALSE(s.awaiting());
  ASSERT_TRUE(isPing(s.due(4.6)));  // the ping due at 4 s goes out at once after the reply
  EXPECT_EQ(s.counters().get("pings_sent"), 1u);
}

TEST(TransceiverSession, AReplyThatNeverComesIsCountedAndTheNextPingGoes) {
  TransceiverSession s(SessionParams{});
  auto m = s.due(0.0);
  m = s.due(2.0);
  ASSERT_TRUE(isPing(m));
  s.sent(*m, 2.0);
  EXPECT_FALSE(s.due(4.9));
  auto next = s.due(5.1);  // 3.1 s without an answer
  EXPECT_EQ(s.counters().get("no_reply"), 1u);
  ASSERT_TRUE(isPing(next));
  // a fix from another beacon does not end the transaction
  s.sent(*next, 5.1);
  s.handle(fixFrom(5), 5.5);
  EXPECT_TRUE(s.awaiting());
  // the transceiver's own timeout status ends it and is counted as such
  s.handle(status(CID_PING_ERROR, kStatusXcvrRespTimeout), 6.0);
  EXPECT_FALSE(s.awaiting());
  EXPECT_EQ(s.counters().get("ping_timeouts"), 1u);
}

TEST(TransceiverSession, DataGoesBetweenPingsAndTheQueueIsBounded) {
  SessionParams p;
  p.max_queued = 2;
  TransceiverSession s(p);
  EXPECT_FALSE(s.queueData({}));
  EXPECT_FALSE(s.queueData(std::vector<std::uint8_t>(kMaxDataPacket + 1, 1)));
  EXPECT_EQ(s.counters().get("data_too_long"), 2u);
  ASSERT_TRUE(s.queueData({1}));
  ASSERT_TRUE(s.queueData({2}));
  ASSERT_TRUE(s.queueData({3}));  // the oldest (1) is dropped
  EXPECT_EQ(s.counters().get("data_dropped"), 1u);
  auto m = s.due(0.5);
  ASSERT_TRUE(isData(m));
  EXPECT_EQ(std::get<DatSend>(m->body).data, std::vector<std::uint8_t>{2});
  s.sent(*m, 0.5);
  EXPECT_TRUE(s.awaiting());  // REQ: the remote answers with its queued packet
  StreamDecoder::Event e;
  DatReceive d;
  d.fix.src_id = 2;
  d.data = {9, 9};
  e.message = Message{false, d};
  const SessionEvent ev = s.handle(e, 1.0);
  EXPECT_EQ(ev.kind, SessionEvent::kData);
  EXPECT_EQ(ev.data, (std::vector<std::uint8_t>{9, 9}));
  EXPECT_FALSE(s.awaiting());
  ASSERT_TRUE(isData(s.due(1.0)));  // the next packet before the ping due at 2 s
}

TEST(TransceiverSession, OneWayDataWaitsForNothingAndBadParametersAreRefused) {
  SessionParams p;
  p.data_msg_type = "OWAY";
  TransceiverSession s(p);
  ASSERT_TRUE(s.queueData({1, 2, 3}));
  auto m = s.due(0.1);
  ASSERT_TRUE(isData(m));
  s.sent(*m, 0.1);
  EXPECT_FALSE(s.awaiting());
  SessionParams bad;
  bad.ping_msg_type = "PING";
  EXPECT_THROW(TransceiverSession x(bad), ConfigError);
  bad = SessionParams{};
  bad.remote_id = 0;
  EXPECT_THROW(TransceiverSession y(bad), ConfigError);
}

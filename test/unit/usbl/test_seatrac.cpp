// SeaTrac codec: golden vectors from the public examples, messages built field by field, round trips, bad input,
// and split / corrupt / shuffle runs over a recorded stream.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <random>
#include <string>
#include <vector>

#include "offshore_gnc/usbl/beacon_sim.h"
#include "usbl/fuzz_check.h"
#include "offshore_gnc/usbl/json.h"
#include "offshore_gnc/usbl/seatrac.h"

using namespace offshore_gnc::usbl;

namespace {
std::vector<StreamDecoder::Event> decodeAll(const std::string& s, StreamDecoder* dec = nullptr) {
  StreamDecoder local;
  std::vector<StreamDecoder::Event> out;
  (dec ? *dec : local).feed(s, out);
  return out;
}
std::vector<std::uint8_t> unhex(const std::string& h) {
  std::vector<std::uint8_t> v;
  for (std::size_t i = 0; i + 1 < h.size(); i += 2) v.push_back(static_cast<std::uint8_t>(std::stoi(h.substr(i, 2), nullptr, 16)));
  return v;
}
// A fully populated fix (range, 4-channel USBL, position).
AcoFix sampleFix() {
  AcoFix f;
  f.dest_id = 1, f.src_id = 2, f.flags = AcoFix::RANGE | AcoFix::USBL | AcoFix::POSITION, f.msg_type = MSG_RESPU;
  f.yaw = 900, f.pitch = -15, f.roll = 20, f.depth_local = 15, f.vos = 15000, f.rssi = -600;
  f.range_count = 1000, f.range_time = 666667, f.range_dist = 1000;
  f.usbl_rssi = {-600, -601, -602, -603};
  f.azimuth = 450, f.elevation = -300, f.fit_error = 30;
  f.east = 700, f.north = 700, f.depth = 600;
  return f;
}
Message reply(Body b) { return Message{false, std::move(b)}; }
}  // namespace

TEST(SeatracCrc, CheckValueOfArc) {
  const std::string s = "123456789";
  EXPECT_EQ(crc16(reinterpret_cast<const std::uint8_t*>(s.data()), s.size()), 0xBB3D);
}

TEST(SeatracGolden, PublicPingSendExample) {
  auto ev = decodeAll("#40020680B6\r\n");
  ASSERT_EQ(ev.size(), 1u);
  ASSERT_TRUE(ev[0].message) << ev[0].reason;
  EXPECT_TRUE(ev[0].message->command);
  const auto& p = std::get<PingSend>(ev[0].message->body);
  EXPECT_EQ(p.dest_id, 2);
  EXPECT_EQ(p.msg_type, MSG_REQX);
  EXPECT_EQ(encodeFrame(Message{true, PingSend{2, MSG_REQX}}), "#40020680B6\r\n");
}

TEST(SeatracGolden, PublicPingErrorExample) {
  auto ev = decodeAll("$43340266D5\r\n");
  ASSERT_EQ(ev.size(), 1u);
  ASSERT_TRUE(ev[0].message) << ev[0].reason;
  const auto& s = std::get<StatusReply>(ev[0].message->body);
  EXPECT_EQ(s.cid, CID_PING_ERROR);
  EXPECT_EQ(s.status, kStatusXcvrRespTimeout);
  EXPECT_EQ(s.beacon_id, 2);
  EXPECT_EQ(encodeFrame(reply(StatusReply{CID_PING_ERROR, 0x34, 2})), "$43340266D5\r\n");
}

TEST(SeatracGolden, RecordedXcvrFixFromAPublicDriverTest) {
  // An XCVR_FIX as a real beacon sent it (a public SeaTrac driver's test vector): flags 0x87 (RANGE, USBL,
  // POSITION and the undocumented bit 7, kept as received), 4 channels, every byte consumed.
  auto ev = decodeAll("$39010F87058E06A9FC810000005C3B4005CC0300004B1D0000050004A006A406B806B3069004A801A800FDFFFDFFFFFF76B3\r\n");
  ASSERT_EQ(ev.size(), 1u);
  ASSERT_TRUE(ev[0].message) << ev[0].reason;
  const auto& f = std::get<FixMessage>(ev[0].message->body).fix;
  EXPECT_EQ(f.dest_id, 1);
  EXPECT_EQ(f.src_id, 15);
  EXPECT_EQ(f.flags, 0x87);
  EXPECT_EQ(f.yaw, 1678);
  EXPECT_EQ(f.pitch, -855);
  EXPECT_EQ(f.vos, 15196);
  EXPECT_EQ(f.range_count, 972u);
  EXPECT_EQ(f.range_time, 7499);
  EXPECT_EQ(f.range_dist, 5);
  EXPECT_EQ(f.usbl_rssi, (std::vector<std::int16_t>{0x06A0, 0x06A4, 0x06B8, 0x06B3}));
  EXPECT_EQ(f.azimuth, 1168);
  EXPECT_EQ(f.elevation, 424);
  EXPECT_EQ(f.fit_error, 168);
  EXPECT_EQ(f.east, -3);
  EXPECT_EQ(f.north, -3);
  EXPECT_EQ(f.depth, -1);
}

TEST(SeatracGolden, PingRespBuiltFieldByField) {
  // Hex written by hand from the ACOFIX layout: every field little-endian at its documented offset.
  const std::string hex =
      "42" "01" "02" "07" "05"          // CID, dest, src, flags RANGE|USBL|POSITION, RESPU
      "8403" "F1FF" "1400"              // yaw 90.0, pitch -1.5, roll 2.0 deg
      "0F00" "983A" "A8FD"              // depth 1.5 m, VOS 1500.0 m/s, RSSI -60.0 dB
      "E8030000" "2B2C0A00" "E803"      // range count 1000, time 0.0666667 s, distance 100.0 m
      "04" "A8FD" "A7FD" "A6FD" "A5FD"  // 4 channels' RSSI
      "C201" "D4FE" "1E00"              // azimuth 45.0, elevation -30.0 deg, fit error 0.30
      "BC02" "BC02" "5802";             // east 70.0, north 70.0, depth 60.0 m
  const auto bin = unhex(hex);
  const std::string frame = encodeFrameRaw(false, bin);
  auto ev = decodeAll(frame);
  ASSERT_EQ(ev.size(), 1u);
  ASSERT_TRUE(ev[0].message) << ev[0].reason;
  const auto& fm = std::get<FixMessage>(ev[0].message->body);
  EXPECT_EQ(fm.cid, CID_PING_RESP);
  EXPECT_EQ(fm.fix, sampleFix());
  EXPECT_NEAR(fm.fix.rangeM(), 100.0, 1e-9);
  EXPECT_NEAR(fm.fix.rangeTimeS(), 0.0666667, 1e-9);
  EXPECT_NEAR(fm.fix.azimuthRad(), M_PI / 4, 1e-9);
  EXPECT_NEAR(fm.fix.elevationRad(), -M_PI / 6, 1e-9);
  EXPECT_NEAR(fm.fix.fitError(), 0.3, 1e-12);
  EXPECT_EQ(encodePayload(*ev[0].message), bin);
  const std::string js = toJson(*ev[0].message);
  EXPECT_NE(js.find("\"cid\":\"PING_RESP\""), std::string::npos);
  EXPECT_NE(js.find("\"range_m\":100"), std::string::npos);
  EXPECT_NE(js.find("\"azimuth_deg\":45"), std::string::npos);
  EXPECT_NE(js.find("\"sound_speed_mps\":1500"), std::string::npos);
}

TEST(SeatracRoundTrip, EveryMessageKind) {
  AcoFix range_only;
  range_only.flags = AcoFix::RANGE;
  range_only.range_dist = 42;
  AcoFix two_channels = sampleFix();
  two_channels.usbl_rssi = {-1, -2};
  two_channels.flags |= AcoFix::FILTER_ERROR | AcoFix::ENHANCED;
  const std::vector<Message> msgs = {
      {true, PingSend{2, MSG_REQU}},
      reply(StatusReply{CID_PING_SEND, kStatusOk, 2}),
      reply(FixMessage{CID_PING_RESP, sampleFix()}),
      reply(FixMessage{CID_XCVR_FIX, range_only}),
      reply(FixMessage{CID_PING_RESP, two_channels}),
      {true, DatSend{2, MSG_REQ, {1, 2, 3, 0xFF}}},
      reply(DatReceive{sampleFix(), true, {9, 8, 7}}),
      reply(DatReceive{range_only, false, {}}),
      reply(Opaque{CID_STATUS, {1, 2, 3}}),
  };
  std::string stream;
  for (const auto& m : msgs) stream += encodeFrame(m);
  auto ev = decodeAll(stream);
  ASSERT_EQ(ev.size(), msgs.size());
  for (std::size_t i = 0; i < msgs.size(); ++i) {
    ASSERT_TRUE(ev[i].message) << i << ": " << ev[i].reason;
    EXPECT_EQ(ev[i].message->command, msgs[i].command);
    EXPECT_TRUE(ev[i].message->body == msgs[i].body) << i;
  }
}

TEST(SeatracBadInput, EachRejectionCountedAndNextGoodDecodes) {
  const std::string good = encodeFrame(reply(FixMessage{CID_PING_RESP, sampleFix()}));
  auto with = [](std::vector<std::uint8_t> p) { return encodeFrameRaw(false, p); };
  auto fixBytes = encodePayload(reply(FixMessage{CID_PING_RESP, sampleFix()}));
  auto truncated = fixBytes;
  truncated.pop_back();
  auto overlong = fixBytes;
  overlong.push_back(0);
  auto five = fixBytes;
  five[27] = 5;  // channel count: CID (1) + fixed ACOFIX part (16) + range fields (10)
  std::string bad_crc = good;
  bad_crc[bad_crc.size() - 3] = bad_crc[bad_crc.size() - 3] == '0' ? '1' : '0';
  const std::vector<std::pair<std::string, std::string>> cases = {
      {bad_crc, "bad_crc"},
      {"$4334026\r\n", "odd_hex_length"},
      {"$43340G66D5\r\n", "non_hex"},
      {with({0x77, 0, 2}), "unknown_cid"},
      {with(truncated), "truncated"},
      {with(overlong), "trailing_bytes"},
      {with(five), "too_many_channels"},
      {"$" + std::string(1000, 'A') + "\r\n", "line_too_long"},
  };
  for (const auto& c : cases) {
    StreamDecoder dec;
    auto ev = decodeAll("garbage" + c.first + good, &dec);
    ASSERT_EQ(ev.size(), 2u) << c.second;
    EXPECT_FALSE(ev[0].message) << c.second;
    EXPECT_EQ(ev[0].reason, c.second);
    EXPECT_EQ(dec.counters().get(c.second), 1u) << c.second;
    ASSERT_TRUE(ev[1].message) << c.second << " then " << ev[1].reason;
    EXPECT_EQ(std::get<FixMessage>(ev[1].message->body).fix, sampleFix());
    EXPECT_EQ(dec.counters().get("garbage_bytes"), 7u);
  }
}

TEST(SeatracBadInput, SyncCharacterInsideALineRestartsTheFrame) {
  const std::string good = encodeFrame(reply(StatusReply{CID_PING_ERROR, 0x34, 2}));
  auto ev = decodeAll("$4334" + good);
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].reason, "unterminated");
  EXPECT_TRUE(ev[1].message);
}

namespace {
// A recorded stream: the simulator's replies to a run of pings, plus commands.
std::vector<std::string> recordedFrames() {
  BeaconSimConfig cfg;
  cfg.dropout_probability = 0.2;
  cfg.seed = 7;
  BeaconSimulator sim(cfg);
  Pose usv;
  std::vector<std::string> frames;
  double t = 0;
  for (int i = 0; i < 60; ++i, t += 2.0) {
    const Eigen::Vector3d auv(30.0 + i, -20.0 + 0.5 * i, 15.0);
    sim.setCurrentRange(transceiverRange(cfg.mount, usv, auv));
    const Message ping{true, PingSend{2, MSG_REQU}};
    frames.push_back(encodeFrame(ping));
    frames.push_back(sim.handle(ping, t));
    frames.push_back(sim.poll(t + 1.5, usv, auv));
  }
  return frames;
}
std::vector<std::string> goodLines(const std::string& s) {
  std::vector<std::string> v;
  for (const auto& e : decodeAll(s))
    if (e.message) v.push_back(e.line);
  return v;
}
}  // namespace

TEST(SeatracStream, RandomSplitsGiveTheSameMessages) {
  std::string stream;
  for (const auto& f : recordedFrames()) stream += f;
  const auto expected = goodLines(stream);
  ASSERT_GE(expected.size(), 150u);
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    StreamDecoder dec;
    std::vector<StreamDecoder::Event> ev;
    std::size_t pos = 0;
    while (pos < stream.size()) {
      const std::size_t len = std::min<std::size_t>(std::uniform_int_distribution<int>(1, 64)(rng), stream.size() - pos);
      dec.feed(reinterpret_cast<const std::uint8_t*>(stream.data() + pos), len, ev);
      pos += len;
    }
    std::vector<std::string> got;
    for (const auto& e : ev)
      if (e.message) got.push_back(e.line);
    EXPECT_EQ(got, expected);
    EXPECT_EQ(dec.counters().total(), dec.counters().get("frames_ok"));
  }
}

TEST(SeatracStream, CorruptionNeverYieldsAFrameThatWasNotSent) {
  const auto frames = recordedFrames();
  std::string stream;
  for (const auto& f : frames) stream += f;
  const auto sent = goodLines(stream);
  std::mt19937 rng(5);
  for (int trial = 0; trial < 30; ++trial) {
    std::string bad = stream;
    for (int k = 0; k < 40; ++k)
      bad[std::uniform_int_distribution<std::size_t>(0, bad.size() - 1)(rng)] =
          static_cast<char>(std::uniform_int_distribution<int>(0, 255)(rng));
    StreamDecoder dec;
    std::vector<StreamDecoder::Event> ev;
    dec.feed(bad, ev);
    std::size_t good = 0;
    for (const auto& e : ev)
      if (e.message) {
        ++good;
        // A 16-bit CRC lets about 1 in 65536 corrupted frames through; with 40 hits per run none is expected. A hit
        // that only changed a hex digit's case (which the decoder accepts) leaves the frame as sent.
        std::string line = e.line;
        std::transform(line.begin(), line.end(), line.begin(), [](unsigned char ch) { return std::toupper(ch); });
        EXPECT_NE(std::find(sent.begin(), sent.end(), line), sent.end()) << e.line;
      }
    EXPECT_GT(good, sent.size() - 45);  // each byte hit costs at most one frame (+ its neighbour on a sync hit)
    EXPECT_GT(dec.counters().total(), dec.counters().get("frames_ok"));
  }
}

TEST(SeatracStream, ShuffledFramesAllDecode) {
  auto frames = recordedFrames();
  std::mt19937 rng(11);
  std::shuffle(frames.begin(), frames.end(), rng);
  std::string stream;
  for (const auto& f : frames) stream += f;
  StreamDecoder dec;
  std::vector<StreamDecoder::Event> ev;
  dec.feed(stream, ev);
  for (const auto& e : ev) EXPECT_TRUE(e.message) << e.reason;
  EXPECT_EQ(dec.counters().total(), dec.counters().get("frames_ok"));
}

TEST(SeatracFuzzSmoke, EntryPointOnRandomAndMutatedInput) {
  // The libFuzzer target's entry point over random bytes and mutated real frames (the long run is
  // `scripts/fuzz usbl`); it aborts on any invariant violation.
  std::string stream;
  for (const auto& f : recordedFrames()) stream += f;
  std::mt19937 rng(13);
  std::size_t decoded = 0;
  for (int i = 0; i < 3000; ++i) {
    std::string s;
    if (i % 2) {
      s.resize(std::uniform_int_distribution<int>(0, 200)(rng));
      for (auto& c : s) c = static_cast<char>(rng());
    } else {
      const std::size_t at = std::uniform_int_distribution<std::size_t>(0, stream.size() - 200)(rng);
      s = stream.substr(at, 200);
      s[rng() % s.size()] = "#$0A\r\n"[rng() % 6];
    }
    decoded += fuzzCodecOnce(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
  }
  EXPECT_GT(decoded, 1000u);  // the mutated windows still hold mostly intact frames
}

// SeaNet codec: golden vectors from the public protocol description (the byte layouts that Tritech's SeaNet
// documentation gives and that independent open drivers send), framing and resynchronisation, bad input.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "offshore_gnc/micron/seanet.h"
#include "offshore_gnc/micron/session.h"

using namespace offshore_gnc;
using namespace offshore_gnc::micron;

namespace {
std::vector<std::uint8_t> bytes(const std::string& s) { return {s.begin(), s.end()}; }
std::string str(const std::vector<std::uint8_t>& b) { return {b.begin(), b.end()}; }
std::vector<StreamDecoder::Event> decodeAll(const std::vector<std::uint8_t>& b, StreamDecoder& d) {
  std::vector<StreamDecoder::Event> ev;
  d.feed(b.data(), b.size(), ev);
  return ev;
}
// The 82-byte mtHeadCommand with the dual-channel V3B block (byte 13 = 0x1D), as published with an open driver
// for the Micron: 6 m range, full circle limits 1 .. 6399, 0.9 degree step, 90 bins.
const std::vector<std::uint8_t> kV3bHeadCommand = {
    0x40, 0x30, 0x30, 0x34, 0x43, 0x4C, 0x00, 0xFF, 0x02, 0x47, 0x13, 0x80, 0x02, 0x1D, 0x01, 0x23, 0x02, 0x99,
    0x99, 0x99, 0x02, 0x66, 0x66, 0x66, 0x05, 0xA3, 0x70, 0x3D, 0x06, 0x70, 0x3D, 0x0A, 0x09, 0x28, 0x00, 0x3C,
    0x00, 0x01, 0x00, 0xFF, 0x18, 0x51, 0x08, 0x54, 0x54, 0x5A, 0x00, 0x7D, 0x00, 0x19, 0x10, 0x8D, 0x00, 0x5A,
    0x00, 0xE8, 0x03, 0x97, 0x03, 0x40, 0x06, 0x01, 0x00, 0x00, 0x00, 0x50, 0x51, 0x09, 0x08, 0x54, 0x54, 0x00,
    0x00, 0x5A, 0x00, 0x7D, 0x00, 0x00, 0x00, 0x00, 0x00, 0x0A};
}  // namespace

TEST(SeaNetGolden, CommandsWithoutBody) {
  // '@' "0008" 08 00 | FF 02 | 03 | type | 80 02 | LF: 14 bytes.
  EXPECT_EQ(bytes(encode(fromPc(Command{mtSendVersion}))),
            (std::vector<std::uint8_t>{0x40, 0x30, 0x30, 0x30, 0x38, 0x08, 0x00, 0xFF, 0x02, 0x03, 0x17, 0x80, 0x02, 0x0A}));
  EXPECT_EQ(bytes(encode(fromPc(Command{mtReBoot}))),
            (std::vector<std::uint8_t>{0x40, 0x30, 0x30, 0x30, 0x38, 0x08, 0x00, 0xFF, 0x02, 0x03, 0x10, 0x80, 0x02, 0x0A}));
  EXPECT_EQ(bytes(encode(fromPc(Command{mtSendBBUser})))[10], 0x18);
}

TEST(SeaNetGolden, SendDataCarriesThePcClock) {
  // 17:11:31.786 = 61891786 ms = 0x03B064CA, little-endian after the node byte; 18 bytes, hex length "000C".
  EXPECT_EQ(bytes(encode(fromPc(SendData{61891786}))),
            (std::vector<std::uint8_t>{0x40, 0x30, 0x30, 0x30, 0x43, 0x0C, 0x00, 0xFF, 0x02, 0x07, 0x19, 0x80, 0x02,
                                       0xCA, 0x64, 0xB0, 0x03, 0x0A}));
}

TEST(SeaNetGolden, HeadCommandForThePaperConfiguration) {
  SonarSettings s;  // 10 m, 90 degree forward sector, 1.8 degree step, 200 bins, 40 % gain
  const auto b = bytes(encode(fromPc(s.headCommand())));
  ASSERT_EQ(b.size(), 66u);  // no V3B block: hex length "003C", byte count 0x37
  EXPECT_EQ(str({b.begin(), b.begin() + 7}), std::string("@003C") + char(0x3C) + char(0x00));
  EXPECT_EQ(b[7], 0xFF);
  EXPECT_EQ(b[8], 0x02);
  EXPECT_EQ(b[9], 0x37);
  EXPECT_EQ(b[10], 0x13);
  EXPECT_EQ(b[13], 0x01);                          // single channel
  EXPECT_EQ(b[14] | (b[15] << 8), 0x2305);         // adc8on, scanright, raw, hasmot, ReplyASL
  EXPECT_EQ(b[16], 0x11);                          // DST head
  EXPECT_EQ(b[35] | (b[36] << 8), 100);            // range scale 10.0 m in dm, metres
  EXPECT_EQ(b[37] | (b[38] << 8), 2400);           // left limit: ahead (3200) - 45 deg (800)
  EXPECT_EQ(b[39] | (b[40] << 8), 4000);           // right limit: ahead + 45 deg
  EXPECT_EQ(b[41], 255);                           // ADSpan 80 dB
  EXPECT_EQ(b[42], 0);                             // ADLow 0 dB
  EXPECT_EQ(b[43], 84);                            // gain 40 % of 210
  EXPECT_EQ(b[49], 25);                            // motor step delay
  EXPECT_EQ(b[50], 32);                            // 1.8 deg = 32/16 gradian
  EXPECT_EQ(b[51] | (b[52] << 8), 104);            // 2 * 10 m / 1500 m/s / 200 bins / 640 ns
  EXPECT_EQ(b[53] | (b[54] << 8), 200);
  EXPECT_EQ(b[55] | (b[56] << 8), 500);
  EXPECT_EQ(b[57] | (b[58] << 8), 100);
  EXPECT_EQ(b[59] | (b[60] << 8), 1600);
  EXPECT_EQ(b[61], 1);
  EXPECT_EQ(b[65], 0x0A);
  std::string why;
  auto m = decodePacket(b.data(), b.size(), why);
  ASSERT_TRUE(m) << why;
  EXPECT_EQ(encode(*m), str(b));
}

TEST(SeaNetGolden, DecodesThePublishedV3bHeadCommand) {
  std::string why;
  auto m = decodePacket(kV3bHeadCommand.data(), kV3bHeadCommand.size(), why);
  ASSERT_TRUE(m) << why;
  const auto& c = std::get<HeadCommand>(m->body);
  EXPECT_EQ(c.v3b, 0x1D);
  EXPECT_EQ(c.hd_ctrl, 0x2301);
  EXPECT_EQ(c.head_type, 0x02);
  EXPECT_EQ(c.range_scale, 60);
  EXPECT_EQ(c.left_limit, 1);
  EXPECT_EQ(c.right_limit, 6399);
  EXPECT_EQ(c.step_angle, 16);
  EXPECT_EQ(c.ad_interval, 141);
  EXPECT_EQ(c.nbins, 90);
  EXPECT_EQ(c.max_ad_buf, 1000);
  ASSERT_EQ(c.v3b_block.size(), 16u);
  EXPECT_EQ(c.v3b_block[0], 0x50);
  EXPECT_EQ(str(kV3bHeadCommand), encode(*m));  // re-encodes byte for byte
}

TEST(SeaNetGolden, AliveFromTheLayout) {
  // 22 bytes: '@' "0010" 10 00 | 02 FF | 0B | 04 80 02 | spare | time (4) | motor position (2) | HeadInf | LF
  const std::vector<std::uint8_t> alive = {0x40, 0x30, 0x30, 0x31, 0x30, 0x10, 0x00, 0x02, 0xFF, 0x0B, 0x04,
                                           0x80, 0x02, 0x00, 0xCA, 0x64, 0xB0, 0x03, 0x80, 0x0C, 0x8A, 0x0A};
  std::string why;
  auto m = decodePacket(alive.data(), alive.size(), why);
  ASSERT_TRUE(m) << why;
  const auto& a = std::get<Alive>(m->body);
  EXPECT_EQ(a.head_time_ms, 61891786u);
  EXPECT_EQ(a.motor_position, 3200);
  EXPECT_EQ(a.head_inf, 0x8A);  // has parameters (SentCfg), motor on, centred: ready for mtSendData
  EXPECT_TRUE(a.head_inf & kSentCfg);
  EXPECT_FALSE(a.head_inf & kNoParams);
  EXPECT_EQ(encode(*m), str(alive));
}

TEST(SeaNetGolden, HeadDataFromTheLayout) {
  // 45 + dbytes bytes; the byte count at 9 is 0 (no multi-packet mode); word 13 = dbytes + 31.
  std::vector<std::uint8_t> p = {0x40, 0x30, 0x30, 0x32, 0x42, 0x2B, 0x00, 0x02, 0xFF, 0x00, 0x02, 0x80, 0x02,
                                 0x23, 0x00,             // 35 bytes from 13 to the last data byte
                                 0x11, 0x10, 0x00,       // DST, 8-bit data, scanning
                                 0x05, 0x23,             // HdCtrl
                                 0x64, 0x00,             // 10.0 m
                                 0, 0, 0, 0, 0x54, 0, 0, 0xFF, 0x00, 0x00, 0x00,
                                 0x68, 0x00,             // ADInterval 104
                                 0x60, 0x09, 0xA0, 0x0F, 0x20,
                                 0x80, 0x0C,             // bearing 3200 = ahead
                                 0x04, 0x00,             // 4 data bytes
                                 10, 20, 200, 30, 0x0A};
  ASSERT_EQ(p.size(), 49u);
  std::string why;
  auto m = decodePacket(p.data(), p.size(), why);
  ASSERT_TRUE(m) << why;
  const auto& h = std::get<HeadData>(m->body);
  EXPECT_EQ(h.bearing, 3200);
  EXPECT_DOUBLE_EQ(h.rangeScaleM(), 10.0);
  EXPECT_EQ(h.step_angle, 32);
  EXPECT_EQ(h.bins(), (std::vector<std::uint8_t>{10, 20, 200, 30}));
  EXPECT_EQ(encode(*m), str(p));
  HeadGeometry g;
  EXPECT_NEAR(g.bearingOf(h.bearing), 0.0, 1e-12);
  EXPECT_NEAR(g.bearingOf(4000), deg2rad(45.0), 1e-12);
  EXPECT_NEAR(g.bearingOf(2400), deg2rad(315.0), 1e-12);
  g.inverted = true;
  EXPECT_NEAR(g.bearingOf(4000), deg2rad(315.0), 1e-12);
}

TEST(SeaNet, FourBitDataIsUnpackedHighNibbleFirstByDefaultTheOtherOrderSelectable) {
  HeadData h;
  h.hd_ctrl = 0;  // adc8on off
  h.data = {0xF1, 0x0A};
  EXPECT_EQ(h.bins(), (std::vector<std::uint8_t>{255, 17, 0, 170}));  // level 15 is the 8-bit mode's 255
  FourBitFormat f;
  f.order = "low_first";
  f.scale = 16;
  EXPECT_EQ(h.bins(f), (std::vector<std::uint8_t>{16, 240, 160, 0}));
  f.scale = 15;
  EXPECT_THROW(FourBitFormat::table().validate(f), ConfigError);
  h.hd_ctrl = kAdc8On;  // 8-bit data as sent, whatever the 4-bit format
  EXPECT_EQ(h.bins(f), h.data);
}

TEST(SeaNet, ResynchronisesAfterGarbageAndDamage) {
  const std::string good = encode(fromPc(Command{mtSendVersion}));
  std::string bad_term = good;
  bad_term.back() = 'X';
  std::string bad_len = good;
  bad_len[5] = 0x09;  // binary length disagrees with the hex length
  std::string bad_hex = good;
  bad_hex[2] = 'G';
  std::string stream = "noise@@\x01" + bad_term + bad_len + bad_hex + good + good.substr(0, 5);
  StreamDecoder d;
  auto ev = decodeAll(bytes(stream), d);
  int ok = 0;
  std::vector<std::string> reasons;
  for (const auto& e : ev) {
    if (e.message) ++ok;
    else reasons.push_back(e.reason);
  }
  EXPECT_EQ(ok, 1);
  EXPECT_EQ(d.counters().get("bad_terminator"), 1u);
  EXPECT_EQ(d.counters().get("length_mismatch"), 1u);
  EXPECT_GE(d.counters().get("bad_hex_length"), 1u);
  EXPECT_GT(d.counters().get("garbage_bytes"), 5u);
  EXPECT_EQ(d.pending(), 5u);  // the cut-off packet waits for its end
}

TEST(SeaNet, RejectsInconsistentHeadData) {
  HeadData h;
  h.hd_ctrl = kAdc8On;
  h.data = {1, 2, 3};
  std::string p = encode(fromSonar(h));
  p[42] = 5;  // dbytes says 5, the packet carries 3
  std::string why;
  EXPECT_FALSE(decodePacket(reinterpret_cast<const std::uint8_t*>(p.data()), p.size(), why));
  EXPECT_EQ(why, "head_data_dbytes_mismatch");
  p = encode(fromSonar(h));
  p[40] = 0x00;
  p[41] = 0x19;  // bearing 6400: out of the scale
  EXPECT_FALSE(decodePacket(reinterpret_cast<const std::uint8_t*>(p.data()), p.size(), why));
  EXPECT_EQ(why, "head_data_bad_bearing");
}

TEST(SeaNet, RejectsAbsurdLengthsWithoutWaiting) {
  StreamDecoder d;
  auto ev = decodeAll(bytes(std::string("@FFFF") + char(0xFF) + char(0xFF) + "rest"), d);
  ASSERT_FALSE(ev.empty());
  EXPECT_EQ(ev[0].reason, "too_long");
  EXPECT_EQ(d.pending(), 0u);
}

TEST(SeaNet, ChunkingDoesNotMatter) {
  std::string s;
  s += encode(fromSonar(Alive{0, 1000, 3200, 0x4A}));
  HeadData h;
  h.hd_ctrl = kAdc8On;
  h.data.assign(200, 7);
  s += encode(fromSonar(h));
  s += "junk";
  s += encode(fromPc(SendData{5}));
  for (std::size_t chunk : {1, 3, 13, 64, 1000}) {
    StreamDecoder d;
    std::vector<StreamDecoder::Event> ev;
    for (std::size_t i = 0; i < s.size(); i += chunk)
      d.feed(reinterpret_cast<const std::uint8_t*>(s.data()) + i, std::min(chunk, s.size() - i), ev);
    int ok = 0;
    for (const auto& e : ev) ok += e.message ? 1 : 0;
    EXPECT_EQ(ok, 3) << chunk;
    EXPECT_EQ(d.counters().get("garbage_bytes"), 4u);
  }
}

TEST(SeaNet, AnglesRoundTrip) {
  EXPECT_EQ(radToUnits(deg2rad(1.8)), 32);
  EXPECT_EQ(radToUnits(-deg2rad(1.8)), 6368);
  EXPECT_EQ(radToUnits(2 * kPi), 0);
  EXPECT_NEAR(unitsToRad(1600), kPi / 2, 1e-12);
}

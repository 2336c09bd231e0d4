// Codec golden vectors: frames hand-built from the NMEA 2000 field definitions and from docs/can-protocol.md,
// encode/decode round trips, and bad input (wrong DLC, unknown ids, out-of-range, counter jumps).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "offshore_gnc/can/decode.h"
#include "offshore_gnc/can/nmea2000.h"
#include "offshore_gnc/can/waterjet_protocol.h"
#include "offshore_gnc/common/angles.h"

using namespace offshore_gnc;
using namespace offshore_gnc::can;

namespace {
CanFrame fromCansend(const std::string& s) {
  auto l = parseCandump("can0 " + s);
  EXPECT_TRUE(l.has_value()) << s;
  return l ? l->frame : CanFrame{};
}
}  // namespace

TEST(IsoId, LayoutPdu2AndPdu1) {
  // 129025 = 0x1F801: DP 1, PF 0xF8 (PDU2), PS 0x01; priority 2, source 0x02 -> 0x09F80102.
  n2k::IsoId id = n2k::decodeId(0x09F80102);
  EXPECT_EQ(id.priority, 2);
  EXPECT_EQ(id.pgn, 129025u);
  EXPECT_EQ(id.source, 2);
  EXPECT_EQ(n2k::encodeId(id), 0x09F80102u);
  // 127250 = 0x1F112, priority 2, source 0x23 -> 0x09F11223.
  id = n2k::decodeId(0x09F11223);
  EXPECT_EQ(id.pgn, 127250u);
  EXPECT_EQ(id.source, 0x23);
  // PDU1 (PF < 240): ISO request 59904 = 0xEA00 to destination 0x1C from 0x05, priority 6 -> 0x18EA1C05.
  id = n2k::decodeId(0x18EA1C05);
  EXPECT_EQ(id.pgn, 59904u);
  EXPECT_EQ(id.destination, 0x1C);
  EXPECT_EQ(id.priority, 6);
  EXPECT_EQ(n2k::encodeId(id), 0x18EA1C05u);
}

TEST(Nmea2000, PositionRapidGolden) {
  // lat 61.4507 deg = 614507000 * 1e-7 = 0x24A0_A1F8; lon 23.727 deg = 237270000 = 0x0E24_73F0; little endian.
  const CanFrame f = fromCansend("09F80102#F8A1A024F073240E");
  auto p = n2k::decodePositionRapid(f);
  ASSERT_TRUE(p);
  EXPECT_NEAR(*p->lat_deg, 61.4507, 1e-9);
  EXPECT_NEAR(*p->lon_deg, 23.727, 1e-9);
  const CanFrame e = n2k::encodePositionRapid(*p, 2);
  EXPECT_EQ(formatCansend(e), "09F80102#F8A1A024F073240E");
  // Southern / western hemisphere: negative two's complement.
  n2k::PositionRapid sw;
  sw.lat_deg = -33.8568;
  sw.lon_deg = -151.2153;
  auto back = n2k::decodePositionRapid(n2k::encodePositionRapid(sw, 7));
  EXPECT_NEAR(*back->lat_deg, -33.8568, 1e-7);
  EXPECT_NEAR(*back->lon_deg, -151.2153, 1e-7);
}

TEST(Nmea2000, VesselHeadingGolden) {
  // SID 5, heading 1.5708 rad = 15708 = 0x3D5C, deviation n/a 0x7FFF, variation -0.0524 rad = -524 = 0xFDF4,
  // reference true (0) with reserved bits set.
  const CanFrame f = fromCansend("09F11240#055C3DFF7FF4FDFC");
  auto h = n2k::decodeVesselHeading(f);
  ASSERT_TRUE(h);
  EXPECT_EQ(h->sid, 5);
  EXPECT_NEAR(*h->heading_rad, 1.5708, 1e-12);
  EXPECT_FALSE(h->deviation_rad);
  EXPECT_NEAR(*h->variation_rad, -0.0524, 1e-12);
  EXPECT_EQ(h->reference, 0);
  EXPECT_EQ(formatCansend(n2k::encodeVesselHeading(*h, 0x40)), "09F11240#055C3DFF7FF4FDFC");
}

TEST(Nmea2000, CogSogRapidGolden) {
  // SID 9, reference true, COG 3.1416 rad = 31416 = 0x7AB8, SOG 2.57 m/s = 257 = 0x0101, reserved 0xFFFF.
  const CanFrame f = fromCansend("09F80240#09FCB87A0101FFFF");
  auto c = n2k::decodeCogSogRapid(f);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->sid, 9);
  EXPECT_NEAR(*c->cog_rad, 3.1416, 1e-12);
  EXPECT_NEAR(*c->sog_mps, 2.57, 1e-12);
  EXPECT_EQ(formatCansend(n2k::encodeCogSogRapid(*c, 0x40)), "09F80240#09FCB87A0101FFFF");
}

TEST(Nmea2000, NotAvailableAndEdges) {
  auto h = n2k::decodeVesselHeading(fromCansend("09F11240#00FFFFFF7FFF7FFF"));
  ASSERT_TRUE(h);
  EXPECT_FALSE(h->heading_rad);
  auto p = n2k::decodePositionRapid(fromCansend("09F80102#FFFFFF7FFFFFFF7F"));
  ASSERT_TRUE(p);
  EXPECT_FALSE(p->lat_deg);
  EXPECT_FALSE(p->lon_deg);
  // |lat| > 90 deg (91 deg = 910000000 = 0x363D7F80) is garbage, not a position.
  p = n2k::decodePositionRapid(fromCansend("09F80102#807F3D3600000000"));
  ASSERT_TRUE(p);
  EXPECT_FALSE(p->lat_deg);
  EXPECT_NEAR(*p->lon_deg, 0.0, 1e-12);
  n2k::PositionRapid bad;
  bad.lat_deg = std::nan("");
  EXPECT_FALSE(n2k::decodePositionRapid(n2k::encodePositionRapid(bad, 1))->lat_deg);
  // Heading just below 2 pi rounds to 2 pi and must wrap to 0, never exceed the field.
  n2k::VesselHeading v;
  v.heading_rad = 2.0 * kPi - 1e-6;
  EXPECT_NEAR(*n2k::decodeVesselHeading(n2k::encodeVesselHeading(v, 1))->heading_rad, 0.0, 1e-12);
  v.heading_rad = -0.5;  // wrapped into [0, 2 pi)
  EXPECT_NEAR(*n2k::decodeVesselHeading(n2k::encodeVesselHeading(v, 1))->heading_rad, 2.0 * kPi - 0.5, 1e-4);
  // Wrong DLC and wrong PGN are rejected.
  EXPECT_FALSE(n2k::decodeVesselHeading(fromCansend("09F11240#055C3DFF7FF4FD")));
  EXPECT_FALSE(n2k::decodeVesselHeading(fromCansend("09F80102#F8A1A024F073240E")));
}

TEST(Waterjet, CommandGoldenAndRoundTrip) {
  jet::Command c;
  c.surge = 0.5;   // 16000 = 0x3E80
  c.sway = -0.25;  // -8000 = 0xE0C0
  c.yaw = 1.0;     // 32000 = 0x7D00
  c.source = 0;
  c.counter = 3;
  const CanFrame f = jet::encodeCommand(c, false);
  // PGN 0xFF10, priority 3, source 0x20 -> 0x0CFF1020. CRC-8 SAE J1850 over 0x10 + bytes 0..6.
  const std::string s = formatCansend(f);
  EXPECT_EQ(s.substr(0, 23), "0CFF1020#803EC0E0007D03");
  EXPECT_EQ(f.data[7], jet::crc(jet::kPgnCommand, f.data.data()));
  jet::Command back;
  bool manual = true;
  ASSERT_EQ(jet::decodeCommand(f, back, &manual), jet::Error::kNone);
  EXPECT_FALSE(manual);
  EXPECT_DOUBLE_EQ(back.surge, 0.5);
  EXPECT_DOUBLE_EQ(back.sway, -0.25);
  EXPECT_DOUBLE_EQ(back.yaw, 1.0);
  EXPECT_EQ(back.counter, 3);
  const CanFrame m = jet::encodeCommand(c, true);
  EXPECT_EQ(formatCansend(m).substr(0, 9), "08FF1110#");  // priority 2, bridge 0x10
  ASSERT_EQ(jet::decodeCommand(m, back, &manual), jet::Error::kNone);
  EXPECT_TRUE(manual);
}

TEST(Waterjet, Crc8SaeJ1850CheckValue) {
  // Catalogue check value of CRC-8/SAE-J1850 (poly 0x1D, init 0xFF, xorout 0xFF): "123456789" -> 0x4B.
  const std::uint8_t digits[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(jet::crc8(digits, sizeof digits), 0x4B);
  // Any single-bit error in the payload is detected.
  jet::Command c;
  c.surge = 0.1;
  const CanFrame f = jet::encodeCommand(c, false);
  for (int byte = 0; byte < 7; ++byte)
    for (int bit = 0; bit < 8; ++bit) {
      CanFrame g = f;
      g.data[byte] ^= static_cast<std::uint8_t>(1 << bit);
      jet::Command out;
      EXPECT_EQ(jet::decodeCommand(g, out), jet::Error::kChecksum) << byte << ":" << bit;
    }
}

TEST(Waterjet, StatusRoundTripAndBadInput) {
  jet::Status s;
  s.jet = 1;
  s.rpm = 1850;
  s.nozzle = -0.3;
  s.bucket = 1.0;
  s.faults = 1 | 8;
  s.counter = 15;
  const CanFrame f = jet::encodeStatus(s);
  jet::Status b;
  ASSERT_EQ(jet::decodeStatus(f, b), jet::Error::kNone);
  EXPECT_EQ(b.jet, 1);
  EXPECT_DOUBLE_EQ(b.rpm, 1850);
  EXPECT_NEAR(b.nozzle, -0.3, 1.0 / jet::kFullScale);
  EXPECT_EQ(b.faults, 9);
  EXPECT_EQ(b.counter, 15);
  // Wrong DLC.
  CanFrame g = f;
  g.len = 7;
  EXPECT_EQ(jet::decodeStatus(g, b), jet::Error::kLength);
  // Out of range but with a valid CRC: rpm 7000.
  g = f;
  putU16(&g.data[0], 7000);
  g.data[7] = jet::crc(jet::kPgnStatus, g.data.data());
  EXPECT_EQ(jet::decodeStatus(g, b), jet::Error::kRange);
  // Deflection beyond full scale on a command.
  CanFrame c = jet::encodeCommand(jet::Command{}, false);
  putU16(&c.data[0], static_cast<std::uint16_t>(-32768));
  c.data[7] = jet::crc(jet::kPgnCommand, c.data.data());
  jet::Command cmd;
  EXPECT_EQ(jet::decodeCommand(c, cmd), jet::Error::kRange);
  // Unknown ids and standard frames are not ours.
  EXPECT_EQ(jet::decodeCommand(fromCansend("123#0011"), cmd), jet::Error::kNotOurs);
  EXPECT_EQ(jet::decodeStatus(fromCansend("09F80102#F8A1A024F073240E"), b), jet::Error::kNotOurs);
  // Non-finite input never reaches the bus as garbage.
  jet::Command nan;
  nan.surge = std::nan("");
  ASSERT_EQ(jet::decodeCommand(jet::encodeCommand(nan, false), cmd), jet::Error::kNone);
  EXPECT_EQ(cmd.surge, 0.0);
}

TEST(Waterjet, SetpointGoldenRoundTripAndBadInput) {
  jet::Setpoint s;
  s.jet = 0;
  s.rpm = 1200;     // 0x04B0
  s.nozzle = -0.25; // -8000 = 0xE0C0
  s.bucket = 0.5;   // 16000 = 0x3E80
  s.source = kAutonomy;
  s.counter = 5;
  // Proprietary A (PGN 0xEF00, PDU1) to the port jet 0x30 from the gateway 0x20, priority 3 -> 0x0CEF3020.
  // CRC-8 SAE J1850 over the destination 0x30 + bytes 0..6 (value computed by hand from the definition).
  const CanFrame f = jet::encodeSetpoint(s);
  EXPECT_EQ(formatCansend(f), "0CEF3020#B004C0E0803E05FD");
  EXPECT_EQ(n2k::decodeId(f.id).destination, 0x30);
  jet::Setpoint back;
  ASSERT_EQ(jet::decodeSetpoint(f, back), jet::Error::kNone);
  EXPECT_EQ(back.jet, 0);
  EXPECT_DOUBLE_EQ(back.rpm, 1200);
  EXPECT_DOUBLE_EQ(back.nozzle, -0.25);
  EXPECT_DOUBLE_EQ(back.bucket, 0.5);
  EXPECT_EQ(back.counter, 5);
  EXPECT_EQ(back.source, kAutonomy);
  s.jet = 1;
  s.source = kWatchdog;
  const CanFrame g = jet::encodeSetpoint(s);
  EXPECT_EQ(formatCansend(g).substr(0, 9), "0CEF3120#");  // the starboard jet's address
  ASSERT_EQ(jet::decodeSetpoint(g, back), jet::Error::kNone);
  EXPECT_EQ(back.jet, 1);
  EXPECT_EQ(back.source, kWatchdog);
  // Not a command or a status: the other decoders leave it alone.
  jet::Command c;
  jet::Status st;
  EXPECT_EQ(jet::decodeCommand(f, c), jet::Error::kNotOurs);
  EXPECT_EQ(jet::decodeStatus(f, st), jet::Error::kNotOurs);
  // The port jet's payload under the starboard jet's id fails the CRC (the destination is in it).
  CanFrame moved = g;
  std::copy(f.data.begin(), f.data.begin() + 8, moved.data.begin());
  EXPECT_EQ(jet::decodeSetpoint(moved, back), jet::Error::kChecksum);
  // Proprietary A to another device is not ours; other addresses move the jets.
  n2k::IsoId other = n2k::decodeId(f.id);
  other.destination = 0x50;
  CanFrame h = f;
  h.id = n2k::encodeId(other);
  EXPECT_EQ(jet::decodeSetpoint(h, back), jet::Error::kNotOurs);
  jet::Addresses moved_jets;
  moved_jets.jet_base = 0x50;
  EXPECT_EQ(jet::decodeSetpoint(h, back, moved_jets), jet::Error::kChecksum);  // its CRC was for 0x30
  // Wrong length, and out of range with a valid CRC: rpm 6001, nozzle beyond full scale, source 5, bit 7.
  h = f;
  h.len = 7;
  EXPECT_EQ(jet::decodeSetpoint(h, back), jet::Error::kLength);
  auto resealed = [&](int byte, std::uint16_t v) {
    CanFrame k = f;
    if (byte == 6) k.data[6] = static_cast<std::uint8_t>(v);
    else putU16(&k.data[byte], v);
    k.data[7] = jet::crc(0x30, k.data.data());
    return k;
  };
  EXPECT_EQ(jet::decodeSetpoint(resealed(0, 6001), back), jet::Error::kRange);
  EXPECT_EQ(jet::decodeSetpoint(resealed(2, static_cast<std::uint16_t>(-32001)), back), jet::Error::kRange);
  EXPECT_EQ(jet::decodeSetpoint(resealed(4, 32001), back), jet::Error::kRange);
  EXPECT_EQ(jet::decodeSetpoint(resealed(6, 0x55), back), jet::Error::kRange);
  EXPECT_EQ(jet::decodeSetpoint(resealed(6, 0x85), back), jet::Error::kRange);
  EXPECT_EQ(jet::decodeSetpoint(resealed(0, 6000), back), jet::Error::kNone);
  // Non-finite or out-of-range values never reach the bus as garbage.
  jet::Setpoint bad;
  bad.rpm = std::nan("");
  bad.nozzle = 3.0;
  bad.bucket = -INFINITY;
  ASSERT_EQ(jet::decodeSetpoint(jet::encodeSetpoint(bad), back), jet::Error::kNone);
  EXPECT_EQ(back.rpm, 0.0);
  EXPECT_EQ(back.nozzle, 1.0);
  EXPECT_EQ(back.bucket, 0.0);
}

TEST(Waterjet, CounterCheck) {
  jet::CounterCheck cc;
  EXPECT_TRUE(cc.accept(1, 14));
  EXPECT_TRUE(cc.accept(1, 15));
  EXPECT_TRUE(cc.accept(1, 0));   // wraps mod 16
  EXPECT_FALSE(cc.accept(1, 5));  // jump: rejected once
  EXPECT_TRUE(cc.accept(1, 6));   // resynchronised
  EXPECT_TRUE(cc.accept(2, 9));   // per sender
}

TEST(Candump, ParseAndFormat) {
  auto l = parseCandump("(1700000000.250000) can0 09F80102#F8A1A024F073240E");
  ASSERT_TRUE(l);
  EXPECT_DOUBLE_EQ(l->stamp, 1700000000.25);
  EXPECT_EQ(l->iface, "can0");
  EXPECT_TRUE(l->frame.extended);
  EXPECT_EQ(l->frame.len, 8);
  l = parseCandump("vcan0 123#R");
  ASSERT_TRUE(l);
  EXPECT_TRUE(l->frame.rtr);
  EXPECT_FALSE(l->frame.extended);
  l = parseCandump("(1.0) can0 20000040#0000000000000000");  // bus-off error frame
  ASSERT_TRUE(l);
  EXPECT_TRUE(l->frame.error);
  EXPECT_EQ(l->frame.id, 0x40u);
  l = parseCandump("can0 1F334455##1" + std::string(24, 'A'));  // FD, 12 bytes
  ASSERT_TRUE(l);
  EXPECT_TRUE(l->frame.fd);
  EXPECT_EQ(l->frame.len, 12);
  std::string err;
  for (const char* bad : {"", "(1.0", "(x) can0 123#00", "(nan) can0 123#00", "() can0 123#00", "can0 12#00", "can0 123#0", "can0 123#GG",
                          "can0 123#001122334455667788", "can0 FFFFFFFFF#00", "can0 1F334455##1AABBCCDDEEFF001122",
                          "can0"}) {
    EXPECT_FALSE(parseCandump(bad, &err)) << bad;
  }
}

TEST(Decode, JsonForEveryKind) {
  std::string err;
  auto json = [&](const std::string& s) { return decodeToJson(*parseCandump("(2.5) can0 " + s), {}, &err); };
  auto j = json("09F80102#F8A1A024F073240E");
  ASSERT_TRUE(j);
  EXPECT_NE(j->find("\"pgn\":129025"), std::string::npos);
  EXPECT_NE(j->find("\"latitude_deg\":61.4507"), std::string::npos);
  j = json("09F11240#055C3DFF7FF4FDFC");
  ASSERT_TRUE(j);
  EXPECT_NE(j->find("\"deviation_rad\":null"), std::string::npos);
  jet::Status s;
  s.rpm = 900;
  j = json(formatCansend(jet::encodeStatus(s)));
  ASSERT_TRUE(j);
  EXPECT_NE(j->find("\"rpm\":900"), std::string::npos);
  EXPECT_FALSE(json("09F11240#055C3D"));
  EXPECT_EQ(err, "wrong_dlc");
  EXPECT_FALSE(json("18EEFF05#0102030405060708"));
  EXPECT_EQ(err, "unknown_id");
  EXPECT_FALSE(json("0CFF1020#0000000000000000"));
  EXPECT_EQ(err, "bad_checksum");
  j = json("0CEF3120#B004C0E0803E05FD");  // the port jet's frame under the starboard jet's id
  EXPECT_FALSE(j);
  EXPECT_EQ(err, "bad_checksum");
  j = json("0CEF3020#B004C0E0803E05FD");
  ASSERT_TRUE(j);
  EXPECT_NE(j->find("\"name\":\"waterjet_setpoint\",\"jet\":0,\"rpm\":1200,\"nozzle\":-0.25,\"bucket\":0.5,\"source\":0,"
                    "\"counter\":5}"),
            std::string::npos)
      << *j;
  EXPECT_FALSE(json("0CEF5020#B004C0E0803E05FD"));  // Proprietary A to another device
  EXPECT_EQ(err, "unknown_id");
}

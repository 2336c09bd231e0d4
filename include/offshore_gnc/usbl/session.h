#pragma once
// The USV's SeaTrac transceiver session, as the USBL node runs it: a ping to the AUV's beacon every ping period,
// one transaction at a time (the transceiver handles one), the reply awaited for reply_timeout, acoustic data
// packets queued and sent with DAT_SEND between pings. Fed the decoded serial events and the time; says what to
// write and hands out the fixes and data that came back. The Usbl nodelet's I/O thread and the ROS-free loops
// both run exactly this. ROS-free.
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/usbl/seatrac.h"

namespace offshore_gnc {
namespace usbl {

struct SessionParams {
  int remote_id = 2;              // the AUV's beacon
  double ping_rate = 0.5;         // pings per second [Hz]
  double reply_timeout = 3.0;     // a ping or data request unanswered this long counts as no reply [s]
  std::string ping_msg_type = "REQU";  // REQ | REQU | REQX: the reply's contents (fix only, + USBL, + extended)
  std::string data_msg_type = "REQ";   // OWAY (no reply) | REQ (the remote answers with its queued packet)
  int max_queued = 16;            // data packets waiting beyond this: the oldest is dropped
  static const ParamTable<SessionParams>& table();
  void validate() const;
};

// What one serial event gave.
struct SessionEvent {
  enum Kind { kNone, kFix, kData } kind = kNone;
  AcoFix fix;                      // kFix, kData: the acoustic fix of the sender
  std::vector<std::uint8_t> data;  // kData
};

class TransceiverSession {
 public:
  explicit TransceiverSession(const SessionParams& p);
  const SessionParams& params() const { return p_; }

  // A packet for the acoustic data channel (1..kMaxDataPacket bytes); false and counted when it cannot be sent.
  bool queueData(std::vector<std::uint8_t> data);
  // A decoded serial event at time t (rejected frames are counted by the decoder).
  SessionEvent handle(const StreamDecoder::Event& e, double t);
  // The frame to write now, if any (the line must be open); call sent() when the write succeeded.
  std::optional<Message> due(double t);
  void sent(const Message& m, double t);

  bool awaiting() const { return awaiting_; }
  const Counters& counters() const { return counters_; }  // pings_sent, no_reply, ping_timeouts, data_*...

 private:
  SessionParams p_;
  std::uint8_t ping_type_ = MSG_REQU, data_type_ = MSG_REQ;
  std::deque<std::vector<std::uint8_t>> data_out_;
  bool awaiting_ = false;
  double sent_at_ = 0.0, next_ping_ = 0.0;
  bool started_ = false;
  Counters counters_;
};

}  // namespace usbl
}  // namespace offshore_gnc

#include "offshore_gnc/usbl/session.h"

#include <algorithm>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace usbl {

const ParamTable<SessionParams>& SessionParams::table() {
  using P = SessionParams;
  static const ParamTable<P> t = ParamTable<P>()
      .integer("remote_beacon_id", &P::remote_id, 1, 15, "beacon id of the AUV's modem")
      .number("ping_rate", &P::ping_rate, 0.01, 5.0, "Hz", "pings to the AUV's beacon per second")
      .number("reply_timeout", &P::reply_timeout, 0.1, 30.0, "s", "a transaction unanswered this long: no reply")
      .choice("ping_msg_type", &P::ping_msg_type, {"REQ", "REQU", "REQX"},
              "ping reply contents: range only, + USBL angles, + extended fix")
      .choice("data_msg_type", &P::data_msg_type, {"OWAY", "REQ"},
              "data packets one way, or answered with the remote's queued packet")
      .integer("max_queued", &P::max_queued, 1, 1000, "data packets waiting beyond this: the oldest is dropped");
  return t;
}

void SessionParams::validate() const { table().validate(*this); }

TransceiverSession::TransceiverSession(const SessionParams& p) : p_(p) {
  p_.validate();
  ping_type_ = p_.ping_msg_type == "REQ" ? MSG_REQ : p_.ping_msg_type == "REQX" ? MSG_REQX : MSG_REQU;
  data_type_ = p_.data_msg_type == "OWAY" ? MSG_OWAY : MSG_REQ;
}

bool TransceiverSession::queueData(std::vector<std::uint8_t> data) {
  if (data.empty() || data.size() > kMaxDataPacket) {
    counters_.increment("data_too_long");
    return false;
  }
  // The channel carries about one packet per ping cycle: keep the newest.
  if (static_cast<int>(data_out_.size()) >= p_.max_queued) {
    data_out_.pop_front();
    counters_.increment("data_dropped");
  }
  data_out_.push_back(std::move(data));
  return true;
}

SessionEvent TransceiverSession::handle(const StreamDecoder::Event& e, double t) {
  (void)t;
  SessionEvent out;
  if (!e.message) return out;
  const auto remote = static_cast<std::uint8_t>(p_.remote_id);
  const auto& body = e.message->body;
  if (auto s = std::get_if<StatusReply>(&body)) {
    const bool data = s->cid == CID_DAT_ERROR || s->cid == CID_DAT_SEND;
    if (s->cid == CID_PING_ERROR || s->cid == CID_DAT_ERROR) {
      awaiting_ = false;
      counters_.increment(std::string(data ? "data" : "ping") +
                          (s->status == kStatusXcvrRespTimeout ? "_timeouts" : "_errors"));
    } else if ((s->cid == CID_PING_SEND || data) && s->status != kStatusOk) {
      awaiting_ = false;
      counters_.increment(data ? "data_errors" : "ping_errors");
    }
  } else if (auto f = std::get_if<FixMessage>(&body)) {
    if (f->fix.src_id == remote) awaiting_ = false;
    out.kind = SessionEvent::kFix;
    out.fix = f->fix;
  } else if (auto d = std::get_if<DatReceive>(&body)) {
    if (d->fix.src_id == remote) awaiting_ = false;
    counters_.increment("data_received");
    out.kind = SessionEvent::kData;  // a data message is also an acoustic fix of its sender
    out.fix = d->fix;
    out.data = d->data;
  }
  return out;
}

std::optional<Message> TransceiverSession::due(double t) {
  if (!started_) {  // the first ping goes out one period after the start, as a timer's would
    started_ = true;
    next_ping_ = t + 1.0 / p_.ping_rate;
  }
  if (awaiting_ && t - sent_at_ > p_.reply_timeout) {
    awaiting_ = false;
    counters_.increment("no_reply");
  }
  if (awaiting_) return std::nullopt;
  const auto remote = static_cast<std::uint8_t>(p_.remote_id);
  if (!data_out_.empty()) return Message{true, DatSend{remote, data_type_, data_out_.front()}};
  if (t >= next_ping_) return Message{true, PingSend{remote, ping_type_}};
  return std::nullopt;
}

void TransceiverSession::sent(const Message& m, double t) {
  sent_at_ = t;
  if (auto d = std::get_if<DatSend>(&m.body)) {
    if (!data_out_.empty()) data_out_.pop_front();
    awaiting_ = d->msg_type != MSG_OWAY;
    counters_.increment("data_sent");
  } else if (std::get_if<PingSend>(&m.body)) {
    awaiting_ = true;
    // Pings keep their schedule; one that could not go out while a transaction was open goes at once after it.
    next_ping_ = std::max(next_ping_ + 1.0 / p_.ping_rate, t);
    counters_.increment("pings_sent");
  }
}

}  // namespace usbl
}  // namespace offshore_gnc

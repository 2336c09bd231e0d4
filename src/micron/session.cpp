// Micron driver state machine (include/offshore_gnc/micron/session.h).
#include "offshore_gnc/micron/session.h"

#include <algorithm>
#include <cmath>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace micron {

namespace {
constexpr double kAdIntervalS = 640e-9;  // unit of ADInterval
constexpr double kUnitRad = 2.0 * kPi / kAngleUnitsPerTurn;
}  // namespace

double HeadGeometry::bearingOf(int head_units) const {
  const double a = unitsToRad(head_units) - forward_offset;
  return wrapTwoPi(inverted ? -a : a);
}

int HeadGeometry::unitsOf(double bearing) const { return radToUnits(forward_offset + (inverted ? -bearing : bearing)); }

const ParamTable<HeadGeometry>& HeadGeometry::table() {
  using G = HeadGeometry;
  static const ParamTable<G> t = ParamTable<G>()
      .degrees("forward_offset_deg", &G::forward_offset, 0.0, 360.0,
               "head angle along the AUV's x axis (SeaNet: 3200/6400 of a turn = 180)")
      .flag("inverted", &G::inverted, "head mounted boot down (head angles run anticlockwise)");
  return t;
}

const ParamTable<SonarSettings>& SonarSettings::table() {
  using S = SonarSettings;
  static const ParamTable<S> t =
      ParamTable<S>()
          .number("range", &S::range, 0.3, 75.0, "m", "the Micron's 0.3 .. 75 m")
          .degrees("sector_deg", &S::sector, 1.8, 360.0, "centred on forward; 360 = continuous rotation")
          .degrees("step_deg", &S::step, 0.05625, 14.3, "motor step per ping (1 .. 255 units; 0.45, 0.9, 1.8, 3.6)")
          .integer("bins", &S::bins, 8, 1500, "samples per beam")
          .number("gain", &S::gain, 0.0, 1.0, "", "initial receiver gain (0 .. 80 dB)")
          .number("ad_low_db", &S::ad_low, 0.0, 80.0, "dB", "echo level mapped to intensity 0")
          .number("ad_span_db", &S::ad_span, 1.0, 80.0, "dB", "... and to 255 above ad_low_db (the sum at most 80)")
          .number("sound_speed", &S::sound_speed, 1300.0, 1700.0, "m/s", "fresh water ~1480, sea water ~1500-1520")
          .degrees("beam_width_deg", &S::beam_width, 0.1, 60.0, "horizontal beam width (not in the protocol)")
          .nest("", &S::geometry, HeadGeometry::table())
          .nest("", &S::four_bit, FourBitFormat::table())
          .integer("head_type", &S::head_type, 0, 255, "0x11 = DST (Micron)")
          .integer("mo_time", &S::mo_time, 1, 255, "motor step delay [10 us]")
          .flag("reboot_on_start", &S::reboot_on_start, "mtReBoot before the bring-up")
          .number("reply_timeout", &S::reply_timeout, 0.05, 30.0, "s", "for mtHeadData after mtSendData")
          .number("command_retry", &S::command_retry, 0.05, 60.0, "s",
                  "between mtSendVersion / mtHeadCommand attempts")
          .number("alive_timeout", &S::alive_timeout, 0.5, 60.0, "s", "without any packet: the head is reported silent")
          .integer("max_data_timeouts", &S::max_data_timeouts, 1, 1000,
                   "reply timeouts in a row before the head command is sent again");
  return t;
}

const ParamTable<DriverConfig>& DriverConfig::table() {
  using D = DriverConfig;
  static const ParamTable<D> t =
      ParamTable<D>()
          .string("port", &D::port, "the head's serial device")
          .integer("baud", &D::baud, 9600, 230400, "the line's speed")
          .number("reconnect_period", &D::reconnect_period, 0.05, 60, "s",
                  "between reopen attempts of a vanished device")
          .number("device_wait", &D::device_wait, 0, 120, "s",
                  "the device must appear within this at start, or the node fails naming it")
          .string("frame_id", &D::frame_id, "the beams' frame (x forward, y starboard, z down)")
          .string("base_frame", &D::base_frame, "the AUV's body frame the head is mounted in")
          .numbers("mount", &D::mount, 3, -10, 10, "m", "head in the AUV's body frame, x forward, y starboard, z down")
          .flag("publish_mount_tf", &D::publish_mount_tf, "the mount as a static transform")
          .nest("", &D::sonar, SonarSettings::table());
  return t;
}

void SonarSettings::validate() const {
  table().validate(*this);
  requireRange("ad_low_db + ad_span_db", ad_low + ad_span, 1.0, 80.0);
  if (sector < 2.0 * kPi - 1e-9 && stepUnits() > radToUnits(sector))
    throw ConfigError("parameter 'step_deg' = " + std::to_string(rad2deg(step)) + " is larger than the sector");
  const double interval = 2.0 * range / sound_speed / bins / kAdIntervalS;
  if (interval < 5.0 || interval > 65535.0)
    throw ConfigError("parameters 'range' / 'bins' give a sampling interval of " + std::to_string(interval) +
                      " x 640 ns, outside the head's 5 .. 65535 (fewer bins or a longer range)");
}

int SonarSettings::stepUnits() const { return std::clamp(static_cast<int>(std::lround(step / kUnitRad)), 1, 255); }

double SonarSettings::binSize(std::uint16_t ad_interval) const { return ad_interval * kAdIntervalS * sound_speed / 2.0; }

HeadCommand SonarSettings::headCommand() const {
  HeadCommand c;
  const bool continuous = sector >= 2.0 * kPi - 1e-9;
  c.hd_ctrl = kAdc8On | kRaw | kHasMot | kReplyAsl | kScanRight | (continuous ? kCont : 0);
  c.head_type = static_cast<std::uint8_t>(head_type);
  c.range_scale = static_cast<std::uint16_t>(std::lround(range * 10.0)) & 0x3FFF;  // metres
  // The sector is centred on forward; the limits are head angles (inversion handled by geometry).
  c.left_limit = static_cast<std::uint16_t>(geometry.unitsOf(geometry.inverted ? sector / 2 : -sector / 2));
  c.right_limit = static_cast<std::uint16_t>(geometry.unitsOf(geometry.inverted ? -sector / 2 : sector / 2));
  c.ad_low = static_cast<std::uint8_t>(std::lround(255.0 * ad_low / 80.0));
  c.ad_span = static_cast<std::uint8_t>(std::lround(255.0 * ad_span / 80.0));
  c.igain_ch1 = c.igain_ch2 = static_cast<std::uint8_t>(std::lround(gain * 210.0));
  c.mo_time = static_cast<std::uint8_t>(mo_time);
  c.step_angle = static_cast<std::uint8_t>(stepUnits());
  c.ad_interval = static_cast<std::uint16_t>(std::lround(2.0 * range / sound_speed / bins / kAdIntervalS));
  c.nbins = static_cast<std::uint16_t>(bins);
  return c;
}

Session::Session(const SonarSettings& s) : settings_(s) {
  settings_.validate();
  command_ = settings_.headCommand();
}

const char* Session::stateName(State s) {
  switch (s) {
    case State::Start: return "start";
    case State::AwaitAlive: return "waiting for mtAlive";
    case State::AwaitVersion: return "waiting for mtVersionData";
    case State::Configuring: return "configuring (mtHeadCommand)";
    case State::Scanning: return "scanning";
  }
  return "?";
}

void Session::enter(State s) {
  state_ = s;
  last_sent_ = -1e9;  // send the state's command at the next poll
  awaiting_ = false;
  timeouts_in_row_ = 0;
}

void Session::reset() {
  enter(State::Start);
  have_prev_ = false;
  direction_ = 0;
}

void Session::feed(const std::uint8_t* data, std::size_t n, double now, std::vector<Beam>& beams) {
  events_.clear();
  decoder_.feed(data, n, events_);
  for (const auto& e : events_)
    if (e.message) handle(*e.message, now, beams);
}

void Session::handle(const Message& m, double now, std::vector<Beam>& beams) {
  last_packet_ = now;
  heard_ = true;
  if (auto a = std::get_if<Alive>(&m.body)) {
    alive_ = *a;
    counters_.increment("alives");
    const bool no_params = a->head_inf & kNoParams;
    if (state_ == State::AwaitAlive) {
      enter(State::AwaitVersion);
    } else if (state_ == State::Configuring && !no_params && (a->head_inf & kSentCfg)) {
      enter(State::Scanning);
    } else if (state_ == State::Scanning && no_params) {
      counters_.increment("head_resets");  // power-cycled or reset: parameters lost
      enter(State::AwaitVersion);
    }
  } else if (auto v = std::get_if<VersionData>(&m.body)) {
    version_ = *v;
    if (state_ == State::AwaitVersion || state_ == State::AwaitAlive) enter(State::Configuring);
  } else if (auto h = std::get_if<HeadData>(&m.body)) {
    if (state_ != State::Scanning) {
      counters_.increment("unexpected_head_data");
      return;
    }
    awaiting_ = false;
    timeouts_in_row_ = 0;
    Beam b;
    b.intensities = h->bins(settings_.four_bit);
    if (b.intensities.empty()) return counters_.increment("empty_beams");
    b.bearing = settings_.geometry.bearingOf(h->bearing);
    b.beam_width = settings_.beam_width;
    b.range_resolution = h->ad_interval ? settings_.binSize(h->ad_interval) : h->rangeScaleM() / b.intensities.size();
    b.range_offset = b.range_resolution / 2;
    b.head_status = h->head_status;
    b.sweep_code = h->sweep_code;
    if (!(h->head_status & kHdPwrLoss)) b.status |= kHeadReady;
    else counters_.increment("power_loss");
    if ((h->hd_ctrl & kHasMot) && !(h->hd_ctrl & kMotOff)) b.status |= kMotorOnBit;
    if (h->head_status & kMotErr) {
      b.status |= kFault;
      counters_.increment("motor_errors");
      enter(State::Configuring);  // the head asks for its parameters again after losing motor sync
    }
    if (alive_.head_inf & kInCentre) b.status |= kCentring;
    if (have_prev_) {
      const double d = angleDiff(b.bearing, prev_bearing_);
      const int dir = d > 1e-9 ? 1 : (d < -1e-9 ? -1 : 0);
      if (dir != 0 && direction_ != 0 && dir != direction_) b.status |= kSectorReverse;
      if (dir != 0) direction_ = dir;
    }
    if (direction_ > 0) b.status |= kScanCw;
    have_prev_ = true;
    prev_bearing_ = b.bearing;
    counters_.increment("beams");
    beams.push_back(std::move(b));
  } else if (std::get_if<HeadCommand>(&m.body) || std::get_if<SendData>(&m.body) || std::get_if<Command>(&m.body)) {
    counters_.increment("echoed_commands");  // our own commands looped back (wiring fault) or a second PC
  } else {
    counters_.increment("other_packets");
  }
}

std::string Session::poll(double now, std::uint32_t time_of_day_ms) {
  if (!heard_) last_packet_ = now;  // the silence timer starts with the session
  switch (state_) {
    case State::Start:
      enter(State::AwaitAlive);
      if (settings_.reboot_on_start) {
        counters_.increment("reboots_sent");
        return encode(fromPc(Command{mtReBoot}));
      }
      return {};
    case State::AwaitAlive:
      return {};
    case State::AwaitVersion:
      if (now - last_sent_ < settings_.command_retry) return {};
      last_sent_ = now;
      counters_.increment("version_requests");
      return encode(fromPc(Command{mtSendVersion}));
    case State::Configuring:
      if (now - last_sent_ < settings_.command_retry) return {};
      last_sent_ = now;
      counters_.increment("head_commands");
      return encode(fromPc(command_));
    case State::Scanning:
      if (awaiting_ && now - last_sent_ > settings_.reply_timeout) {
        awaiting_ = false;
        counters_.increment("data_timeouts");
        if (++timeouts_in_row_ >= settings_.max_data_timeouts) {
          counters_.increment("reconfigures");
          enter(State::Configuring);
          return poll(now, time_of_day_ms);
        }
      }
      if (awaiting_) return {};
      awaiting_ = true;
      last_sent_ = now;
      counters_.increment("data_requests");
      return encode(fromPc(SendData{time_of_day_ms}));
  }
  return {};
}

}  // namespace micron
}  // namespace offshore_gnc

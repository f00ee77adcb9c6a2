// The LCM side of every gpilot process: typed publish/subscribe with counted rejection of malformed or
// invalid messages, timers, HEALTH once a second, and a clean stop on SIGINT/SIGTERM.
//
// A handler sees only messages that decoded exactly (LCM 1.3.1's generated decoders throw on a negative or
// zero length: caught; a datagram with bytes after the message is not this message) and passed
// check_message(); anything else is counted in HEALTH (rejected, last_reject_reason) and never reaches the
// stage. A handler's throw never unwinds through LCM's C dispatch, and the process keeps running: an
// InputError (input_error.hpp: the message is unusable) is a counted rejection like bytes that do not decode;
// anything else (std::logic_error, cv::Exception, std::bad_alloc, ...) is a defect of the process, not of
// the message: logged at error level, and HEALTH says ERROR from then on (StageStats::failed).
#pragma once

#include <cstdint>
#include <exception>
#include <functional>
#include <map>
#include <memory>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bus_params.hpp"
#include "bus_signature.hpp"
#include "clock.hpp"
#include "input_error.hpp"
#include "gpilot/flight_control_t.hpp"
#include "message_checks.hpp"
#include "stream_guard.hpp"
#include "stage_stats.hpp"
#include "wire_lengths.hpp"

namespace gpilot {

// Decodes size bytes as Msg, exactly: "" when they are one whole message, else why not (the decoder threw,
// failed, or left trailing bytes). Never throws.
template <class Msg>
std::string decode_exactly(const void* data, size_t size, Msg& msg) {
  const auto not_a = [&](const std::string& why) {
    return std::to_string(size) + " bytes do not decode as gpilot." + Msg::getTypeName() + why;
  };
  if (size > static_cast<size_t>(INT32_MAX)) return std::to_string(size) + " bytes: too large for one LCM message";
  const std::string lengths = size >= 8 ? check_wire_lengths<Msg>(data, size) : std::string();
  if (!lengths.empty()) return not_a(": " + lengths);
  int used = -1;
  try {
    used = msg.decode(data, 0, static_cast<int>(size));
  } catch (const std::exception& e) {
    return not_a(std::string(": a length field is out of range (") + e.what() + ")");
  }
  if (used < 0) return not_a(" (truncated, malformed or another type)");
  if (static_cast<size_t>(used) != size)
    return std::to_string(size) + " bytes hold a gpilot." + Msg::getTypeName() + " of " + std::to_string(used) +
           " bytes and trailing bytes";
  return "";
}

// A subscription's message is decoded into again and again. LCM's decoders write every field but leave a
// variable array of length 0 as it was: a message starts afresh (its few small vectors freed), except a
// frame, whose pixel vector keeps its capacity (resize to the same size neither allocates nor fills) and is
// emptied after a decode that found no bytes.
template <class Msg>
void before_reused_decode(Msg& msg) {
  msg = Msg{};
}
inline void before_reused_decode(image_t&) {}
template <class Msg>
void after_reused_decode(Msg&) {}
inline void after_reused_decode(image_t& msg) {
  if (msg.size == 0) msg.data.clear();
}

// Which publisher's stream a message belongs to, where one channel has several (beside the signer's id).
template <class Msg>
std::string stream_of(const Msg&) {
  return "";
}
inline std::string stream_of(const health_t& m) { return m.name + "/" + std::to_string(m.pid); }
inline std::string stream_of(const flight_control_t& m) { return m.source; }

// True for an LCM URL that can reach other hosts (udpm with ttl > 0): such a bus needs a key.
bool url_leaves_host(const std::string& url);

class BusError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Default: host only (ttl=0), with a receive buffer that holds 1280x720 BGR frames at 30 Hz (STACK.md).
constexpr const char* kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";

// --lcm-url if given, else $GPILOT_LCM_URL, else kDefaultLcmUrl.
std::string resolve_lcm_url(const std::string& flag);

// The recv_buf_size asked for in an LCM URL, or 0 if none.
int64_t recv_buf_size_of(const std::string& url);

// Where the frames (bus.frames_channels) travel beside the bus `url`: bus.frames_url when set, else for a
// udpm:// URL the same group and options on port + 1, else (memq://, udp://, file://: one process or one
// peer) `url` itself. The same answer in every process, in gpilot-launch's ${frames_url} (the frames' logger)
// and deploy/spy.
std::string frames_url_for(const std::string& url, const BusParams& params);

class BusNode {
 public:
  // Throws BusError when LCM cannot start (no multicast route, bad URL), when a key cannot be read, or on
  // a bus that leaves the host without a key. Warns once on stderr when the kernel's net.core.rmem_max is
  // below the URL's recv_buf_size. $GPILOT_BUS_KEY, when set, is the key file (over bus.key_file).
  // With a key, every message sent is signed and every message received must be (bus_signature.hpp).
  // Per-stream order and freshness (stream_guard.hpp) are checked on a network bus and in replay.
  // The channels of bus.frames_channels are sent and received on frames_url_for(url, params) when that is
  // another URL: its LCM is opened on first use, so a process that never touches a frame channel has no
  // socket on it (and the kernel copies no frame to it).
  BusNode(std::string name, const std::string& url, const BusParams& params = BusParams{});
  ~BusNode();
  BusNode(const BusNode&) = delete;
  BusNode& operator=(const BusNode&) = delete;

  // handler(msg, receive_utime) runs on the loop thread for each valid message; receive_utime is on the
  // node's clock (the log's time in replay). queue_capacity > 0 bounds
  // LCM's queue for this channel (its default is 30): a slow stage then skips messages instead of falling
  // behind. LCM 1.3.1 drops the arrivals that find the queue full (not the oldest queued), before this node
  // sees them, so the stage counts its own gaps (seq: common/seq_gaps.hpp).
  // Each subscription decodes into one message object of its own, reused (a frame's pixel vector keeps its
  // capacity: no fresh 921 kB allocation and its page faults per 640x480 frame).
  template <class Msg>
  void subscribe(const std::string& channel, std::function<void(const Msg&, int64_t)> handler,
                 int queue_capacity = 0) {
    subscribe_taking<Msg>(channel, std::function<void(Msg&, int64_t)>(std::move(handler)), queue_capacity);
  }
  // The same, for a handler that keeps the message past its call without copying it: it may move or swap
  // the message's contents out (a stage pairing frames with tracks); the next message is decoded into what
  // it leaves there (hand back a used buffer of the same size to keep the decode free of allocations).
  template <class Msg>
  void subscribe_taking(const std::string& channel, std::function<void(Msg&, int64_t)> handler,
                        int queue_capacity = 0);

  // Encodes msg into a reused buffer and sends it (signed when the node has a bus key).
  template <class Msg>
  void publish(const std::string& channel, const Msg& msg) {
    send(channel, msg);
    stats_.published();
  }
  // The process's own reports (CONFIG at start): sent like any message, not counted as the stage's output.
  template <class Msg>
  void publish_report(const std::string& channel, const Msg& msg) {
    send(channel, msg);
  }

  // Publishes raw bytes (tools and tests that must send malformed data).
  void publish_raw(const std::string& channel, const void* data, size_t size);

  // Every message on channel (a regex in LCM's sense), undecoded: fn(channel, data, size, receive_utime).
  // For tools that record or forward (gpilot-replay, gpilot-record); stages use the typed subscribe. On both
  // the bus and the frames URL (the pattern may match either's channels); queue_capacity as subscribe's.
  using RawHandler = std::function<void(const std::string&, const void*, size_t, int64_t)>;
  void subscribe_raw(const std::string& channel, RawHandler fn, int queue_capacity = 0);

  // Dispatches every message already queued (memq:// replay), then runs the idle work (when_idle); returns
  // how many messages were handled.
  int drain();

  // Work done from the loop once no message is waiting: after spin_once has dispatched every message that had
  // arrived (up to kMaxMessagesBeforeIdle of them), and at the end of drain(). A stage slower than its input
  // keeps only its newest unit of work in its handlers (a newer one replaces it, counted) and does it here, so
  // it answers the newest frame rather than working through frames gone stale in the queue. fn returns true
  // when it did work: its time is counted as processing time. It runs like a handler (an InputError rejects,
  // any other throw is the process's failure); `what` names it there.
  void when_idle(const std::string& what, std::function<bool()> fn) { idle_.push_back(Idle{what, std::move(fn)}); }
  // The messages spin_once dispatches before it runs the idle work even if more keep coming.
  static constexpr int kMaxMessagesBeforeIdle = 64;

  // Runs fn every period_s seconds from the loop, on the timer clock (the monotonic clock unless a test set
  // its own). In replay (the node on the log's clock, set_log_time) timers never fire by themselves: the
  // replay fires them with run_timers_at at the instants the live process's did (a timer's output is stamped
  // with now(), so the log says when).
  void every(double period_s, std::function<void()> fn);
  // The clock the loop's timers run on (µs, never jumping back): monotonic_utime unless replaced. A test
  // moves its own clock by hand and calls spin_once(0): the timers fire by that clock, not by how long the
  // test happened to take. Set it before the first every().
  using TimerClock = std::function<int64_t()>;
  void set_timer_clock(TimerClock clock) { timer_clock_ = std::move(clock); }
  // Replay: the live process's timers fired at utime. Sets the clock to utime and runs every timer once (a
  // replayed stage has one: gpilot-flight's setpoint tick, its other timers belong to backends not replayed).
  void run_timers_at(int64_t utime);

  // A stage found an input unusable (bad image, unmatched frame): counted and reported in HEALTH.
  void reject(const std::string& reason) { stats_.rejected(reason); }
  void drop() { stats_.dropped(); }
  void set_state(int8_t health_state, const std::string& detail);

  // Loops until SIGINT/SIGTERM or stop(); publishes HEALTH once a second and a last one on the way out.
  void run();
  // One loop step: handles messages for up to timeout_ms and runs due timers. False once stopping.
  bool spin_once(int timeout_ms);
  void stop();
  bool stopping() const;

  // The node's clock, on the message time base (µs since the epoch): the wall clock live; in replay, the
  // time of the log event being dispatched (set_log_time), so time checks and stamps replay exactly.
  int64_t now() const { return log_time_ >= 0 ? log_time_ : wall_utime(); }
  void set_log_time(int64_t utime) { log_time_ = utime; }

  const std::string& name() const { return name_; }
  const std::string& url() const { return url_; }
  const std::string& frames_url() const { return frames_url_; }
  // True when channel is sent and received on frames_url() (bus.frames_channels, and another URL).
  bool on_frames_bus(const std::string& channel);
  bool signs() const { return signer_ != nullptr; }
  StageStats& stats() { return stats_; }
  void publish_health();

 private:
  struct SubscriptionBase {
    virtual ~SubscriptionBase() = default;
  };
  template <class Msg>
  struct TypedSubscription : SubscriptionBase {
    BusNode* node;
    std::string channel;
    std::function<void(Msg&, int64_t)> handler;
    Msg msg{};            // decoded into, message after message
    bool in_use = false;  // a handler that dispatches again (drain) gets a fresh message, not this one
  };
  struct Idle {
    std::string what;
    std::function<bool()> fn;
  };
  bool run_idle();  // true when some idle work was done
  struct Timer {
    int64_t period_us;
    int64_t next_us;
    std::function<void()> fn;
  };

  struct RawSubscription : SubscriptionBase {
    BusNode* node;
    RawHandler fn;
  };
  static void on_any(const lcm::ReceiveBuffer* rbuf, const std::string& channel, RawSubscription* sub);
  // Runs a handler: an InputError rejects the message, any other throw is the process's failure (logged).
  template <class Fn>
  void run_handler(const std::string& channel, Fn&& handler);
  void handler_failed(const std::string& channel, const std::string& what);

  template <class Msg>
  static void on_raw(const lcm::ReceiveBuffer* rbuf, const std::string& channel, TypedSubscription<Msg>* sub);
  void run_due_timers();
  // Waits up to timeout_ms for a message on the bus or (when subscribed) the frames URL and handles it:
  // > 0 handled, 0 none, < 0 LCM failed.
  int handle_for(int timeout_ms);
  template <class Msg>
  void send(const std::string& channel, const Msg& msg) {
    const int size = msg.getEncodedSize();
    out_.resize(static_cast<size_t>(size) + kMaxTrailerBytes);
    msg.encode(out_.data(), 0, size);
    send_encoded(channel, static_cast<size_t>(size));
  }
  void send_encoded(const std::string& channel, size_t size);
  // The message bytes of a received datagram (after the bus signature, when there is one, is verified and
  // stripped), or a reason to reject it.
  struct Opened {
    const void* data = nullptr;
    size_t size = 0;
    std::string why;
    uint64_t sender = 0;  // the signer's id (0: unsigned)
  };
  Opened open(const std::string& channel, const lcm::ReceiveBuffer& rbuf);
  // The per-stream rules (seq moves forward, utime near the arrival time): "" or why not.
  std::string check_stream(const std::string& channel, int64_t utime, int64_t seq, int64_t arrival_utime);
  int64_t arrival_time(const lcm::ReceiveBuffer& rbuf) const { return log_time_ >= 0 ? log_time_ : rbuf.recv_utime; }

  static constexpr size_t kMaxTrailerBytes = kSignatureBytes;
  std::vector<uint8_t> out_;
  int64_t log_time_ = -1;
  std::unique_ptr<BusSigner> signer_;
  std::unique_ptr<BusVerifier> verifier_;
  std::unique_ptr<StreamGuard> streams_;  // applied on a network bus, and in replay (on the log's clock)
  struct LastOpened {                     // one datagram dispatched to several subscriptions: one verdict
    const void* data = nullptr;
    int64_t recv_utime = 0;
    std::string channel;
    Opened opened;
  } last_opened_;

  // The LCM that carries channel: the frames' (opened now if need be) or the bus's.
  lcm::LCM& lcm_for(const std::string& channel);
  lcm::LCM& frames_lcm();

  std::string name_;
  std::string url_;
  std::string frames_url_;
  bool network_bus_;  // udpm:// or udp://: other processes' messages
  std::unique_ptr<lcm::LCM> lcm_;
  std::unique_ptr<lcm::LCM> frames_lcm_;  // opened on first use; null while unused or when frames_url_ == url_
  bool frames_subscribed_ = false;        // the loop waits on the frames' socket too
  std::regex frames_channels_;
  std::map<std::string, bool> frames_channel_cache_;  // channel -> on the frames bus (publish is per message)
  StageStats stats_;
  std::vector<std::unique_ptr<SubscriptionBase>> subs_;
  std::vector<Timer> timers_;
  std::vector<Idle> idle_;
  TimerClock timer_clock_ = monotonic_utime;
  bool stop_requested_ = false;
};

template <class Msg>
void BusNode::subscribe_taking(const std::string& channel, std::function<void(Msg&, int64_t)> handler,
                               int queue_capacity) {
  auto sub = std::make_unique<TypedSubscription<Msg>>();
  sub->node = this;
  sub->channel = channel;
  sub->handler = std::move(handler);
  const bool frames = on_frames_bus(channel);
  lcm::Subscription* s = lcm_for(channel).subscribeFunction(channel, &BusNode::on_raw<Msg>, sub.get());
  frames_subscribed_ = frames_subscribed_ || frames;
  if (queue_capacity > 0 && s) s->setQueueCapacity(queue_capacity);
  subs_.push_back(std::move(sub));
}

template <class Msg>
void BusNode::on_raw(const lcm::ReceiveBuffer* rbuf, const std::string& channel, TypedSubscription<Msg>* sub) {
  BusNode& node = *sub->node;
  const Opened opened = node.open(channel, *rbuf);
  std::string why = opened.why;
  std::unique_ptr<Msg> nested;  // only when a handler of this subscription is still running
  if (sub->in_use) nested = std::make_unique<Msg>();
  Msg& msg = nested ? *nested : sub->msg;
  before_reused_decode(msg);
  if (why.empty()) why = decode_exactly(opened.data, opened.size, msg);
  if (why.empty()) after_reused_decode(msg);
  if (why.empty()) why = check_message(msg);
  const int64_t arrival = node.arrival_time(*rbuf);
  if (why.empty() && (node.network_bus_ || node.log_time_ >= 0))
    why = node.check_stream(channel + "/" + std::to_string(opened.sender) + "/" + stream_of(msg), msg.utime, msg.seq,
                            arrival);
  if (!why.empty()) {
    node.stats_.rejected(channel + ": " + why);
    return;
  }
  node.stats_.accepted();
  const int64_t t0 = monotonic_utime();
  const bool outer = !nested;
  if (outer) sub->in_use = true;
  node.run_handler(channel, [&] { sub->handler(msg, arrival); });
  if (outer) sub->in_use = false;
  node.stats_.processing_time(monotonic_utime() - t0);
}

template <class Fn>
void BusNode::run_handler(const std::string& channel, Fn&& handler) {
  try {
    handler();
  } catch (const InputError& e) {
    stats_.rejected(channel + ": " + e.what());
  } catch (const std::exception& e) {
    handler_failed(channel, e.what());
  } catch (...) {
    handler_failed(channel, "an exception that is not a std::exception");
  }
}

}  // namespace gpilot

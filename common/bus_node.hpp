// The LCM side of every gpilot process: typed publish/subscribe with counted rejection of malformed or
// invalid messages, timers, HEALTH once a second, and a clean stop on SIGINT/SIGTERM.
//
// A handler sees only messages that decoded and passed check_message(); anything else is counted in
// HEALTH (rejected, last_reject_reason) and never reaches the stage.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "clock.hpp"
#include "message_checks.hpp"
#include "stage_stats.hpp"

namespace gpilot {

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

class BusNode {
 public:
  // Throws BusError when LCM cannot start (no multicast route, bad URL). Warns once on stderr when the
  // kernel's net.core.rmem_max is below the URL's recv_buf_size.
  BusNode(std::string name, const std::string& url);
  ~BusNode();
  BusNode(const BusNode&) = delete;
  BusNode& operator=(const BusNode&) = delete;

  // handler(msg, receive_utime) runs on the loop thread for each valid message.
  template <class Msg>
  void subscribe(const std::string& channel, std::function<void(const Msg&, int64_t)> handler);

  template <class Msg>
  void publish(const std::string& channel, const Msg& msg) {
    lcm_->publish(channel, &msg);
    stats_.published();
  }

  // Publishes raw bytes (tools and tests that must send malformed data).
  void publish_raw(const std::string& channel, const void* data, size_t size);

  // Every message on channel (a regex in LCM's sense), undecoded: fn(channel, data, size, receive_utime).
  // For tools that record or forward (gpilot-replay); stages use the typed subscribe.
  using RawHandler = std::function<void(const std::string&, const void*, size_t, int64_t)>;
  void subscribe_raw(const std::string& channel, RawHandler fn);

  // Dispatches every message already queued (memq:// replay); returns how many were handled.
  int drain();

  // Runs fn every period_s seconds from the loop, on the monotonic clock.
  void every(double period_s, std::function<void()> fn);

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

  const std::string& name() const { return name_; }
  const std::string& url() const { return url_; }
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
    std::function<void(const Msg&, int64_t)> handler;
  };
  struct Timer {
    int64_t period_us;
    int64_t next_us;
    std::function<void()> fn;
  };

  struct RawSubscription : SubscriptionBase {
    RawHandler fn;
  };
  static void on_any(const lcm::ReceiveBuffer* rbuf, const std::string& channel, RawSubscription* sub);

  template <class Msg>
  static void on_raw(const lcm::ReceiveBuffer* rbuf, const std::string& channel, TypedSubscription<Msg>* sub);
  void run_due_timers();

  std::string name_;
  std::string url_;
  std::unique_ptr<lcm::LCM> lcm_;
  StageStats stats_;
  std::vector<std::unique_ptr<SubscriptionBase>> subs_;
  std::vector<Timer> timers_;
  bool stop_requested_ = false;
};

template <class Msg>
void BusNode::subscribe(const std::string& channel, std::function<void(const Msg&, int64_t)> handler) {
  auto sub = std::make_unique<TypedSubscription<Msg>>();
  sub->node = this;
  sub->channel = channel;
  sub->handler = std::move(handler);
  lcm_->subscribeFunction(channel, &BusNode::on_raw<Msg>, sub.get());
  subs_.push_back(std::move(sub));
}

template <class Msg>
void BusNode::on_raw(const lcm::ReceiveBuffer* rbuf, const std::string& channel, TypedSubscription<Msg>* sub) {
  BusNode& node = *sub->node;
  Msg msg;
  if (msg.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) < 0) {
    node.stats_.rejected(channel + ": " + std::to_string(rbuf->data_size) + " bytes do not decode as gpilot." +
                         Msg::getTypeName() + " (truncated, malformed or another type)");
    return;
  }
  const std::string why = check_message(msg);
  if (!why.empty()) {
    node.stats_.rejected(channel + ": " + why);
    return;
  }
  node.stats_.accepted();
  const int64_t t0 = monotonic_utime();
  sub->handler(msg, rbuf->recv_utime);
  node.stats_.processing_time(monotonic_utime() - t0);
}

}  // namespace gpilot

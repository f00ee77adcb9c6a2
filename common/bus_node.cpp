#include "bus_node.hpp"
#include "log.hpp"
#include "process_channels.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <poll.h>
#include <regex>
#include <unistd.h>

namespace gpilot {
namespace {

std::atomic<bool> g_signalled{false};

extern "C" void on_signal(int) { g_signalled.store(true); }

void install_signal_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

int64_t read_rmem_max() {
  std::ifstream in("/proc/sys/net/core/rmem_max");
  int64_t v = -1;
  in >> v;
  return in ? v : -1;
}

}  // namespace

std::string resolve_lcm_url(const std::string& flag) {
  if (!flag.empty()) return flag;
  if (const char* env = std::getenv("GPILOT_LCM_URL"); env && *env) return env;
  return kDefaultLcmUrl;
}

int64_t recv_buf_size_of(const std::string& url) {
  static const std::regex re("[?&]recv_buf_size=([0-9]+)");
  std::smatch m;
  if (std::regex_search(url, m, re)) return std::stoll(m[1].str());
  return 0;
}

namespace {

// A bus between processes (udpm://, udp://), not one inside this process or a file (memq://, file://).
bool is_network_url(const std::string& url) { return url.rfind("udpm://", 0) == 0 || url.rfind("udp://", 0) == 0; }

}  // namespace

std::string frames_url_for(const std::string& url, const BusParams& params) {
  if (!params.frames_url.empty()) return params.frames_url;
  // udpm://GROUP:PORT?OPTIONS (LCM's own default port 7667 when none is given)
  static const std::regex udpm(R"(^udpm://([^:/?]+)(?::([0-9]+))?(.*)$)");
  std::smatch m;
  if (!std::regex_match(url, m, udpm)) return url;
  const long port = m[2].matched ? std::stol(m[2].str()) : 7667;
  if (port <= 0 || port >= 65535) return url;
  return "udpm://" + m[1].str() + ":" + std::to_string(port + 1) + m[3].str();
}

bool url_leaves_host(const std::string& url) {
  if (!is_network_url(url)) return false;
  static const std::regex ttl("[?&]ttl=([0-9]+)");
  std::smatch m;
  return std::regex_search(url, m, ttl) && std::stoll(m[1].str()) > 0;  // LCM's default ttl is 0
}

BusNode::BusNode(std::string name, const std::string& url, const BusParams& params)
    : name_(std::move(name)), url_(url), frames_url_(frames_url_for(url, params)), network_bus_(is_network_url(url)) {
  std::string key_file = params.key_file;
  if (const char* env = std::getenv("GPILOT_BUS_KEY"); env && *env) key_file = env;
  const int64_t window = seconds_to_utime(params.time_window_s);
  try {
    if (!key_file.empty()) {
      std::vector<BusKey> keys{load_bus_key(key_file)};
      if (!params.previous_key_file.empty()) keys.push_back(load_bus_key(params.previous_key_file));
      signer_ = std::make_unique<BusSigner>(keys.front(), random_sender_id());
      verifier_ = std::make_unique<BusVerifier>(keys, window);
    }
  } catch (const std::runtime_error& e) {
    throw BusError(name_ + ": " + e.what());
  }
  for (const std::string& u : {url_, frames_url_})
    if (!signer_ && url_leaves_host(u))
      throw BusError(name_ + ": '" + u + "' reaches other hosts (ttl > 0) and no bus key is set: anyone on the "
                     "network could fly the drone. Make a key with gpilot-keygen FILE, install the same file on the "
                     "drone and the ground station, and set bus.key_file (or GPILOT_BUS_KEY=FILE)");
  try {
    frames_channels_ = std::regex(params.frames_channels);
  } catch (const std::regex_error& e) {
    throw BusError(name_ + ": bus.frames_channels '" + params.frames_channels + "' is not a regex: " + e.what());
  }
  streams_ = std::make_unique<StreamGuard>(window);
  lcm_ = std::make_unique<lcm::LCM>(url_);
  if (!lcm_->good())
    throw BusError(name_ + ": cannot start LCM on '" + url_ +
                   "' (a udpm:// URL needs a multicast route: ip route add 224.0.0.0/4 dev lo)");
  const int64_t asked = recv_buf_size_of(url_);
  const int64_t rmem_max = read_rmem_max();
  if (asked > 0 && rmem_max >= 0 && rmem_max < asked)
    log_warn("LCM asked for a %lld-byte receive buffer but net.core.rmem_max is %lld; large images will be "
             "dropped. Raise it: sysctl -w net.core.rmem_max=%lld",
             static_cast<long long>(asked), static_cast<long long>(rmem_max), static_cast<long long>(asked));
  install_signal_handlers();
  stats_.set_state(health_t::STATE_STARTING, "");
}

BusNode::~BusNode() = default;

bool BusNode::on_frames_bus(const std::string& channel) {
  if (frames_url_ == url_) return false;
  const auto it = frames_channel_cache_.find(channel);
  if (it != frames_channel_cache_.end()) return it->second;
  return frames_channel_cache_[channel] = std::regex_match(channel, frames_channels_);
}

lcm::LCM& BusNode::frames_lcm() {
  if (!frames_lcm_) {
    auto lcm = std::make_unique<lcm::LCM>(frames_url_);
    if (!lcm->good())
      throw BusError(name_ + ": cannot start LCM on the frames URL '" + frames_url_ +
                     "' (bus.frames_url; a udpm:// URL needs a multicast route: ip route add 224.0.0.0/4 dev lo)");
    frames_lcm_ = std::move(lcm);
  }
  return *frames_lcm_;
}

lcm::LCM& BusNode::lcm_for(const std::string& channel) { return on_frames_bus(channel) ? frames_lcm() : *lcm_; }

void BusNode::send_encoded(const std::string& channel, size_t size) {
  if (signer_) size = signer_->sign(channel, out_.data(), size, now());
  lcm_for(channel).publish(channel, out_.data(), static_cast<unsigned int>(size));
}

BusNode::Opened BusNode::open(const std::string& channel, const lcm::ReceiveBuffer& rbuf) {
  if (last_opened_.data == rbuf.data && last_opened_.recv_utime == rbuf.recv_utime && last_opened_.channel == channel)
    return last_opened_.opened;
  Opened o;
  o.data = rbuf.data;
  if (verifier_) {
    const BusVerifier::Result r = verifier_->verify(channel, rbuf.data, rbuf.data_size, arrival_time(rbuf));
    o.why = r.why;
    o.size = r.message_size;
    o.sender = r.sender;
  } else {
    o.size = message_size_of(rbuf.data, rbuf.data_size);  // no key: a signature is stripped, not checked
  }
  last_opened_ = LastOpened{rbuf.data, rbuf.recv_utime, channel, o};
  return o;
}

std::string BusNode::check_stream(const std::string& stream, int64_t utime, int64_t seq, int64_t arrival_utime) {
  return streams_->admit(stream, utime, seq, arrival_utime);
}

void BusNode::publish_raw(const std::string& channel, const void* data, size_t size) {
  lcm_for(channel).publish(channel, data, static_cast<unsigned int>(size));
}

void BusNode::subscribe_raw(const std::string& channel, RawHandler fn, int queue_capacity) {
  auto sub = std::make_unique<RawSubscription>();
  sub->node = this;
  sub->fn = std::move(fn);
  std::vector<lcm::LCM*> buses{lcm_.get()};
  if (frames_url_ != url_) buses.push_back(&frames_lcm());
  for (lcm::LCM* bus : buses) {
    lcm::Subscription* s = bus->subscribeFunction(channel, &BusNode::on_any, sub.get());
    if (queue_capacity > 0 && s) s->setQueueCapacity(queue_capacity);
  }
  frames_subscribed_ = frames_subscribed_ || frames_url_ != url_;
  subs_.push_back(std::move(sub));
}

void BusNode::on_any(const lcm::ReceiveBuffer* rbuf, const std::string& channel, RawSubscription* sub) {
  sub->node->run_handler(channel, [&] { sub->fn(channel, rbuf->data, rbuf->data_size, rbuf->recv_utime); });
}

void BusNode::handler_failed(const std::string& channel, const std::string& what) {
  const int64_t n = stats_.failed(channel + ": " + what);
  // Every failure counts in HEALTH; the log gets the 1st, 2nd, 4th, 8th ... so that a defect hit on every
  // frame does not flood it.
  if ((n & (n - 1)) == 0)
    log_error("the handler of %s failed (%lld so far): %s; a defect of this process, not a bad message: HEALTH "
              "says ERROR until it restarts",
              channel.c_str(), static_cast<long long>(n), what.c_str());
}

int BusNode::drain() {
  int n = 0;
  do {  // what the idle work published is dispatched too (memq://: to this node's own subscribers)
    while (lcm_->handleTimeout(0) > 0) ++n;
    if (frames_lcm_)
      while (frames_lcm_->handleTimeout(0) > 0) ++n;
  } while (run_idle());
  return n;
}

bool BusNode::run_idle() {
  bool any = false;
  for (auto& idle : idle_) {
    const int64_t t0 = monotonic_utime();
    bool worked = false;
    run_handler(idle.what, [&] { worked = idle.fn(); });
    if (worked) stats_.processing_time(monotonic_utime() - t0);
    any = any || worked;
  }
  return any;
}

int BusNode::handle_for(int timeout_ms) {
  if (!frames_subscribed_) return lcm_->handleTimeout(timeout_ms);
  // Both sockets: wait for either, then dispatch what each has (one message each: LCM's handle).
  pollfd fds[2] = {{lcm_->getFileno(), POLLIN, 0}, {frames_lcm_->getFileno(), POLLIN, 0}};
  const int ready = ::poll(fds, 2, timeout_ms);
  if (ready < 0) return errno == EINTR ? 0 : -1;
  int handled = 0;
  for (int i = 0; i < 2; ++i) {
    if (!(fds[i].revents & POLLIN)) continue;
    const int r = (i == 0 ? *lcm_ : *frames_lcm_).handleTimeout(0);
    if (r < 0) return r;
    handled += r;
  }
  return handled;
}

void BusNode::every(double period_s, std::function<void()> fn) {
  const int64_t period = std::max<int64_t>(1, seconds_to_utime(period_s));
  timers_.push_back(Timer{period, timer_clock_() + period, std::move(fn)});
}

void BusNode::run_timers_at(int64_t utime) {
  set_log_time(utime);
  for (auto& t : timers_) t.fn();
}

void BusNode::set_state(int8_t health_state, const std::string& detail) { stats_.set_state(health_state, detail); }

void BusNode::publish_health() {
  health_t h = stats_.report(now(), name_, static_cast<int32_t>(getpid()));
  h.cpu_s = process_cpu_seconds();
  send(process_channels::kHealth.name, h);
}

void BusNode::run_due_timers() {
  if (log_time_ >= 0) return;  // replay: fired by run_timers_at at the live instants
  const int64_t now = timer_clock_();
  for (auto& t : timers_) {
    if (now < t.next_us) continue;
    t.fn();
    t.next_us += t.period_us;
    if (t.next_us <= now) t.next_us = now + t.period_us;  // do not burst after a stall
  }
}

bool BusNode::spin_once(int timeout_ms) {
  if (stopping()) return false;
  int wait_ms = timeout_ms;
  const int64_t now = timer_clock_();
  for (const auto& t : timers_)
    wait_ms = std::min<int>(wait_ms, static_cast<int>(std::max<int64_t>(0, (t.next_us - now + 999) / 1000)));
  int handled = handle_for(wait_ms);
  // What else has arrived is dispatched before the idle work, so that the idle work takes the newest.
  for (int n = handled; handled > 0 && !idle_.empty() && n < kMaxMessagesBeforeIdle; n += handled)
    handled = handle_for(0);
  if (handled < 0) {
    stats_.set_state(health_t::STATE_ERROR, "LCM receive failed");
    return false;
  }
  run_idle();
  run_due_timers();
  return !stopping();
}

void BusNode::run() {
  every(1.0, [this] { publish_health(); });
  publish_health();
  while (spin_once(100)) {
  }
  stats_.set_state(health_t::STATE_STOPPING, "stopping");
  publish_health();
}

void BusNode::stop() { stop_requested_ = true; }

bool BusNode::stopping() const { return stop_requested_ || g_signalled.load(); }

}  // namespace gpilot

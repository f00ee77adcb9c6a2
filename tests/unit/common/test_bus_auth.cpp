// Bus signatures, keys and per-stream rules as plain classes (no LCM): known answers for each way a
// message can be forged, altered, replayed or stale.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sys/stat.h>

#include "bus_key.hpp"
#include "bus_node.hpp"
#include "bus_signature.hpp"
#include "stream_guard.hpp"

namespace gpilot {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() / ("gpilot-auth-" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

BusKey key_of(uint8_t fill) {
  BusKey k;
  k.bytes.fill(fill);
  k.id = bus_key_id(k.bytes);
  return k;
}

// A message's bytes with room for a trailer.
std::vector<uint8_t> message(const std::string& text) {
  std::vector<uint8_t> b(text.begin(), text.end());
  b.resize(b.size() + kSignatureBytes);
  return b;
}

constexpr int64_t kNow = 1'800'000'000'000'000;  // µs since the epoch
constexpr int64_t kWindow = 1'000'000;

TEST(BusSignature, ASignedMessageVerifiesAndKeepsItsBytes) {
  BusSigner signer(key_of(1), 42);
  BusVerifier verifier({key_of(1)}, kWindow);
  auto b = message("hello");
  const size_t n = signer.sign("CHAN", b.data(), 5, kNow);
  ASSERT_EQ(n, 5 + kSignatureBytes);
  EXPECT_EQ(message_size_of(b.data(), n), 5u);
  const auto r = verifier.verify("CHAN", b.data(), n, kNow + 1000);
  EXPECT_EQ(r.why, "");
  EXPECT_EQ(r.message_size, 5u);
  EXPECT_EQ(r.sender, 42u);
  EXPECT_EQ(std::string(b.begin(), b.begin() + 5), "hello");
}

TEST(BusSignature, ForgedAlteredOtherChannelWrongKeyUnsignedAreRejected) {
  BusSigner signer(key_of(1), 42), stranger(key_of(2), 43);
  BusVerifier verifier({key_of(1)}, kWindow);
  auto b = message("engage");
  const size_t n = signer.sign("FLIGHT_CONTROL", b.data(), 6, kNow);
  auto altered = b;
  altered[0] ^= 1;
  EXPECT_NE(verifier.verify("FLIGHT_CONTROL", altered.data(), n, kNow).why.find("bad signature"), std::string::npos);
  EXPECT_NE(verifier.verify("TRACKER_INIT", b.data(), n, kNow).why.find("bad signature"), std::string::npos);
  auto other = message("engage");
  const size_t m = stranger.sign("FLIGHT_CONTROL", other.data(), 6, kNow);
  EXPECT_NE(verifier.verify("FLIGHT_CONTROL", other.data(), m, kNow).why.find("unknown key"), std::string::npos);
  EXPECT_NE(verifier.verify("FLIGHT_CONTROL", b.data(), 6, kNow).why.find("unsigned"), std::string::npos);
  // the genuine one still passes: the rejections left no state behind
  EXPECT_EQ(verifier.verify("FLIGHT_CONTROL", b.data(), n, kNow).why, "");
}

TEST(BusSignature, AReplayedOrStaleMessageIsRejected) {
  BusSigner signer(key_of(1), 7);
  BusVerifier verifier({key_of(1)}, kWindow);
  auto first = message("engage");
  const size_t n = signer.sign("FLIGHT_CONTROL", first.data(), 6, kNow);
  auto second = message("land");
  const size_t m = signer.sign("FLIGHT_CONTROL", second.data(), 4, kNow);  // same clock: time still grows
  EXPECT_EQ(verifier.verify("FLIGHT_CONTROL", first.data(), n, kNow).why, "");
  EXPECT_EQ(verifier.verify("FLIGHT_CONTROL", second.data(), m, kNow).why, "");
  // a byte-identical copy of the earlier message
  EXPECT_NE(verifier.verify("FLIGHT_CONTROL", first.data(), n, kNow).why.find("replayed"), std::string::npos);
  // a receiver that just started still refuses it once it is older than the window
  BusVerifier fresh({key_of(1)}, kWindow);
  EXPECT_NE(fresh.verify("FLIGHT_CONTROL", first.data(), n, kNow + 2 * kWindow).why.find("outside bus.time_window_s"),
            std::string::npos);
}

TEST(BusSignature, TwoKeysAreAcceptedWhileRotating) {
  BusSigner old_signer(key_of(1), 1), new_signer(key_of(2), 2);
  BusVerifier verifier({key_of(2), key_of(1)}, kWindow);
  auto a = message("a"), b = message("b");
  EXPECT_EQ(verifier.verify("C", a.data(), old_signer.sign("C", a.data(), 1, kNow), kNow).why, "");
  EXPECT_EQ(verifier.verify("C", b.data(), new_signer.sign("C", b.data(), 1, kNow), kNow).why, "");
}

TEST(BusKeyFile, MadeWithMode0600ReadBackAndRefusedWhenOthersCanRead) {
  const fs::path dir = temp_dir();
  const std::string path = (dir / "bus.key").string();
  fs::remove(path);
  const BusKey made = make_bus_key_file(path);
  struct stat st {};
  ASSERT_EQ(::stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  const BusKey read = load_bus_key(path);
  EXPECT_EQ(read.bytes, made.bytes);
  EXPECT_EQ(read.id, made.id);
  EXPECT_THROW(make_bus_key_file(path), std::runtime_error);  // never overwrites
  ::chmod(path.c_str(), 0644);
  try {
    load_bus_key(path);
    FAIL() << "a key readable by others was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("mode 644"), std::string::npos) << e.what();
  }
  const std::string junk = (dir / "junk.key").string();
  std::ofstream(junk) << "not a key\n";
  ::chmod(junk.c_str(), 0600);
  EXPECT_THROW(load_bus_key(junk), std::runtime_error);
  EXPECT_THROW(load_bus_key((dir / "missing.key").string()), std::runtime_error);
  fs::remove_all(dir);
}

TEST(BusNodeKeys, ANetworkBusWithoutAKeyRefusesToStart) {
  EXPECT_TRUE(url_leaves_host("udpm://239.255.76.67:7667?ttl=1"));
  EXPECT_FALSE(url_leaves_host("udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"));
  EXPECT_FALSE(url_leaves_host("udpm://239.255.76.67:7667"));
  EXPECT_FALSE(url_leaves_host("memq://"));
  ::unsetenv("GPILOT_BUS_KEY");
  try {
    BusNode node("gpilot-flight", "udpm://239.255.76.67:7667?ttl=1");
    FAIL() << "a ttl=1 bus started without a key";
  } catch (const BusError& e) {
    EXPECT_NE(std::string(e.what()).find("no bus key"), std::string::npos) << e.what();
  }
}

TEST(StreamGuard, StaleFutureDuplicateAndOlderAreRejectedARestartIsNot) {
  StreamGuard g(kWindow);
  EXPECT_EQ(g.admit("CAMERA", kNow, 10, kNow), "");
  EXPECT_EQ(g.admit("CAMERA", kNow + 40'000, 11, kNow + 40'000), "");
  EXPECT_NE(g.admit("CAMERA", kNow + 40'000, 11, kNow + 41'000).find("duplicate"), std::string::npos);
  EXPECT_NE(g.admit("CAMERA", kNow + 20'000, 12, kNow + 50'000).find("older than this stream's newest"), std::string::npos);
  EXPECT_NE(g.admit("CAMERA", kNow - 3'600'000'000, 13, kNow).find("before its arrival"), std::string::npos);
  EXPECT_NE(g.admit("CAMERA", kNow + 3'600'000'000, 13, kNow).find("after its arrival"), std::string::npos);
  EXPECT_NE(g.admit("CAMERA", kNow + 80'000, INT64_MAX, kNow + 80'000).find("outside [-1, 2^53]"), std::string::npos);
  EXPECT_NE(g.admit("CAMERA", kNow + 80'000, -2, kNow + 80'000).find("outside [-1, 2^53]"), std::string::npos);
  // the publisher restarted: seq from 0 again, time moving on
  EXPECT_EQ(g.admit("CAMERA", kNow + 120'000, 0, kNow + 120'000), "");
  EXPECT_EQ(g.admit("CAMERA", kNow + 160'000, 1, kNow + 160'000), "");
  // another stream is judged on its own
  EXPECT_EQ(g.admit("HEALTH/gpilot-hands/12", kNow, 0, kNow), "");
}

}  // namespace
}  // namespace gpilot

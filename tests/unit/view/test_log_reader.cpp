// The log reader: every event of a log lcm::LogFile wrote, a truncated tail and corrupt bytes end or
// skip cleanly with a warning, bad files are clear errors, undecodable messages are counted.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <lcm/lcm-cpp.hpp>

#include "log_reader.hpp"
#include "synthetic_run.hpp"

namespace gpilot {
namespace {

namespace fs = std::filesystem;

class LogReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("gpilot_log_reader_" + std::to_string(::getpid()) + "_" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir);
    path = (dir / "run.lcmlog").string();
    run.frames = 6;
    run.size = cv::Size(64, 48);
    events = test::write_synthetic_log(path, run);
  }
  void TearDown() override { fs::remove_all(dir); }
  std::vector<char> bytes() {
    std::ifstream in(path, std::ios::binary);
    return std::vector<char>(std::istreambuf_iterator<char>(in), {});
  }
  void write(const std::vector<char>& b) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(b.data(), static_cast<std::streamsize>(b.size()));
  }
  int64_t read_all(LogReader& r, std::vector<LogEvent>* out = nullptr) {
    LogEvent ev;
    int64_t n = 0;
    while (r.next(ev)) {
      ++n;
      if (out) out->push_back(ev);
    }
    return n;
  }

  fs::path dir;
  std::string path;
  test::SyntheticRun run;
  int64_t events = 0;
};

TEST_F(LogReaderTest, ReadsEveryEventInOrderAsLcmWroteIt) {
  LogReader r(path);
  std::vector<LogEvent> got;
  EXPECT_EQ(read_all(r, &got), events);
  EXPECT_TRUE(r.warnings().empty());
  EXPECT_EQ(r.bytes_skipped(), 0);
  EXPECT_EQ(r.position(), r.file_size());
  for (size_t i = 1; i < got.size(); ++i) EXPECT_LE(got[i - 1].timestamp, got[i].timestamp);
  // The same events through LCM's own reader.
  lcm::LogFile lf(path, "r");
  for (const auto& ev : got) {
    const lcm::LogEvent* le = lf.readNextEvent();
    ASSERT_NE(le, nullptr);
    EXPECT_EQ(le->channel, ev.channel);
    EXPECT_EQ(le->timestamp, ev.timestamp);
    ASSERT_EQ(static_cast<size_t>(le->datalen), ev.data.size());
  }
  EXPECT_EQ(got[0].channel, "CAMERA");
  image_t img;
  ASSERT_GT(img.decode(got[0].data.data(), 0, static_cast<int>(got[0].data.size())), 0);
  EXPECT_EQ(img.width, 64);
  EXPECT_EQ(img.utime, run.t0);
}

TEST_F(LogReaderTest, ATruncatedTailEndsTheReadWithAWarning) {
  auto b = bytes();
  b.resize(b.size() - 7);  // cut into the last event's data
  write(b);
  LogReader r(path);
  EXPECT_EQ(read_all(r), events - 1);
  ASSERT_EQ(r.warnings().size(), 1u);
  EXPECT_NE(r.warnings()[0].find("truncated"), std::string::npos) << r.warnings()[0];
}

TEST_F(LogReaderTest, AHalfHeaderAtTheEndIsATruncation) {
  auto b = bytes();
  const char extra[10] = {char(0xED), char(0xA1), char(0xDA), 0x01, 0, 0, 0, 0, 0, 0};
  b.insert(b.end(), extra, extra + 10);
  write(b);
  LogReader r(path);
  EXPECT_EQ(read_all(r), events);
  ASSERT_EQ(r.warnings().size(), 1u);
  EXPECT_NE(r.warnings()[0].find("truncated"), std::string::npos);
}

TEST_F(LogReaderTest, CorruptBytesInTheMiddleAreSkippedToTheNextEvent) {
  // GIVEN the sync word of the second event overwritten
  auto b = bytes();
  LogReader first(path);
  LogEvent ev;
  ASSERT_TRUE(first.next(ev));
  const int64_t second_at = first.position();
  b[static_cast<size_t>(second_at)] = 0x55;
  write(b);
  // WHEN read; THEN that event is lost, all others are read, and the skip is reported
  LogReader r(path);
  EXPECT_EQ(read_all(r), events - 1);
  EXPECT_GT(r.bytes_skipped(), 0);
  ASSERT_FALSE(r.warnings().empty());
  EXPECT_NE(r.warnings()[0].find("corrupt"), std::string::npos);
}

TEST_F(LogReaderTest, BadFilesAreClearErrors) {
  EXPECT_THROW(LogReader((dir / "missing.lcmlog").string()), LogError);
  write({});
  try {
    LogReader r(path);
    FAIL() << "an empty log must not open";
  } catch (const LogError& e) {
    EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos);
  }
  write({'h', 'e', 'l', 'l', 'o', '\n'});
  try {
    LogReader r(path);
    FAIL() << "a text file must not open";
  } catch (const LogError& e) {
    EXPECT_NE(std::string(e.what()).find("not an LCM log"), std::string::npos);
  }
  EXPECT_THROW(LogReader(dir.string()), LogError);
}

TEST_F(LogReaderTest, DispatcherCountsWhatDoesNotDecodeOrIsInvalid) {
  LogDispatcher d;
  int cameras = 0, vehicles = 0;
  d.on<image_t>("CAMERA", [&](const image_t&, int64_t) { ++cameras; });
  d.on<vehicle_state_t>("VEHICLE_STATE", [&](const vehicle_state_t&, int64_t) { ++vehicles; });
  LogEvent ev;
  ev.channel = "CAMERA";
  ev.data = {1, 2, 3};
  d.dispatch(ev);
  vehicle_state_t v = test::vehicle_of(run, 0);
  v.position[0] = std::nanf("");
  ev.channel = "VEHICLE_STATE";
  ev.data.resize(static_cast<size_t>(v.getEncodedSize()));
  v.encode(ev.data.data(), 0, static_cast<int>(ev.data.size()));
  d.dispatch(ev);
  v.position[0] = 1.0f;
  v.encode(ev.data.data(), 0, static_cast<int>(ev.data.size()));
  d.dispatch(ev);
  ev.channel = "SOMETHING_ELSE";
  d.dispatch(ev);
  EXPECT_EQ(cameras, 0);
  EXPECT_EQ(vehicles, 1);
  EXPECT_EQ(d.rejected_total(), 2);
  EXPECT_EQ(d.rejected_by_channel().at("CAMERA"), 1);
  EXPECT_EQ(d.rejected_by_channel().at("VEHICLE_STATE"), 1);
  EXPECT_NE(d.last_reject_reason().find("not finite"), std::string::npos) << d.last_reject_reason();
  EXPECT_EQ(d.ignored(), 1);
}

}  // namespace
}  // namespace gpilot

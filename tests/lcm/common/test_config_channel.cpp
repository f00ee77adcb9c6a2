// Every process publishes its effective config on CONFIG when it starts (inside the test's network
// namespace): the YAML read back gives the values the process runs with, --set included.
#include <gtest/gtest.h>

#include <optional>

#include "bus_node.hpp"
#include "child_process.hpp"
#include "config_schema.hpp"
#include "decide/decide_params.hpp"

namespace gpilot {
namespace {

TEST(ConfigChannel, AProcessPublishesTheConfigItRunsWith) {
  BusNode bus("test-config", kDefaultLcmUrl);
  std::optional<config_t> got;
  bus.subscribe<config_t>("CONFIG", [&](const config_t& m, int64_t) {
    if (m.process == "gpilot-decide") got = m;
  });
  test::ChildProcess decide({std::string(GPILOT_BIN_DIR) + "/gpilot-decide", "--lcm-url", kDefaultLcmUrl, "--set",
                             "decide.lambda4=0.25"});
  ASSERT_GT(decide.pid(), 0);
  const int64_t end = monotonic_utime() + 10'000'000;
  while (!got && monotonic_utime() < end) bus.spin_once(50);
  ASSERT_TRUE(got.has_value()) << "no CONFIG from gpilot-decide";
  EXPECT_EQ(got->pid, decide.pid());
  const Config back = Config::from_string(got->yaml, "CONFIG");
  validate_config(back);
  EXPECT_EQ(back.section<DecideParams>("decide").lambda4, 0.25);
  EXPECT_EQ(back.section<DecideParams>("decide").buffer_size, DecideParams{}.buffer_size);
}

}  // namespace
}  // namespace gpilot

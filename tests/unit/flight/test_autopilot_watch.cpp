// AutopilotWatch: the ENGAGE gate and the link watch decide at ticks, on the ticks' times, from the AUTOPILOT
// messages each tick had (what a replay gives them again).
#include <gtest/gtest.h>

#include "autopilot_watch.hpp"

namespace gpilot {
namespace {

constexpr int64_t kTick = 20000;  // 50 Hz setpoint ticks, us
constexpr int64_t kStart = 1700000000000000;

AutopilotMessage heartbeat() { return AutopilotMessage{}; }
AutopilotMessage answer(const std::string& name, float value) {
  AutopilotMessage m;
  m.kind = AutopilotMessage::Kind::ParamValue;
  m.param_id = name;
  m.param_value = value;
  m.param_type = 9;  // REAL32
  return m;
}
// PX4's parameter, at most 1 s acceptable, 1 s to answer, the link lost after 3 s of silence.
AutopilotWatch watch() { return AutopilotWatch("COM_OF_LOSS_T", 1.0, 1.0, 3.0); }

TEST(AutopilotWatch, AnEngageAskedAtATickIsAcceptedAtTheTickAfterTheAnswer) {
  AutopilotWatch w = watch();
  // GIVEN an ENGAGE between two ticks
  w.engage_requested();
  // WHEN the tick comes: the parameter is asked then
  const auto first = w.tick(kStart);
  EXPECT_TRUE(first.request_param);
  EXPECT_FALSE(first.engage);
  // AND the answer 0.5 s arrives before the next tick
  w.heard(answer("COM_OF_LOSS_T", 0.5f));
  // THEN that tick engages
  const auto second = w.tick(kStart + kTick);
  EXPECT_TRUE(second.engage);
  EXPECT_TRUE(second.refuse.empty());
  EXPECT_FLOAT_EQ(w.last_value(), 0.5f);
}

TEST(AutopilotWatch, NoAnswerIsRefusedAtTheFirstTickPastTheTimeout) {
  AutopilotWatch w = watch();
  w.engage_requested();
  EXPECT_TRUE(w.tick(kStart).request_param);
  // GIVEN no answer: asked again every timeout / 4, refused once more than 1 s has passed since the first tick
  int requests = 0;
  int64_t t = kStart;
  std::string why;
  while (why.empty() && t < kStart + 2000000) {
    t += kTick;
    const auto d = w.tick(t);
    requests += d.request_param;
    why = d.refuse;
  }
  EXPECT_EQ(t, kStart + 1000000 + kTick);  // the first tick strictly past 1 s
  EXPECT_EQ(requests, 3);                  // at 0.25, 0.5, 0.75 s (the refusal comes before a fourth at 1 s)
  EXPECT_NE(why.find("did not answer PARAM_REQUEST_READ COM_OF_LOSS_T within 1.00 s"), std::string::npos) << why;
}

TEST(AutopilotWatch, ATooLongFailsafeIsRefused) {
  AutopilotWatch w = watch();
  w.engage_requested();
  w.tick(kStart);
  w.heard(answer("COM_OF_LOSS_T", 5.0f));
  const auto d = w.tick(kStart + kTick);
  EXPECT_FALSE(d.engage);
  EXPECT_NE(d.refuse.find("is 5.00 s, above flight.max_autopilot_loss_s 1.00 s"), std::string::npos) << d.refuse;
}

TEST(AutopilotWatch, TheLinkIsLostAfterItsTimeoutAndBackWithTheNextMessage) {
  AutopilotWatch w = watch();
  // GIVEN a heartbeat at the first tick
  w.heard(heartbeat());
  w.tick(kStart);
  EXPECT_TRUE(w.link_up());
  // WHEN nothing more is heard: still up at exactly 3 s, lost at the tick after
  EXPECT_TRUE(w.tick(kStart + 3000000).link_lost.empty());
  const auto lost = w.tick(kStart + 3000000 + kTick);
  EXPECT_NE(lost.link_lost.find("nothing heard from it for 3.02 s"), std::string::npos) << lost.link_lost;
  EXPECT_FALSE(w.link_up());
  // THEN a heartbeat brings it back, said once
  w.heard(heartbeat());
  EXPECT_TRUE(w.tick(kStart + 5000000).link_back);
  EXPECT_FALSE(w.tick(kStart + 5000000 + kTick).link_back);
  EXPECT_TRUE(w.link_up());
}

TEST(AutopilotWatch, AnAnswerForAnotherParameterOrWithoutAnEngageChangesNothing) {
  AutopilotWatch w = watch();
  w.heard(answer("COM_OF_LOSS_T", 0.5f));  // no ENGAGE pending
  EXPECT_FALSE(w.tick(kStart).engage);
  w.engage_requested();
  w.tick(kStart + kTick);
  w.heard(answer("GUID_TIMEOUT", 0.5f));
  const auto d = w.tick(kStart + 2 * kTick);
  EXPECT_FALSE(d.engage);
  EXPECT_TRUE(d.refuse.empty());
  EXPECT_TRUE(w.pending());
}

}  // namespace
}  // namespace gpilot

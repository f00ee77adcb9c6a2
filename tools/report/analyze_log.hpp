// Reads a run's LCM log through a RunAnalyzer: the one place that says which channel feeds what.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "run_summary.hpp"

namespace gpilot {

struct LogAnalysis {
  Summary summary;
  std::vector<TrajectoryPoint> path;
  int64_t events = 0;
  std::vector<std::string> warnings;          // truncation, corrupt stretches, undecodable messages
  std::map<std::string, int64_t> rejected;    // per channel: did not decode or failed check_message()
};

// Throws LogError for a missing, empty or foreign file. progress_tool: "" for no progress on stderr.
LogAnalysis analyse_log(const std::string& path, const Settling& settling, const std::string& progress_tool = "");

}  // namespace gpilot

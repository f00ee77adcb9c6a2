// A whole text file as a string, for tests that compare a committed file with what the code generates
// (DEVELOPERS.md's tables, deploy/ files). "" when it cannot be read: the comparison then names the file.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace gpilot::test {

inline std::string read_text_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace gpilot::test

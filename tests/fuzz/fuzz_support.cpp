#include <cstdio>
#include <cstdlib>

#include "fuzz_input.hpp"

namespace gpilot::fuzz {

void fail(const std::string& why) {
  std::fprintf(stderr, "fuzz invariant broken: %s\n", why.c_str());
  std::abort();
}

}  // namespace gpilot::fuzz

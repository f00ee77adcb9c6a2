// The one exception a bus handler throws to refuse its message: the message (what a peer sent) is at fault,
// not the code. BusNode counts it as a rejection in HEALTH, as it counts bytes that do not decode. Anything
// else a handler throws (std::logic_error, cv::Exception, std::bad_alloc, ...) is a defect of this process:
// logged at error level, and HEALTH reports ERROR from then on (bus_node.hpp).
#pragma once

#include <stdexcept>

namespace gpilot {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace gpilot

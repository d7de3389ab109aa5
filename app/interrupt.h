// SIGINT and SIGTERM while rendering: the first asks the render to stop (tiles in flight
// finish, the frame keeps every finished sample and is written); the second ends the
// process at once with exit code 130, leaving any earlier output file untouched.
#pragma once

#include <atomic>

namespace tessera {

class InterruptHandler {
 public:
  explicit InterruptHandler(std::atomic<bool>& cancel);  // installs the handlers
  ~InterruptHandler();  // restores the previous ones
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;

  bool interrupted() const;
};

}  // namespace tessera

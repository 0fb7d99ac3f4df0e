#pragma once
// Errors thrown by the core. Messages name what was wrong and where (file, index, face).
#include <stdexcept>
#include <string>

namespace geoshift {

// Bad input from the caller or a file: the message is meant for the user as it is.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A long call stopped because its Progress cancel flag was raised; nothing was written.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

}  // namespace geoshift

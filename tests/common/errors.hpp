#pragma once
// The message of the exception of type E that fn throws ("" when it throws none), for tests that
// check what an error names.
#include <functional>
#include <string>

namespace rbfib::testing {

template <class E>
std::string message_of(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

}  // namespace rbfib::testing

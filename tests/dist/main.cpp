// The distributed tests' entry point: every rank runs every test (the code under test is
// collective); rank 0 prints the progress, every rank prints its own failures, and the program
// fails on every rank when a test failed on any.
//
// Checks inside a test are reduced over the ranks before they are asserted (EXPECT on a global
// maximum), and no test returns early on one rank alone: a rank that left a collective call
// would leave the others waiting.
#include "rbfib/dist/comm.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace {
class FailurePrinter : public ::testing::EmptyTestEventListener {
 public:
  explicit FailurePrinter(int rank) : rank_(rank) {}
  void OnTestPartResult(const ::testing::TestPartResult& r) override {
    if (r.failed())
      std::fprintf(stderr, "[rank %d] %s:%d: failure\n%s\n", rank_, r.file_name() ? r.file_name() : "?", r.line_number(),
                   r.message());
  }

 private:
  int rank_;
};
}  // namespace

int main(int argc, char** argv) {
  rbfib::dist::Session session(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  const rbfib::dist::Comm world;
  if (world.rank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
    listeners.Append(new FailurePrinter(world.rank()));
  }
  const int failed = RUN_ALL_TESTS();
  return world.all(failed == 0) ? 0 : 1;
}

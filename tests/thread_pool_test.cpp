// The pool hands out every index of a job exactly once and returns only when
// all of them are done, also when workers join late or not at all (more
// threads than cores here, so the OS keeps some of them waiting).
#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "pipeline/thread_pool.h"

namespace dv {
namespace {

TEST(ThreadPool, EveryIndexOnceAndDoneOnReturnOverManyJobs) {
  for (int threads : {2, 5}) {
    ThreadPool pool(threads);
    std::vector<int> hits(64);
    for (int job = 0; job < 20000; ++job) {
      const int n = 1 + job % 64;
      std::fill(hits.begin(), hits.end(), 0);
      pool.parallelFor(n, [&](int b, int e) {
        for (int i = b; i < e; ++i) ++hits[i];  // disjoint ranges: no two threads touch one index
      });
      int wrong = 0;
      for (int i = 0; i < 64; ++i) wrong += hits[i] != (i < n ? 1 : 0);
      ASSERT_EQ(wrong, 0) << "threads " << threads << ", job " << job << ", n " << n;
    }
  }
}

}  // namespace
}  // namespace dv

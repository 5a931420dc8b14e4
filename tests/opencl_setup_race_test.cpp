// Two cameras of `serve` set up their pipelines at the same moment, and with
// them OpenCL. PoCL's first platform query is not thread-safe: it crashed
// inside hwloc in about one start in fifteen. The first query only happens
// once per process, so each try is a fresh child process whose two threads
// list the devices at once.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <barrier>
#include <thread>

#include "pipeline/opencl/ocl_runtime.h"

namespace dv {
namespace {

int listTwiceAtOnce() {
  std::barrier start(2);
  int found[2] = {0, 0};
  auto list = [&](int i) {
    start.arrive_and_wait();
    found[i] = static_cast<int>(listOpenClDevices(nullptr).size());
  };
  std::thread a(list, 0), b(list, 1);
  a.join();
  b.join();
  return found[0] == found[1] ? 0 : 3;
}

TEST(OpenClRuntime, DevicesListedFromTwoThreadsAtOnceInFreshProcesses) {
  const int tries = 40;
  int crashed = 0, disagreed = 0;
  for (int i = 0; i < tries; ++i) {
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) _exit(listTwiceAtOnce());
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    if (WIFSIGNALED(status)) ++crashed;
    else if (WEXITSTATUS(status) != 0) ++disagreed;
  }
  EXPECT_EQ(crashed, 0) << "of " << tries << " processes";
  EXPECT_EQ(disagreed, 0) << "the two threads saw different device lists";
}

}  // namespace
}  // namespace dv

#include "app/signals.h"

#include <pthread.h>
#include <unistd.h>

#include <atomic>
#include <mutex>
#include <csignal>
#include <thread>

namespace dv::app {

namespace {
std::atomic<int> g_stop{0};
std::atomic<bool> g_reload{false};
std::atomic<bool> g_dump{false};
}  // namespace

// The signals are blocked in this thread and so in every thread started
// after it (the pipelines', OpenCL's, the cameras'), and taken by one
// thread with sigwait: no handler that a library installs later (an
// OpenCL runtime does) can swallow them, and nothing runs in signal context.
void installSignalHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    sigset_t set;
    sigemptyset(&set);
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGUSR1}) sigaddset(&set, sig);
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
    std::thread([set] {
      while (true) {
        int sig = 0;
        if (sigwait(&set, &sig) != 0) continue;
        switch (sig) {
          case SIGINT:
          case SIGTERM:
            if (g_stop.fetch_add(1) >= 1 && sig == SIGINT) _exit(130);  // second Ctrl-C: at once
            break;
          case SIGHUP: g_reload = true; break;
          case SIGUSR1: g_dump = true; break;
          default: break;
        }
      }
    }).detach();
  });
}

bool stopRequested() { return g_stop.load() > 0; }
void requestStop() { g_stop.fetch_add(1); }
bool takeReloadRequest() { return g_reload.exchange(false); }
bool takeDumpRequest() { return g_dump.exchange(false); }

}  // namespace dv::app

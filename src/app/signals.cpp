#include "app/signals.h"

#include <atomic>
#include <csignal>
#include <unistd.h>

namespace dv::app {

namespace {
std::atomic<int> g_stop{0};
std::atomic<bool> g_reload{false};
std::atomic<bool> g_dump{false};

extern "C" void onSignal(int sig) {
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
}  // namespace

void installSignalHandlers() {
  struct sigaction sa {};
  sa.sa_handler = onSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGUSR1}) sigaction(sig, &sa, nullptr);
}

bool stopRequested() { return g_stop.load() > 0; }
void requestStop() { g_stop.fetch_add(1); }
bool takeReloadRequest() { return g_reload.exchange(false); }
bool takeDumpRequest() { return g_dump.exchange(false); }

}  // namespace dv::app

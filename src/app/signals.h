#pragma once
// Signals as flags the main loop polls: SIGINT / SIGTERM ask for a clean
// stop (summary printed, files closed whole), SIGHUP for a config reload,
// SIGUSR1 for a dump of the raw frame ring. A second SIGINT ends at once.
namespace dv::app {

void installSignalHandlers();
bool stopRequested();
// True once per SIGHUP / SIGUSR1 received since the last call.
bool takeReloadRequest();
bool takeDumpRequest();
// For tests and for a job that ends by itself.
void requestStop();

}  // namespace dv::app

#pragma once
// The console's JSON API under /api/ (documented in the README's "Console"
// section): status, cameras, detections, geometry, config, snapshots. The
// token check for requests that change something is the server's
// (console_server.cpp); these handlers trust that it ran.
namespace httplib {
class Server;
}

namespace dv::app {

class ConsoleState;

void addConsoleApi(httplib::Server& server, ConsoleState& state);

}  // namespace dv::app

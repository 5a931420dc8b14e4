#pragma once
// The operator's console of `dotvision serve`: an HTTP server on its own
// threads serving the pages (embedded at build time from src/app/console/)
// and the JSON API (console_api.h). Listens on 127.0.0.1 unless told;
// every request that changes something (any method but GET/HEAD) needs the
// operator's token, as "Authorization: Bearer TOKEN" or "X-Dotvision-Token:
// TOKEN" (401 without one, 403 with a wrong one); reading needs none.
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include <nlohmann/json_fwd.hpp>

namespace httplib {
class Server;
}

namespace dv::app {

class ConsoleState;
class LogRing;
class ConsoleHost;

struct ConsoleOptions {
  std::string host = "127.0.0.1";
  uint16_t port = 8080;  // 0: any free port
  std::string token;     // "": a random one
  std::shared_ptr<const LogRing> log_ring;  // serve's recent lines, for the Status page
};

// The first line of a token file, blanks trimmed. Throws InputError(path, ...)
// when it cannot be read or holds no token.
std::string readTokenFile(const std::string& path);

class ConsoleServer;

// The console serve or run asks for: `http_override` (--http, when given)
// else the config's console.http; "" is none (nullptr). The token from the
// config's token_file, else a random one. A console that cannot listen is
// logged and left out (the cameras matter more); a token file that cannot
// be read throws InputError.
std::unique_ptr<ConsoleServer> makeConsole(ConsoleHost& host, const std::string* http_override,
                                           std::function<void(const std::string&)> log,
                                           std::shared_ptr<const LogRing> log_ring = nullptr);

class ConsoleServer {
 public:
  using LogFn = std::function<void(const std::string&)>;
  // Installs its frame hook on every camera of `host` (call before the
  // cameras start) and binds the port. Throws InputError when it cannot
  // listen there.
  ConsoleServer(ConsoleHost& host, const std::string& config_text, const ConsoleOptions& options, LogFn log);
  ~ConsoleServer();

  void start();  // serves from its own thread
  void stop();
  uint16_t port() const { return port_; }
  const std::string& token() const { return token_; }
  std::string url() const;

  // The host's main loop: each turn (applies config changes and
  // calibrations asked for on the console to the host), and once a second (the status document).
  void service(ConsoleHost& host);
  void setStatus(const nlohmann::json& status);

 private:
  std::unique_ptr<ConsoleState> state_;
  std::unique_ptr<httplib::Server> server_;
  std::thread thread_;
  std::string host_, token_;
  uint16_t port_ = 0;
  LogFn log_;
};

}  // namespace dv::app

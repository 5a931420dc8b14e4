#include "app/console_server.h"

#include <pthread.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "app/console_api.h"
#include "app/console_assets.h"
#include "app/console_state.h"
#include "app/camera_runner.h"
#include "app/console_host.h"
#include "core/error.h"
// Last: it brings <resolv.h>, whose _res macro breaks Eigen headers included after it.
#include <httplib.h>

namespace dv::app {

namespace {

// The console's threads give way to the cameras' (issue: the console must
// cost the detection nothing measurable): each HTTP thread lowers its own
// priority to nice 10 at its first request (Linux: a thread's own), so
// encoding images and the layer pipeline get the CPU the detection threads
// leave, wherever the browsers are.
void giveWayToTheCameras() {
  thread_local const bool done = [] {
    pthread_setname_np(pthread_self(), "console");
    return ::setpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()), 10) == 0;
  }();
  (void)done;
}

std::string randomToken() {
  std::random_device rd;
  static const char* hex = "0123456789abcdef";
  std::string t;
  for (int i = 0; i < 32; ++i) t += hex[rd() & 15];
  return t;
}

// Compares without stopping at the first difference (no timing hint).
bool sameToken(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned diff = 0;
  for (size_t i = 0; i < a.size(); ++i) diff |= unsigned(a[i] ^ b[i]);
  return diff == 0;
}

std::string contentType(const std::string& name) {
  auto ends = [&](const char* s) { return name.size() >= std::strlen(s) && name.rfind(s) == name.size() - std::strlen(s); };
  if (ends(".html")) return "text/html; charset=utf-8";
  if (ends(".css")) return "text/css; charset=utf-8";
  if (ends(".js")) return "text/javascript; charset=utf-8";
  if (ends(".svg")) return "image/svg+xml";
  return "text/plain; charset=utf-8";
}

std::vector<uint32_t> cameraIds(ConsoleHost& rt) {
  std::vector<uint32_t> ids;
  for (size_t i = 0; i < rt.cameraCount(); ++i) ids.push_back(rt.runner(i).cameraId());
  return ids;
}

}  // namespace

std::string readTokenFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, std::string("cannot read the console's token file: ") + std::strerror(errno));
  std::string line;
  std::getline(in, line);
  const size_t a = line.find_first_not_of(" \t\r"), b = line.find_last_not_of(" \t\r");
  if (a == std::string::npos) throw InputError(path, "the console's token file is empty: write the token on its first line");
  return line.substr(a, b - a + 1);
}

ConsoleServer::ConsoleServer(ConsoleHost& runtime, const std::string& config_text, const ConsoleOptions& options,
                             LogFn log)
    : state_(std::make_unique<ConsoleState>(runtime.geometry(), cameraIds(runtime), runtime.config(), config_text)),
      server_(std::make_unique<httplib::Server>()),
      host_(options.host),
      token_(options.token.empty() ? randomToken() : options.token),
      log_(std::move(log)) {
  state_->setLogRing(options.log_ring);
  for (size_t i = 0; i < runtime.cameraCount(); ++i) {
    // The hook holds the feed, so it outlives the console if the cameras do.
    std::shared_ptr<CameraFeed> feed = state_->sharedFeed(runtime.runner(i).cameraId());
    CameraRunner* runner = &runtime.runner(i);  // the hook runs on its thread, while it lives
    runner->addFrameHook([feed, runner](const Frame& f, const ssl::SSL_WrapperPacket& p) {
      feed->onFrame(f, p, runner->processorInHook());
    });
  }
  server_->set_payload_max_length(1 << 20);
  // Changing something needs the token; reading does not.
  server_->set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    giveWayToTheCameras();
    if (req.method == "GET" || req.method == "HEAD") return httplib::Server::HandlerResponse::Unhandled;
    std::string given;
    const std::string auth = req.get_header_value("Authorization");
    if (auth.rfind("Bearer ", 0) == 0) given = auth.substr(7);
    if (given.empty()) given = req.get_header_value("X-Dotvision-Token");
    if (given.empty() || !sameToken(given, token_)) {
      res.status = given.empty() ? 401 : 403;
      const nlohmann::json j = {
          {"error", given.empty() ? "this request changes something: it needs the operator's token "
                                    "(Authorization: Bearer TOKEN, or X-Dotvision-Token: TOKEN)"
                                  : "the token is not the operator's"}};
      if (given.empty()) res.set_header("WWW-Authenticate", "Bearer");
      res.set_content(j.dump(), "application/json");
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });
  addConsoleApi(*server_, *state_);
  for (int i = 0; i < embeddedConsoleAssetCount(); ++i) {
    const EmbeddedConsoleAsset a = embeddedConsoleAssets()[i];
    const std::string name = a.name, text = a.text, type = contentType(name);
    server_->Get("/" + name, [text, type](const httplib::Request&, httplib::Response& res) {
      res.set_content(text, type.c_str());
    });
    if (name == "field.html")
      server_->Get("/", [text, type](const httplib::Request&, httplib::Response& res) {
        res.set_content(text, type.c_str());
      });
  }
  if (options.port == 0) {
    const int p = server_->bind_to_any_port(host_);
    if (p <= 0) throw InputError("console", "cannot listen on " + host_ + " (any port)");
    port_ = static_cast<uint16_t>(p);
  } else {
    if (!server_->bind_to_port(host_, options.port))
      throw InputError("console", "cannot listen on " + host_ + ":" + std::to_string(options.port) +
                                      " (in use? choose another with --http ADDR:PORT, or --http \"\" for none)");
    port_ = options.port;
  }
}

std::unique_ptr<ConsoleServer> makeConsole(ConsoleHost& runtime, const std::string* http_override,
                                           std::function<void(const std::string&)> log,
                                           std::shared_ptr<const LogRing> log_ring) {
  const SiteConfig& config = runtime.config();
  const std::string http = http_override ? *http_override : config.console.http;
  if (http.empty()) return nullptr;
  ConsoleOptions o;
  o.log_ring = std::move(log_ring);
  if (!splitListenAddress(http, o.host, o.port))
    throw InputError("--http", "expected IPv4ADDR:PORT (e.g. 127.0.0.1:8080), or \"\" for no console, got '" + http + "'");
  if (!config.console.token_file.empty()) o.token = readTokenFile(config.console.token_file);
  std::ifstream in(config.path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return std::make_unique<ConsoleServer>(runtime, text.str(), o, log);
  } catch (const InputError& e) {
    log(std::string("console not started: ") + e.what());
    return nullptr;
  }
}

ConsoleServer::~ConsoleServer() { stop(); }

void ConsoleServer::start() {
  thread_ = std::thread([this] { server_->listen_after_bind(); });
}

void ConsoleServer::stop() {
  if (server_) server_->stop();
  if (thread_.joinable()) thread_.join();
}

std::string ConsoleServer::url() const { return "http://" + host_ + ":" + std::to_string(port_) + "/"; }

void ConsoleServer::service(ConsoleHost& host) { state_->service(host); }

void ConsoleServer::setStatus(const nlohmann::json& status) { state_->setStatus(status); }

}  // namespace dv::app

#pragma once
// A small W3C WebDriver client for the console's browser tests: starts
// Debian's chromedriver on a free loopback port with a headless chromium
// session, then navigates, runs scripts, finds, clicks and types, and takes
// screenshots. skipReason() says why a machine cannot run these tests.
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

// Last: it brings <resolv.h>, whose _res macro breaks Eigen headers included after it.
#include <httplib.h>

namespace dv {

class WebDriver {
 public:
  static constexpr const char* kChromium = "/usr/bin/chromium";
  static constexpr const char* kDriver = "/usr/bin/chromedriver";
  static constexpr const char* kElement = "element-6066-11e4-a52e-4f735466cecf";

  static std::string skipReason() {
    for (const char* p : {kChromium, kDriver})
      if (!std::filesystem::exists(p))
        return std::string(p) + " is not installed (Debian packages chromium and chromium-driver; "
                                "scripts/setup.sh installs them): the console's browser tests are skipped";
    return "";
  }

  // `profile`: an empty folder for the browser's profile.
  explicit WebDriver(const std::string& profile) {
    port_ = freePort();
    pid_ = ::fork();
    if (pid_ == 0) {
      const std::string port = "--port=" + std::to_string(port_);
      const std::string log = "--log-path=" + profile + ".chromedriver.log";
      execl(kDriver, kDriver, port.c_str(), log.c_str(), nullptr);
      _exit(127);
    }
    client_ = std::make_unique<httplib::Client>("127.0.0.1", port_);
    client_->set_read_timeout(60, 0);
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (std::chrono::steady_clock::now() < until) {
      auto r = client_->Get("/status");
      if (r && r->status == 200 && nlohmann::json::parse(r->body)["value"].value("ready", false)) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    const nlohmann::json args = {"--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                                 "--disable-component-update", "--disable-sync", "--no-first-run",
                                 "--disable-dev-shm-usage", "--window-size=1280,900",
                                 "--user-data-dir=" + profile};
    const nlohmann::json caps = {
        {"capabilities",
         {{"alwaysMatch", {{"browserName", "chrome"}, {"goog:chromeOptions", {{"binary", kChromium}, {"args", args}}}}}}}};
    const nlohmann::json r = call("POST", "/session", caps);
    if (r.contains("sessionId")) session_ = r["sessionId"];
    else why_ = "no browser session: " + r.dump();
  }
  ~WebDriver() {
    if (!session_.empty()) client_->Delete(("/session/" + session_).c_str());
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      ::waitpid(pid_, nullptr, 0);
    }
  }

  bool ok() const { return !session_.empty(); }
  const std::string& why() const { return why_; }

  void navigate(const std::string& url) { call("POST", path("/url"), {{"url", url}}); }
  // Runs `script` (a function body; `arguments` holds args) and returns its value.
  nlohmann::json execute(const std::string& script, const nlohmann::json& args = nlohmann::json::array()) {
    return call("POST", path("/execute/sync"), {{"script", script}, {"args", args}});
  }
  // Repeats `script` until it returns true or timeout_s passed.
  bool waitUntil(const std::string& script, double timeout_s = 60) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (std::chrono::steady_clock::now() < until) {
      if (execute(script) == true) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(250));
    }
    return false;
  }
  std::string find(const std::string& css) {
    const nlohmann::json e = call("POST", path("/element"), {{"using", "css selector"}, {"value", css}});
    return e.is_object() && e.contains(kElement) ? e[kElement].get<std::string>() : "";
  }
  void clear(const std::string& element) { call("POST", path("/element/" + element + "/clear"), nlohmann::json::object()); }
  void click(const std::string& element) { call("POST", path("/element/" + element + "/click"), nlohmann::json::object()); }
  void type(const std::string& element, const std::string& text) {
    call("POST", path("/element/" + element + "/value"), {{"text", text}});
  }
  // Saves a PNG of the window; false when the browser gave none.
  bool screenshot(const std::string& file) {
    const nlohmann::json v = call("GET", path("/screenshot"), nullptr);
    if (!v.is_string()) return false;
    std::filesystem::create_directories(std::filesystem::path(file).parent_path());
    const std::string png = decodeBase64(v.get<std::string>());
    std::ofstream(file, std::ios::binary) << png;
    return !png.empty();
  }

 private:
  std::string path(const std::string& tail) const { return "/session/" + session_ + tail; }

  // One WebDriver command; returns its "value" (an error's too).
  nlohmann::json call(const std::string& method, const std::string& p, const nlohmann::json& body) {
    httplib::Result r = method == "GET" ? client_->Get(p.c_str())
                                        : client_->Post(p.c_str(), body.dump(), "application/json");
    if (!r) return {{"error", "no answer from chromedriver"}};
    try {
      const nlohmann::json j = nlohmann::json::parse(r->body);
      if (p == "/session" && j.contains("value") && j["value"].contains("sessionId")) return j["value"];
      return j.value("value", nlohmann::json());
    } catch (const nlohmann::json::exception&) {
      return {{"error", r->body}};
    }
  }

  static int freePort() {
    const int s = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a);
    socklen_t n = sizeof a;
    ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &n);
    ::close(s);
    return ntohs(a.sin_port);
  }

  static std::string decodeBase64(const std::string& in) {
    static const std::string chars = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    int val = 0, bits = -8;
    for (char c : in) {
      const size_t k = chars.find(c);
      if (k == std::string::npos) continue;  // padding, line breaks
      val = (val << 6) + int(k);
      bits += 6;
      if (bits >= 0) {
        out.push_back(char((val >> bits) & 0xFF));
        bits -= 8;
      }
    }
    return out;
  }

  int port_ = 0;
  pid_t pid_ = -1;
  std::unique_ptr<httplib::Client> client_;
  std::string session_, why_;
};

}  // namespace dv

#pragma once
// A test suite over one `dotvision serve` with its console (console_serve.h)
// for all its tests, the operator's token in a token file the config names:
// derive, and start it from SetUpTestSuite with startServe(prefix, token)
// (or startRun(prefix) for `dotvision run --http`).
// Include this header last: it brings httplib.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "console_serve.h"
// Last: it brings <resolv.h>, whose _res macro breaks Eigen headers included after it.
#include <httplib.h>

namespace dv {

class ConsoleSuite : public ::testing::Test {
 protected:
  using json = nlohmann::json;

  static void startServe(const std::string& prefix, const std::string& token) {
    token_ = token;
    serve_ = new ConsoleServe(prefix, "console: {token_file: TOKEN_FILE}\n");
    // The token file lives in the serve's temp dir; rewrite the placeholder.
    const std::string token_file = serve_->dir().file("token");
    std::ofstream(token_file) << token << "\n";
    std::string text = serve_->configText();
    text.replace(text.find("TOKEN_FILE"), 10, token_file);
    std::ofstream(serve_->configPath()) << text;
    started_ = serve_->start();
  }
  // `dotvision run --http` on camera 0 instead; the token is the printed one.
  static void startRun(const std::string& prefix) {
    serve_ = new ConsoleServe(prefix);
    started_ = serve_->startRun();
    token_ = serve_->printedToken();
  }
  static void TearDownTestSuite() {
    delete serve_;
    serve_ = nullptr;
    started_ = false;
  }
  void SetUp() override { ASSERT_TRUE(started_) << serve_->log(); }

  static httplib::Client client() {
    httplib::Client c("127.0.0.1", serve_->port());
    c.set_read_timeout(30, 0);
    return c;
  }
  // Null unless answered 200 (a request timing out on a loaded machine).
  static json getJson(const std::string& path) {
    auto r = client().Get(path.c_str());
    if (!r || r->status != 200) return json();
    return json::parse(r->body);
  }
  static httplib::Headers auth() { return {{"Authorization", "Bearer " + token_}}; }
  // The status records once every camera has processed frames.
  static json liveStatus() {
    json s;
    ConsoleServe::waitFor([&] {
      s = getJson("/api/status");
      if (!s.is_object() || s["cameras"].size() != 2) return false;
      for (const json& c : s["cameras"])
        if (c["fps_out"].get<double>() <= 0) return false;
      return true;
    });
    return s;
  }

  // Starts a run on camera `id` with the token and waits for it to end;
  // null (with a failure added) when it does not start or never ends.
  static json finishedRun(int id, const std::string& body) {
    auto r = client().Post(("/api/cameras/" + std::to_string(id) + "/calibrate").c_str(), auth(), body,
                           "application/json");
    if (!r || r->status != 202 || json::parse(r->body)["state"] != "running") {
      ADD_FAILURE() << "not started: " << (r ? r->body : "no answer");
      return json();
    }
    json run;
    if (!ConsoleServe::waitFor([&] {
          run = getJson("/api/cameras/" + std::to_string(id) + "/calibration");
          return run.is_object() && run["state"] != "running";
        }, 300)) {
      ADD_FAILURE() << "still running: " << run.dump();
      return json();
    }
    return run;
  }

  // One suite runs at a time; each starts its own serve.
  inline static ConsoleServe* serve_ = nullptr;
  inline static bool started_ = false;
  inline static std::string token_;
};

}  // namespace dv

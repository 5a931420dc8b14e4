#pragma once
// Running the dotvision binary from a test: to the end with its output
// captured, or in the background (to signal it), its stdout and stderr in
// one file.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace dv {

inline std::string readAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs `dotvision ARGS` to its end; returns the exit code, `out` gets stdout and stderr.
inline int runCli(const std::string& args, std::string& out) {
  const std::string file = "/tmp/dv_cli_" + std::to_string(::getpid()) + ".txt";
  const int status = std::system((std::string("'") + DV_CLI_PATH + "' " + args + " >" + file + " 2>&1").c_str());
  out = readAll(file);
  std::remove(file.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Starts `dotvision ARGS...` in the background, its output to `log`.
inline pid_t spawnCli(const std::vector<std::string>& args, const std::string& log) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (!freopen(log.c_str(), "w", stdout)) _exit(126);
    ::dup2(STDOUT_FILENO, STDERR_FILENO);  // one file offset for both
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(DV_CLI_PATH));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(DV_CLI_PATH, argv.data());
    _exit(127);
  }
  return pid;
}

// Waits for the process; its exit code, -1 when killed by a signal.
inline int waitExit(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace dv

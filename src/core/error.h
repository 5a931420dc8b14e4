#pragma once
// Errors at the edges of the system (files, command line, network) carry the
// source they came from, so the CLI can print one clear line and exit 2.
#include <stdexcept>
#include <string>

namespace dv {

class InputError : public std::runtime_error {
 public:
  // source: file path, "command line", "udp 224.5.23.2:10006", ...
  // what: where in the source and what is wrong.
  InputError(std::string source, const std::string& what)
      : std::runtime_error(source + ": " + what), source_(std::move(source)) {}
  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

}  // namespace dv

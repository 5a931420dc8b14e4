#pragma once
// Strict reading of a YAML config: every key known, every value of the
// right type and range, else one InputError("<file>:<line>", "key 'a.b[1].c':
// what is wrong"). Keys are written as paths from the top of the file, so a
// message says exactly which value is meant.
#include <yaml-cpp/yaml.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace dv::app {

// The candidate closest to `word` (edit distance, ignoring case) where it is
// close enough to be a likely typo; nullopt otherwise.
std::optional<std::string> closestWord(const std::string& word, const std::vector<std::string>& candidates);

// {a, b, c} -> "a, b, c".
std::string joinWords(const std::vector<std::string>& words);

class StrictYaml {
 public:
  explicit StrictYaml(std::string file) : file_(std::move(file)) {}
  const std::string& file() const { return file_; }

  // "<file>:<line>" of a node (1-based), or the file alone for a node without a place.
  std::string where(const YAML::Node& at) const;
  [[noreturn]] void fail(const YAML::Node& at, const std::string& key, const std::string& what) const;

  // Calls fn(child_key_path, value) for each entry of `map` whose value is not
  // null (null keeps the default), in file order. Rejects a value that is not a
  // map, a key outside `allowed` (listing them, with a "did you mean") and a
  // key given twice (naming both lines). A null `map` has no entries.
  void forEach(const YAML::Node& map, const std::string& path, const std::vector<std::string>& allowed,
               const std::function<void(const std::string& key, const YAML::Node& value)>& fn) const;

  double number(const YAML::Node& n, const std::string& key) const;
  // number() within [lo, hi] (lo excluded where lo_open); `unit` and `why`
  // (may be empty) go into the message.
  double number(const YAML::Node& n, const std::string& key, double lo, double hi, const std::string& unit,
                bool lo_open = false, const std::string& why = "") const;
  long long integer(const YAML::Node& n, const std::string& key, long long lo, long long hi) const;
  bool boolean(const YAML::Node& n, const std::string& key) const;
  std::string text(const YAML::Node& n, const std::string& key) const;
  // text() that must be one of `allowed`.
  std::string choice(const YAML::Node& n, const std::string& key, const std::vector<std::string>& allowed) const;

 private:
  std::string file_;
};

// "path.key", or "key" at the top.
std::string childKey(const std::string& path, const std::string& key);

}  // namespace dv::app

#include "app/strict_yaml.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <sstream>

#include "core/error.h"

namespace dv::app {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// How a value that is not a scalar is named in "got ..." messages.
std::string shapeOf(const YAML::Node& n) {
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a map";
  if (n.IsNull()) return "nothing";
  return "'" + n.Scalar() + "'";
}

std::string numberText(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

std::optional<std::string> closestWord(const std::string& word, const std::vector<std::string>& candidates) {
  const std::string w = lower(word);
  std::optional<std::string> best;
  size_t best_distance = 0;
  for (const std::string& c : candidates) {
    const size_t d = editDistance(w, lower(c));
    if (!best || d < best_distance) best = c, best_distance = d;
  }
  // A typo: a couple of letters, or a third of a long word.
  const size_t limit = std::max<size_t>(2, w.size() / 3);
  if (!best || best_distance > limit || best_distance >= w.size()) return std::nullopt;
  return best;
}

std::string joinWords(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : ", ") + w;
  return out;
}

std::string childKey(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string StrictYaml::where(const YAML::Node& at) const {
  const YAML::Mark m = at.Mark();
  return m.line < 0 ? file_ : file_ + ":" + std::to_string(m.line + 1);
}

void StrictYaml::fail(const YAML::Node& at, const std::string& key, const std::string& what) const {
  if (key.empty()) throw InputError(where(at), what);
  throw InputError(where(at), "key '" + key + "': " + what);
}

void StrictYaml::forEach(const YAML::Node& map, const std::string& path, const std::vector<std::string>& allowed,
                         const std::function<void(const std::string&, const YAML::Node&)>& fn) const {
  if (!map.IsDefined() || map.IsNull()) return;
  if (!map.IsMap()) fail(map, path, "expected a map of keys (" + joinWords(allowed) + "), got " + shapeOf(map));
  std::map<std::string, int> seen;  // key -> its line (1-based)
  for (const auto& kv : map) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : "";
    const std::string full = childKey(path, key);
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      std::string what = "unknown key (allowed " + std::string(path.empty() ? "at the top" : "here") + ": " +
                         joinWords(allowed) + ")";
      if (const auto near = closestWord(key, allowed)) what += "; did you mean '" + *near + "'?";
      fail(kv.first, full, what);
    }
    const int line = kv.first.Mark().line + 1;
    if (const auto it = seen.find(key); it != seen.end())
      fail(kv.first, full, "given twice (lines " + std::to_string(it->second) + " and " + std::to_string(line) + ")");
    seen[key] = line;
  }
  for (const auto& kv : map)
    if (!kv.second.IsNull()) fn(childKey(path, kv.first.Scalar()), kv.second);
}

double StrictYaml::number(const YAML::Node& n, const std::string& key) const {
  if (!n.IsScalar()) fail(n, key, "expected a number, got " + shapeOf(n));
  double v = 0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    fail(n, key, "expected a number, got " + shapeOf(n));
  }
  if (!std::isfinite(v)) fail(n, key, "expected a finite number, got " + shapeOf(n));
  return v;
}

double StrictYaml::number(const YAML::Node& n, const std::string& key, double lo, double hi,
                          const std::string& unit, bool lo_open, const std::string& why) const {
  const double v = number(n, key);
  if (v < lo || v > hi || (lo_open && v == lo)) {
    const std::string u = unit.empty() ? "" : " " + unit;
    std::string what = numberText(v) + u + " is out of range: ";
    what += lo_open ? "must be more than " + numberText(lo) + u + " and at most " + numberText(hi) + u
                    : "must be " + numberText(lo) + ".." + numberText(hi) + u;
    if (!why.empty()) what += " (" + why + ")";
    fail(n, key, what);
  }
  return v;
}

long long StrictYaml::integer(const YAML::Node& n, const std::string& key, long long lo, long long hi) const {
  if (!n.IsScalar()) fail(n, key, "expected a whole number, got " + shapeOf(n));
  long long v = 0;
  try {
    v = n.as<long long>();
  } catch (const YAML::Exception&) {
    fail(n, key, "expected a whole number, got " + shapeOf(n));
  }
  if (v < lo || v > hi)
    fail(n, key, std::to_string(v) + " is out of range: must be " + std::to_string(lo) + ".." + std::to_string(hi));
  return v;
}

bool StrictYaml::boolean(const YAML::Node& n, const std::string& key) const {
  if (!n.IsScalar()) fail(n, key, "expected true or false, got " + shapeOf(n));
  try {
    return n.as<bool>();
  } catch (const YAML::Exception&) {
    fail(n, key, "expected true or false, got " + shapeOf(n));
  }
}

std::string StrictYaml::text(const YAML::Node& n, const std::string& key) const {
  if (!n.IsScalar()) fail(n, key, "expected a text, got " + shapeOf(n));
  return n.Scalar();
}

std::string StrictYaml::choice(const YAML::Node& n, const std::string& key,
                               const std::vector<std::string>& allowed) const {
  const std::string v = text(n, key);
  if (std::find(allowed.begin(), allowed.end(), v) != allowed.end()) return v;
  std::string what = "expected one of " + joinWords(allowed) + ", got '" + v + "'";
  if (const auto near = closestWord(v, allowed)) what += "; did you mean '" + *near + "'?";
  fail(n, key, what);
}

}  // namespace dv::app

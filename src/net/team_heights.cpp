#include "net/team_heights.h"

#include <cctype>
#include <cmath>

#include "core/error.h"

namespace dv {
namespace {

std::string nameKey(const std::string& name) {
  const size_t a = name.find_first_not_of(" \t\r\n"), b = name.find_last_not_of(" \t\r\n");
  std::string key = a == std::string::npos ? std::string() : name.substr(a, b - a + 1);
  for (char& c : key) c = char(std::tolower(static_cast<unsigned char>(c)));
  return key;
}

std::string mmText(double mm) {
  std::string t = std::to_string(mm);
  t.erase(t.find_last_not_of('0') + 1);
  if (!t.empty() && t.back() == '.') t.pop_back();
  return t + " mm";
}

double checkedHeight(double mm, const std::string& what, const std::string& origin) {
  if (!std::isfinite(mm) || mm < kMinRobotHeight_mm || mm > kMaxRobotHeight_mm)
    throw InputError(origin, what + " height " + mmText(mm) + " is outside " + mmText(kMinRobotHeight_mm) +
                                 ".." + mmText(kMaxRobotHeight_mm));
  return mm;
}

}  // namespace

TeamHeights::TeamHeights(double default_mm, const std::string& origin)
    : default_mm_(checkedHeight(default_mm, "default robot", origin)) {}

void TeamHeights::addTeam(const std::string& name, double height_mm, const std::string& origin) {
  const std::string key = nameKey(name);
  if (key.empty()) throw InputError(origin, "a team height without a team name");
  checkedHeight(height_mm, "team \"" + name + "\"", origin);
  if (!by_key_.emplace(key, height_mm).second)
    throw InputError(origin, "team \"" + name + "\" is listed twice (names match case-insensitively)");
}

void TeamHeights::setYellow(double height_mm, const std::string& origin) {
  yellow_mm_ = checkedHeight(height_mm, "yellow robot", origin);
}

void TeamHeights::setBlue(double height_mm, const std::string& origin) {
  blue_mm_ = checkedHeight(height_mm, "blue robot", origin);
}

std::optional<double> TeamHeights::find(const std::string& name) const {
  auto it = by_key_.find(nameKey(name));
  if (it == by_key_.end()) return std::nullopt;
  return it->second;
}

double TeamHeights::colorHeight(const std::optional<double>& fixed, const std::string& color,
                                const std::string& team, bool referee_valid,
                                std::vector<std::string>& warnings) {
  if (fixed) return *fixed;
  if (!referee_valid) return default_mm_;
  if (auto mm = find(team)) return *mm;
  const std::string key = nameKey(team);
  const std::string warn_key = key.empty() ? color + ":" : key;
  if (warned_.insert(warn_key).second) {
    warnings.push_back(key.empty()
                           ? "the game controller names no " + color +
                                 " team yet; using the default robot height " + mmText(default_mm_)
                           : "team \"" + team + "\" (" + color +
                                 ") is not in the team height table; using the default robot height " +
                                 mmText(default_mm_));
  }
  return default_mm_;
}

TeamHeightsResult TeamHeights::resolve(const RefereeSnapshot& referee) {
  TeamHeightsResult r;
  r.yellow_mm = colorHeight(yellow_mm_, "yellow", referee.yellow_name, referee.valid, r.warnings);
  r.blue_mm = colorHeight(blue_mm_, "blue", referee.blue_name, referee.valid, r.warnings);
  return r;
}

}  // namespace dv

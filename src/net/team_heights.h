#pragma once
// Robot heights by team: the league's robots are 130-150 mm tall and every
// blob is projected along its camera ray to its robot's height, so the
// height of the team playing each color must be known. The table maps team
// names (as the game controller spells them, matched case-insensitively and
// without surrounding blanks) to heights; a fixed per-color height, where
// configured, wins over the names.
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "net/referee_listener.h"

namespace dv {

inline constexpr double kDefaultRobotHeight_mm = 140;
// Heights outside this range are refused: no league robot is that tall or short.
inline constexpr double kMinRobotHeight_mm = 50;
inline constexpr double kMaxRobotHeight_mm = 300;

struct TeamHeightsResult {
  double yellow_mm = kDefaultRobotHeight_mm;
  double blue_mm = kDefaultRobotHeight_mm;
  std::vector<std::string> warnings;  // new ones only: each is given once
};

class TeamHeights {
 public:
  // Each setter checks the height and throws InputError(origin, ...) for a
  // value outside kMinRobotHeight_mm..kMaxRobotHeight_mm, and addTeam also
  // for an empty name or a name given twice (case-insensitively).
  explicit TeamHeights(double default_mm = kDefaultRobotHeight_mm,
                       const std::string& origin = "robot heights");
  void addTeam(const std::string& name, double height_mm, const std::string& origin);
  void setYellow(double height_mm, const std::string& origin);  // fixed, whatever the team
  void setBlue(double height_mm, const std::string& origin);

  double defaultHeight() const { return default_mm_; }
  // The height listed for `name`, if any (case-insensitive).
  std::optional<double> find(const std::string& name) const;

  // Heights for the teams the referee names. Without a referee packet yet
  // (snapshot.valid false), the default (or the per-color height). An
  // unknown or empty team name gets the default height and one warning per
  // name (per color for an empty name) over this object's lifetime.
  TeamHeightsResult resolve(const RefereeSnapshot& referee);

 private:
  double colorHeight(const std::optional<double>& fixed, const std::string& color, const std::string& team,
                     bool referee_valid, std::vector<std::string>& warnings);

  double default_mm_;
  std::map<std::string, double> by_key_;  // key: lower case, trimmed
  std::optional<double> yellow_mm_, blue_mm_;
  std::set<std::string> warned_;  // keys (or "<color>:") already warned about
};

}  // namespace dv

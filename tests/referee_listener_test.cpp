// The game controller's referee messages over real loopback multicast:
// packets built from dotvision's own copy of the league's schema, sent with
// MulticastSender on 127.0.0.1 to a random port (parallel runs of this suite
// and the league's real port 10003 stay apart), then mapped to robot
// heights through the team table.
#include "net/referee_listener.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <random>
#include <string>
#include <thread>

#include "core/error.h"
#include "dotvision/ssl_referee.pb.h"
#include "net/multicast.h"
#include "net/team_heights.h"

namespace dv {
namespace {

constexpr char kLoopback[] = "127.0.0.1";
constexpr char kRefereeGroup[] = "224.5.23.1";

uint16_t randomPort() {
  static std::mt19937_64 rng(std::random_device{}() ^ uint64_t(::getpid()) << 32);
  return uint16_t(49000 + rng() % 8000);
}

void fillTeam(dv::ssl::Referee::TeamInfo* team, const std::string& name) {
  team->set_name(name);
  team->set_score(1);
  team->set_red_cards(0);
  team->set_yellow_cards(2);
  team->set_timeouts(4);
  team->set_timeout_time(300000000);
  team->set_goalkeeper(0);
}

dv::ssl::Referee refereePacket(const std::string& yellow, const std::string& blue, bool blue_positive,
                               dv::ssl::Referee::Command command = dv::ssl::Referee::STOP) {
  dv::ssl::Referee r;
  r.set_source_identifier("test-gc");
  r.set_packet_timestamp(1700000000123456ull);
  r.set_stage(dv::ssl::Referee::NORMAL_FIRST_HALF);
  r.set_command(command);
  r.set_command_counter(7);
  r.set_command_timestamp(1700000000000000ull);
  fillTeam(r.mutable_yellow(), yellow);
  fillTeam(r.mutable_blue(), blue);
  r.set_blue_team_on_positive_half(blue_positive);
  return r;
}

// A listener and a sender on the same fresh port.
struct Link {
  uint16_t port = randomPort();
  RefereeListener listener{RefereeListenerOptions{kRefereeGroup, port, kLoopback}};
  MulticastSender sender{kRefereeGroup, port, kLoopback};

  // Sends `bytes` every 50 ms (as a game controller repeats its state) until
  // `done` holds; false after 10 s, a safety limit only.
  bool sendUntil(const std::string& bytes, const std::function<bool()>& done) {
    for (int i = 0; i < 200; ++i) {
      sender.send(bytes);
      const uint64_t seen = listener.stats().datagrams;
      listener.waitForDatagrams(seen + 1, 0.05);
      if (done()) return true;
    }
    return done();
  }
  bool sendUntilTeams(const dv::ssl::Referee& r) {
    return sendUntil(r.SerializeAsString(), [&] {
      const RefereeSnapshot s = listener.snapshot();
      return s.valid && s.yellow_name == r.yellow().name() && s.blue_name == r.blue().name() &&
             s.blue_on_positive_half == r.blue_team_on_positive_half() && s.command == r.command();
    });
  }
};

TEST(RefereeListener, ReportsTheTeamsOfARealPacket) {
  Link link;
  EXPECT_FALSE(link.listener.snapshot().valid);
  EXPECT_EQ(link.listener.changeCount(), 0u);
  ASSERT_TRUE(link.sendUntilTeams(refereePacket("TIGERs Mannheim", "ER-Force", true)))
      << "no referee packet arrived on " << link.listener.name();

  const RefereeSnapshot s = link.listener.snapshot();
  EXPECT_EQ(s.yellow_name, "TIGERs Mannheim");
  EXPECT_EQ(s.blue_name, "ER-Force");
  EXPECT_TRUE(s.has_blue_side);
  EXPECT_TRUE(s.blue_on_positive_half);
  EXPECT_EQ(s.stage, dv::ssl::Referee::NORMAL_FIRST_HALF);
  EXPECT_EQ(s.command, dv::ssl::Referee::STOP);
  EXPECT_EQ(s.command_counter, 7u);
  EXPECT_DOUBLE_EQ(s.packet_time, 1700000000.123456);
  EXPECT_EQ(s.sender.rfind("127.0.0.1:", 0), 0u) << s.sender;
  EXPECT_EQ(s.source_identifier, "test-gc");
  EXPECT_EQ(link.listener.changeCount(), 1u);
  EXPECT_EQ(s.changes, 1u);
  EXPECT_EQ(link.listener.stats().malformed, 0u);
}

TEST(RefereeListener, TeamSwitchAndColorSwapAreChangesButACommandIsNot) {
  Link link;
  ASSERT_TRUE(link.sendUntilTeams(refereePacket("RoboTeam Twente", "KIKS", false)));
  const uint64_t first = link.listener.changeCount();
  EXPECT_EQ(first, 1u);

  // A new command with the same teams: no team change.
  ASSERT_TRUE(
      link.sendUntilTeams(refereePacket("RoboTeam Twente", "KIKS", false, dv::ssl::Referee::FORCE_START)));
  EXPECT_EQ(link.listener.changeCount(), first);

  // Colors swapped at half time.
  ASSERT_TRUE(
      link.sendUntilTeams(refereePacket("KIKS", "RoboTeam Twente", false, dv::ssl::Referee::FORCE_START)));
  EXPECT_EQ(link.listener.changeCount(), first + 1);
  EXPECT_EQ(link.listener.snapshot().yellow_name, "KIKS");

  // Sides swapped.
  ASSERT_TRUE(
      link.sendUntilTeams(refereePacket("KIKS", "RoboTeam Twente", true, dv::ssl::Referee::FORCE_START)));
  EXPECT_EQ(link.listener.changeCount(), first + 2);

  // Another team takes yellow.
  ASSERT_TRUE(
      link.sendUntilTeams(refereePacket("ZJUNlict", "RoboTeam Twente", true, dv::ssl::Referee::FORCE_START)));
  EXPECT_EQ(link.listener.changeCount(), first + 3);
  EXPECT_EQ(link.listener.snapshot().changes, first + 3);
}

TEST(RefereeListener, MalformedDatagramsAreCountedAndTheListenerGoesOn) {
  Link link;
  // Not protobuf at all (a field tag with wire type 7 does not exist).
  ASSERT_TRUE(link.sendUntil(std::string("\xff\xff\xff\xff garbage", 13),
                             [&] { return link.listener.stats().malformed >= 1; }));
  // Other garbage of another length is the same reason: still one warning.
  ASSERT_TRUE(
      link.sendUntil(std::string("\xff\xff\xfe", 3), [&] { return link.listener.stats().malformed >= 2; }));
  EXPECT_EQ(link.listener.stats().malformed_reasons, 1u);
  // Protobuf, but a Referee without its required team counters, as an old
  // or foreign sender might produce.
  dv::ssl::Referee partial = refereePacket("A", "B", true);
  partial.mutable_blue()->clear_goalkeeper();
  const uint64_t before = link.listener.stats().malformed;
  ASSERT_TRUE(link.sendUntil(partial.SerializePartialAsString(),
                             [&] { return link.listener.stats().malformed > before; }));
  EXPECT_FALSE(link.listener.snapshot().valid) << "a partial packet must not be taken";

  ASSERT_TRUE(link.sendUntilTeams(refereePacket("A", "B", true))) << "the listener stopped after bad input";
  const RefereeListenerStats stats = link.listener.stats();
  EXPECT_GE(stats.malformed, 3u);
  EXPECT_EQ(stats.malformed_reasons, 2u);
  EXPECT_GE(stats.accepted, 1u);
  EXPECT_EQ(stats.datagrams, stats.accepted + stats.malformed);
}

TEST(RefereeListener, BadGroupNamesTheEndpoint) {
  try {
    RefereeListener listener(RefereeListenerOptions{"10.0.0.1", 10003, ""});
    FAIL() << "a unicast group was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("udp 10.0.0.1:10003"), std::string::npos) << e.what();
  }
}

RefereeSnapshot teams(const std::string& yellow, const std::string& blue) {
  RefereeSnapshot s;
  s.valid = true;
  s.yellow_name = yellow;
  s.blue_name = blue;
  return s;
}

TEST(TeamHeights, NamesMatchCaseInsensitively) {
  TeamHeights table(140, "test");
  table.addTeam("TIGERs Mannheim", 145, "test");
  table.addTeam("ER-Force", 135, "test");
  const TeamHeightsResult r = table.resolve(teams("tigers MANNHEIM ", "er-force"));
  EXPECT_DOUBLE_EQ(r.yellow_mm, 145);
  EXPECT_DOUBLE_EQ(r.blue_mm, 135);
  EXPECT_TRUE(r.warnings.empty());
}

TEST(TeamHeights, UnknownTeamGetsTheDefaultAndOneWarning) {
  TeamHeights table(142, "test");
  table.addTeam("KIKS", 148, "test");
  TeamHeightsResult r = table.resolve(teams("Unknown United", "kiks"));
  EXPECT_DOUBLE_EQ(r.yellow_mm, 142);
  EXPECT_DOUBLE_EQ(r.blue_mm, 148);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("\"Unknown United\""), std::string::npos) << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("142 mm"), std::string::npos) << r.warnings[0];

  // Same team again, even on the other color or in other case: no new warning.
  r = table.resolve(teams("kiks", "UNKNOWN UNITED"));
  EXPECT_DOUBLE_EQ(r.yellow_mm, 148);
  EXPECT_DOUBLE_EQ(r.blue_mm, 142);
  EXPECT_TRUE(r.warnings.empty());
  // A second unknown team warns for itself.
  r = table.resolve(teams("kiks", "Other FC"));
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("Other FC"), std::string::npos);
}

TEST(TeamHeights, ColorOverridesWinAndNoRefereeMeansDefault) {
  TeamHeights table(140, "test");
  table.addTeam("KIKS", 148, "test");
  EXPECT_DOUBLE_EQ(table.resolve(RefereeSnapshot{}).yellow_mm, 140);
  EXPECT_TRUE(table.resolve(RefereeSnapshot{}).warnings.empty()) << "no referee yet is not an unknown team";
  table.setBlue(131, "test");
  const TeamHeightsResult r = table.resolve(teams("KIKS", "KIKS"));
  EXPECT_DOUBLE_EQ(r.yellow_mm, 148);
  EXPECT_DOUBLE_EQ(r.blue_mm, 131);
  EXPECT_DOUBLE_EQ(table.resolve(RefereeSnapshot{}).blue_mm, 131);
}

TEST(TeamHeights, EmptyTeamNameWarnsOncePerColor) {
  TeamHeights table(140, "test");
  TeamHeightsResult r = table.resolve(teams("", ""));
  EXPECT_DOUBLE_EQ(r.yellow_mm, 140);
  ASSERT_EQ(r.warnings.size(), 2u);
  EXPECT_NE(r.warnings[0].find("no yellow team"), std::string::npos) << r.warnings[0];
  EXPECT_TRUE(table.resolve(teams("", "")).warnings.empty());
}

TEST(TeamHeights, BadEntriesAreRefusedNamingTheOrigin) {
  TeamHeights table(140, "site.yaml:12");
  EXPECT_THROW(TeamHeights(20, "x"), InputError);
  try {
    table.addTeam("KIKS", 1450, "site.yaml:14");
    FAIL() << "1450 mm accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("site.yaml:14"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("KIKS"), std::string::npos) << e.what();
  }
  table.addTeam("KIKS", 145, "site.yaml:14");
  EXPECT_THROW(table.addTeam("kiks", 146, "site.yaml:15"), InputError);
  EXPECT_THROW(table.addTeam("  ", 146, "site.yaml:16"), InputError);
  EXPECT_THROW(table.setYellow(-1, "site.yaml:17"), InputError);
}

// The whole path: a team switch sent by the "game controller" changes the
// heights a consumer resolves at its next check of changeCount().
TEST(TeamHeights, RefereeTeamSwitchChangesTheHeights) {
  Link link;
  TeamHeights table(140, "test");
  table.addTeam("TIGERs Mannheim", 145, "test");
  table.addTeam("ER-Force", 135, "test");
  ASSERT_TRUE(link.sendUntilTeams(refereePacket("TIGERs Mannheim", "ER-Force", false)));
  uint64_t applied = link.listener.changeCount();
  TeamHeightsResult r = table.resolve(link.listener.snapshot());
  EXPECT_DOUBLE_EQ(r.yellow_mm, 145);
  EXPECT_DOUBLE_EQ(r.blue_mm, 135);

  ASSERT_TRUE(link.sendUntilTeams(refereePacket("ER-Force", "TIGERs Mannheim", false)));
  ASSERT_NE(link.listener.changeCount(), applied);
  applied = link.listener.changeCount();
  r = table.resolve(link.listener.snapshot());
  EXPECT_DOUBLE_EQ(r.yellow_mm, 135);
  EXPECT_DOUBLE_EQ(r.blue_mm, 145);
}

}  // namespace
}  // namespace dv

// dotvision's Referee (package dv.ssl, only the fields it reads plus every
// required one) against the game controller's ssl_gc_referee_message.proto:
// each field we declare matches the league's, packets the league's schema
// writes parse with ours (the fields we leave out kept as unknown fields and
// forwarded unchanged), and packets we write parse with the league's.
#include <google/protobuf/stubs/logging.h>
#include <gtest/gtest.h>

#include <string>

#include "dotvision/ssl_referee.pb.h"
#include "proto_reflection.h"
#include "state/ssl_gc_referee_message.pb.h"

namespace dv::conformance {
namespace {

TEST(RefereeConformance, OurFieldsAreTheLeaguesAndNoRequiredOneIsMissing) {
  EXPECT_EQ(::Referee::descriptor()->file()->name(), "state/ssl_gc_referee_message.proto");
  EXPECT_EQ(joined(partDescriptorDifferences(*dv::ssl::Referee::descriptor(), *::Referee::descriptor())), "");
  // The check itself can fail: the league's TeamInfo is not its Referee.
  EXPECT_NE(
      joined(partDescriptorDifferences(*dv::ssl::Referee::TeamInfo::descriptor(), *::Referee::descriptor())),
      "");
}

TEST(RefereeConformance, EnumsHaveTheLeaguesValues) {
  EXPECT_EQ(joined(enumDifferences(*dv::ssl::Referee::Stage_descriptor(), *::Referee::Stage_descriptor())),
            "");
  EXPECT_EQ(
      joined(enumDifferences(*dv::ssl::Referee::Command_descriptor(), *::Referee::Command_descriptor())), "");
}

TEST(RefereeConformance, LeaguePacketsParseWithOursAndPassThroughUnchanged) {
  ::Referee league;
  fillEveryField(league, 11);  // game events, proposals, timers: all set
  ASSERT_TRUE(league.IsInitialized()) << league.InitializationErrorString();
  dv::ssl::Referee ours;
  ASSERT_TRUE(ours.ParseFromString(league.SerializeAsString())) << ours.InitializationErrorString();
  EXPECT_EQ(joined(partMessageDifferences(ours, league)), "");
  EXPECT_EQ(ours.yellow().name(), league.yellow().name());
  EXPECT_NE(joined(unknownFields(ours)), "") << "the fields we leave out are kept as unknown fields";

  ::Referee again;
  ASSERT_TRUE(again.ParseFromString(ours.SerializeAsString()));
  EXPECT_EQ(joined(messageDifferences(league, again)), "");
}

TEST(RefereeConformance, OurPacketsParseWithTheLeagues) {
  dv::ssl::Referee ours;
  fillEveryField(ours, 12);
  ASSERT_EQ(joined(unsetFields(ours)), "");
  ::Referee league;
  ASSERT_TRUE(league.ParseFromString(ours.SerializeAsString())) << league.InitializationErrorString();
  EXPECT_EQ(joined(partMessageDifferences(ours, league)), "");
  EXPECT_EQ(league.blue_team_on_positive_half(), ours.blue_team_on_positive_half());
}

// Clearing any one of our required fields makes both schemas reject the bytes.
TEST(RefereeConformance, SameFieldsAreRequired) {
  google::protobuf::LogSilencer quiet;
  for (const auto* d : {dv::ssl::Referee::descriptor(), dv::ssl::Referee::TeamInfo::descriptor()}) {
    for (int i = 0; i < d->field_count(); ++i) {
      const auto* field = d->field(i);
      if (!field->is_required()) continue;
      dv::ssl::Referee ours;
      fillEveryField(ours, 13);
      google::protobuf::Message& holder = d == dv::ssl::Referee::descriptor()
                                              ? static_cast<google::protobuf::Message&>(ours)
                                              : *ours.mutable_blue();
      holder.GetReflection()->ClearField(&holder, field);
      const std::string bytes = ours.SerializePartialAsString();
      ::Referee league;
      EXPECT_FALSE(league.ParseFromString(bytes)) << field->full_name() << " is optional there";
      dv::ssl::Referee ours_again;
      EXPECT_FALSE(ours_again.ParseFromString(bytes)) << field->full_name();
    }
  }
}

}  // namespace
}  // namespace dv::conformance

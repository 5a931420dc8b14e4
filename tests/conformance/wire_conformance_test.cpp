// dotvision's schemas (package dv.ssl) against the league's reference
// schemas (global namespace, ../shared/reference/proto): the descriptors
// must agree field by field, and bytes written with one must decode with
// the other to the same values, in both directions. Everything is driven by
// descriptor reflection, so a field added on either side fails here until
// the other side has it too.
#include <google/protobuf/descriptor.h>
#include <google/protobuf/dynamic_message.h>
#include <google/protobuf/stubs/logging.h>
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "dotvision/ssl_detection.pb.h"
#include "dotvision/ssl_geometry.pb.h"
#include "dotvision/ssl_wrapper.pb.h"
#include "messages_robocup_ssl_detection.pb.h"
#include "messages_robocup_ssl_geometry.pb.h"
#include "messages_robocup_ssl_wrapper.pb.h"
#include "messages_robocup_ssl_wrapper_legacy.pb.h"
#include "proto_reflection.h"

namespace dv::conformance {
namespace {

using google::protobuf::Descriptor;
using google::protobuf::DescriptorPool;
using google::protobuf::EnumDescriptor;
using google::protobuf::FileDescriptor;
using google::protobuf::Message;
using google::protobuf::MessageFactory;

constexpr char kOurPackage[] = "dv.ssl.";

// Our three schema files and the league's three vision files.
std::vector<const FileDescriptor*> ourFiles() {
  return {dv::ssl::SSL_DetectionFrame::descriptor()->file(),
          dv::ssl::SSL_GeometryData::descriptor()->file(),
          dv::ssl::SSL_WrapperPacket::descriptor()->file()};
}
std::vector<const FileDescriptor*> leagueFiles() {
  return {::SSL_DetectionFrame::descriptor()->file(), ::SSL_GeometryData::descriptor()->file(),
          ::SSL_WrapperPacket::descriptor()->file()};
}

const Descriptor* leagueMessage(const std::string& name) {
  return DescriptorPool::generated_pool()->FindMessageTypeByName(name);
}
const Descriptor* ourMessage(const std::string& name) {
  return DescriptorPool::generated_pool()->FindMessageTypeByName(kOurPackage + name);
}

std::unique_ptr<Message> newMessage(const Descriptor* d) {
  return std::unique_ptr<Message>(MessageFactory::generated_factory()->GetPrototype(d)->New());
}

// Every message type of our files, by its unqualified name.
std::vector<std::string> ourMessageNames() {
  std::vector<std::string> names;
  for (const auto* f : ourFiles()) {
    for (int i = 0; i < f->message_type_count(); ++i) names.push_back(f->message_type(i)->name());
  }
  return names;
}

TEST(SchemaConformance, ReferenceIsTheLeagueSchema) {
  // Guards against the build picking up some other copy.
  EXPECT_EQ(::SSL_WrapperPacket::descriptor()->full_name(), "SSL_WrapperPacket");
  EXPECT_EQ(::SSL_WrapperPacket::descriptor()->file()->name(), "messages_robocup_ssl_wrapper.proto");
  EXPECT_EQ(dv::ssl::SSL_WrapperPacket::descriptor()->full_name(), "dv.ssl.SSL_WrapperPacket");
}

TEST(SchemaConformance, EveryOurMessageMatchesTheLeagueDescriptor) {
  int compared = 0;
  for (const auto& name : ourMessageNames()) {
    const Descriptor* ours = ourMessage(name);
    const Descriptor* league = leagueMessage(name);
    ASSERT_NE(league, nullptr) << name << " has no counterpart in the league schema";
    EXPECT_EQ(joined(descriptorDifferences(*ours, *league)), "") << name;
    ++compared;
  }
  EXPECT_GE(compared, 13);  // 3 detection + 9 geometry + 1 wrapper messages today
}

TEST(SchemaConformance, EveryLeagueMessageAndEnumExistsInOurs) {
  for (const auto* file : leagueFiles()) {
    for (int i = 0; i < file->message_type_count(); ++i) {
      const std::string name = file->message_type(i)->name();
      EXPECT_NE(ourMessage(name), nullptr) << file->name() << ": " << name << " missing in dv.ssl";
    }
    for (int i = 0; i < file->enum_type_count(); ++i) {
      const std::string name = file->enum_type(i)->name();
      EXPECT_NE(DescriptorPool::generated_pool()->FindEnumTypeByName(kOurPackage + name), nullptr)
          << file->name() << ": enum " << name << " missing in dv.ssl";
    }
  }
}

TEST(SchemaConformance, EnumsHaveTheSameValues) {
  int compared = 0;
  for (const auto* file : ourFiles()) {
    for (int i = 0; i < file->enum_type_count(); ++i) {
      const EnumDescriptor* ours = file->enum_type(i);
      const EnumDescriptor* league =
          DescriptorPool::generated_pool()->FindEnumTypeByName(ours->name());
      ASSERT_NE(league, nullptr) << ours->name();
      EXPECT_EQ(joined(enumDifferences(*ours, *league)), "");
      ++compared;
    }
  }
  EXPECT_EQ(compared, 2);  // SSL_FieldShapeType, SSL_Source
  EXPECT_EQ(::SSL_FieldShapeType_MAX, int(dv::ssl::SSL_FieldShapeType_MAX));
  EXPECT_EQ(::SSL_Source_MAX, int(dv::ssl::SSL_Source_MAX));
}

// Fills `from` completely, sends its bytes through `to`'s schema and checks
// that nothing was lost, added or changed, and that `to` writes the very
// same bytes back.
void expectLosslessTransfer(Message& from, Message& to, int seed) {
  fillEveryField(from, seed);
  ASSERT_EQ(joined(unsetFields(from)), "") << "the filler missed fields";
  const std::string bytes = from.SerializeAsString();
  ASSERT_TRUE(to.ParseFromString(bytes))
      << to.GetDescriptor()->full_name() << " rejects " << from.GetDescriptor()->full_name()
      << ": " << to.InitializationErrorString();
  EXPECT_EQ(joined(unknownFields(to)), "") << "fields the receiving schema does not know";
  EXPECT_EQ(joined(unsetFields(to)), "") << "fields the sending schema does not have";
  EXPECT_EQ(joined(messageDifferences(from, to)), "");
  EXPECT_EQ(to.SerializeAsString(), bytes) << "re-encoding changed the bytes";
}

class MessageConformance : public ::testing::TestWithParam<std::string> {};

TEST_P(MessageConformance, OursDecodesWithTheLeagueSchema) {
  auto ours = newMessage(ourMessage(GetParam()));
  auto league = newMessage(leagueMessage(GetParam()));
  ASSERT_TRUE(ours && league);
  expectLosslessTransfer(*ours, *league, 1);
}

TEST_P(MessageConformance, LeagueDecodesWithOurSchema) {
  auto ours = newMessage(ourMessage(GetParam()));
  auto league = newMessage(leagueMessage(GetParam()));
  ASSERT_TRUE(ours && league);
  expectLosslessTransfer(*league, *ours, 2);
}

// Clearing any one required field must make both schemas reject the bytes.
TEST_P(MessageConformance, SameFieldsAreRequired) {
  google::protobuf::LogSilencer quiet;  // each rejection would log a line
  const Descriptor* d = ourMessage(GetParam());
  for (int i = 0; i < d->field_count(); ++i) {
    const auto* field = d->field(i);
    if (!field->is_required()) continue;
    auto ours = newMessage(d);
    fillEveryField(*ours, 3);
    ours->GetReflection()->ClearField(ours.get(), field);
    const std::string bytes = ours->SerializePartialAsString();
    auto league = newMessage(leagueMessage(GetParam()));
    EXPECT_FALSE(league->ParseFromString(bytes)) << field->full_name() << " is optional there";
    auto ours_again = newMessage(d);
    EXPECT_FALSE(ours_again->ParseFromString(bytes)) << field->full_name();
  }
}

INSTANTIATE_TEST_SUITE_P(AllMessages, MessageConformance, ::testing::ValuesIn(ourMessageNames()),
                         [](const auto& info) { return info.param; });

// The packets ssl-vision actually sends: detection and geometry travel in
// separate wrappers, each with source = SSL_SOURCE_SSL_VISION.
TEST(WrapperConformance, DetectionOnlyPacket) {
  dv::ssl::SSL_WrapperPacket ours;
  fillEveryField(*ours.mutable_detection(), 4);
  ours.set_source(dv::ssl::SSL_SOURCE_SSL_VISION);
  ::SSL_WrapperPacket league;
  ASSERT_TRUE(league.ParseFromString(ours.SerializeAsString()));
  EXPECT_TRUE(league.has_detection());
  EXPECT_FALSE(league.has_geometry());
  EXPECT_EQ(league.source(), ::SSL_SOURCE_SSL_VISION);
  EXPECT_EQ(league.detection().robots_blue_size(), 3);
  EXPECT_EQ(joined(messageDifferences(ours, league)), "");
}

TEST(WrapperConformance, GeometryOnlyPacket) {
  ::SSL_WrapperPacket league;
  fillEveryField(*league.mutable_geometry(), 5);
  league.set_source(::SSL_SOURCE_SSL_VISION);
  dv::ssl::SSL_WrapperPacket ours;
  ASSERT_TRUE(ours.ParseFromString(league.SerializeAsString()));
  EXPECT_FALSE(ours.has_detection());
  EXPECT_EQ(ours.source(), dv::ssl::SSL_SOURCE_SSL_VISION);
  EXPECT_EQ(ours.geometry().field().field_lines_size(), 3);
  EXPECT_EQ(ours.geometry().calib_size(), 3);
  EXPECT_TRUE(ours.geometry().models().has_chip_fixed_loss());
  EXPECT_EQ(joined(messageDifferences(league, ours)), "");
}

// Each enum value on its own, through a field that carries it.
TEST(WrapperConformance, EveryEnumValueSurvives) {
  const EnumDescriptor* shapes = dv::ssl::SSL_FieldShapeType_descriptor();
  for (int i = 0; i < shapes->value_count(); ++i) {
    dv::ssl::SSL_FieldLineSegment line;
    fillEveryField(line, 6);
    line.set_type(dv::ssl::SSL_FieldShapeType(shapes->value(i)->number()));
    ::SSL_FieldLineSegment theirs;
    ASSERT_TRUE(theirs.ParseFromString(line.SerializeAsString()));
    EXPECT_EQ(::SSL_FieldShapeType_Name(theirs.type()), shapes->value(i)->name());
  }
  const EnumDescriptor* sources = dv::ssl::SSL_Source_descriptor();
  for (int i = 0; i < sources->value_count(); ++i) {
    dv::ssl::SSL_WrapperPacket packet;
    packet.set_source(dv::ssl::SSL_Source(sources->value(i)->number()));
    ::SSL_WrapperPacket theirs;
    ASSERT_TRUE(theirs.ParseFromString(packet.SerializeAsString()));
    EXPECT_EQ(::SSL_Source_Name(theirs.source()), sources->value(i)->name());
  }
}

// Legacy receivers (port 10005) read the same detection message inside
// RoboCup2014Legacy.Wrapper.SSL_WrapperPacket.
TEST(WrapperConformance, DetectionReadsAsLegacyWrapper) {
  dv::ssl::SSL_WrapperPacket ours;
  fillEveryField(*ours.mutable_detection(), 7);
  RoboCup2014Legacy::Wrapper::SSL_WrapperPacket legacy;
  ASSERT_TRUE(legacy.ParseFromString(ours.SerializeAsString()));
  EXPECT_EQ(joined(unknownFields(legacy)), "");
  EXPECT_EQ(joined(messageDifferences(ours.detection(), legacy.detection())), "");
}

// The comparison itself must be able to fail: a changed value, a missing
// entry and an unset field are all reported.
TEST(ReflectionHelpers, DetectDifferences) {
  dv::ssl::SSL_DetectionFrame ours;
  fillEveryField(ours, 8);
  ::SSL_DetectionFrame league;
  ASSERT_TRUE(league.ParseFromString(ours.SerializeAsString()));
  ASSERT_EQ(joined(messageDifferences(ours, league)), "");

  league.mutable_balls(1)->set_x(league.balls(1).x() + 1.0f);
  EXPECT_NE(joined(messageDifferences(ours, league)).find("balls[1].x"), std::string::npos);
  league.mutable_robots_blue()->RemoveLast();
  EXPECT_NE(joined(messageDifferences(ours, league)).find("robots_blue: 3 vs 2"), std::string::npos);
  league.clear_t_capture_camera();
  EXPECT_NE(joined(unsetFields(league)).find("t_capture_camera unset"), std::string::npos);

  // A schema with a different field type is reported by the descriptor check.
  EXPECT_NE(joined(descriptorDifferences(*dv::ssl::SSL_DetectionBall::descriptor(),
                                         *::SSL_DetectionRobot::descriptor())),
            "");
}

}  // namespace
}  // namespace dv::conformance

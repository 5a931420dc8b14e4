#pragma once
// Descriptor-driven helpers for comparing two schemas that describe the same
// wire format under different names (dv.ssl.X versus the league's global X).
// Everything walks the descriptors, so a field added to either schema is
// covered without touching the tests.
#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include <string>
#include <vector>

namespace dv::conformance {

// Sets every field of `m`, recursively: singular fields once, repeated
// fields `repeat` times, each with a different value (negative numbers,
// fractions, non-ASCII strings, non-default enum values). `seed` varies the
// values between calls. A field of a message type that contains itself is
// filled on the outer level only.
void fillEveryField(google::protobuf::Message& m, int seed, int repeat = 3);

// Paths of fields left unset (singular) or with fewer than two entries
// (repeated) anywhere in `m`; empty when the message is full.
std::vector<std::string> unsetFields(const google::protobuf::Message& m);

// Paths of submessages that hold unknown fields, i.e. data the parsing
// schema did not recognise.
std::vector<std::string> unknownFields(const google::protobuf::Message& m);

// Differences between two messages of different schemas, matched by field
// number: a field missing on one side, a different name / type / label, or
// a different value (enums compared by number and value name).
std::vector<std::string> messageDifferences(const google::protobuf::Message& a,
                                            const google::protobuf::Message& b);

// Differences between two message descriptors, recursively into message and
// enum field types: field numbers, names, types, labels, default values and
// enum values. Type names are compared without their package.
std::vector<std::string> descriptorDifferences(const google::protobuf::Descriptor& a,
                                               const google::protobuf::Descriptor& b);
std::vector<std::string> enumDifferences(const google::protobuf::EnumDescriptor& a,
                                         const google::protobuf::EnumDescriptor& b);

// Like messageDifferences and descriptorDifferences, for a schema that
// declares only part of another's fields (our Referee). Values: the fields
// `part` declares, compared with `whole`'s. Descriptors: every field of
// `part` must match `whole`'s, and every required field of `whole` must be in
// `part` (else real packets would not parse); `whole`'s optional and
// repeated fields may be missing.
std::vector<std::string> partMessageDifferences(const google::protobuf::Message& part,
                                                const google::protobuf::Message& whole);
std::vector<std::string> partDescriptorDifferences(const google::protobuf::Descriptor& part,
                                                   const google::protobuf::Descriptor& whole);

// "a; b; c" for failure messages.
std::string joined(const std::vector<std::string>& items);

}  // namespace dv::conformance

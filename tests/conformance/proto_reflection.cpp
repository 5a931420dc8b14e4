#include "proto_reflection.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <set>

namespace dv::conformance {
namespace {

using google::protobuf::Descriptor;
using google::protobuf::EnumDescriptor;
using google::protobuf::FieldDescriptor;
using google::protobuf::Message;
using google::protobuf::Reflection;

// ------------------------------------------------------------- filling

struct Filler {
  int counter;
  int repeat;
  std::vector<const Descriptor*> open;  // messages being filled, outermost first

  // Alternating signs and fractions exercise zig-zag-free varints of
  // negative int32 (10 bytes on the wire) and the exact float bits.
  int32_t nextInt32() {
    int k = counter++;
    return (k % 2 ? -1 : 1) * (k * 1009 + 7);
  }
  uint32_t nextUint32() {
    int k = counter++;
    return k % 2 ? 4000000000u - uint32_t(k) : uint32_t(k * 13 + 1);
  }
  float nextFloat() {
    int k = counter++;
    return float(k % 2 ? -1 : 1) * (float(k) * 1.5f + 0.125f);
  }
  double nextDouble() {
    int k = counter++;
    return (k % 2 ? -1.0 : 1.0) * (1.7e9 + k * 0.001);
  }

  void setOne(Message& m, const FieldDescriptor* f) {
    const Reflection* r = m.GetReflection();
    const bool rep = f->is_repeated();
    switch (f->cpp_type()) {
      case FieldDescriptor::CPPTYPE_INT32:
        rep ? r->AddInt32(&m, f, nextInt32()) : r->SetInt32(&m, f, nextInt32());
        break;
      case FieldDescriptor::CPPTYPE_INT64: {
        int64_t v = int64_t(nextInt32()) * 1000003;
        rep ? r->AddInt64(&m, f, v) : r->SetInt64(&m, f, v);
        break;
      }
      case FieldDescriptor::CPPTYPE_UINT32:
        rep ? r->AddUInt32(&m, f, nextUint32()) : r->SetUInt32(&m, f, nextUint32());
        break;
      case FieldDescriptor::CPPTYPE_UINT64: {
        uint64_t v = uint64_t(nextUint32()) * 4000037u;
        rep ? r->AddUInt64(&m, f, v) : r->SetUInt64(&m, f, v);
        break;
      }
      case FieldDescriptor::CPPTYPE_FLOAT:
        rep ? r->AddFloat(&m, f, nextFloat()) : r->SetFloat(&m, f, nextFloat());
        break;
      case FieldDescriptor::CPPTYPE_DOUBLE:
        rep ? r->AddDouble(&m, f, nextDouble()) : r->SetDouble(&m, f, nextDouble());
        break;
      case FieldDescriptor::CPPTYPE_BOOL: {
        bool v = counter++ % 2 == 0;  // the first one differs from the default
        rep ? r->AddBool(&m, f, v) : r->SetBool(&m, f, v);
        break;
      }
      case FieldDescriptor::CPPTYPE_STRING: {
        std::string v = f->name() + "_" + std::to_string(counter++) + " \xc2\xb5";
        rep ? r->AddString(&m, f, v) : r->SetString(&m, f, v);
        break;
      }
      case FieldDescriptor::CPPTYPE_ENUM: {
        const EnumDescriptor* e = f->enum_type();
        // Skip the first (default) value so "set" and "unset" differ.
        int n = e->value_count();
        int index = n > 1 ? 1 + counter++ % (n - 1) : 0;
        int number = e->value(index)->number();
        rep ? r->AddEnumValue(&m, f, number) : r->SetEnumValue(&m, f, number);
        break;
      }
      case FieldDescriptor::CPPTYPE_MESSAGE:
        fill(rep ? *r->AddMessage(&m, f) : *r->MutableMessage(&m, f));
        break;
    }
  }

  // A field whose type is already being filled (the game controller's
  // GameEvent holds GameEvents) is left out, so recursion ends.
  void fill(Message& m) {
    const Descriptor* d = m.GetDescriptor();
    open.push_back(d);
    for (int i = 0; i < d->field_count(); ++i) {
      const FieldDescriptor* f = d->field(i);
      if (f->message_type() && std::find(open.begin(), open.end(), f->message_type()) != open.end()) continue;
      const int times = f->is_repeated() ? repeat : 1;
      for (int k = 0; k < times; ++k) setOne(m, f);
    }
    open.pop_back();
  }
};

// ------------------------------------------------------------- inspecting

std::string hexFloat(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", v);
  return buf;
}

// Exact text of one non-message value; enums as NAME(number).
std::string valueText(const Message& m, const FieldDescriptor* f, int index) {
  const Reflection* r = m.GetReflection();
  const bool rep = index >= 0;
  switch (f->cpp_type()) {
    case FieldDescriptor::CPPTYPE_INT32:
      return std::to_string(rep ? r->GetRepeatedInt32(m, f, index) : r->GetInt32(m, f));
    case FieldDescriptor::CPPTYPE_INT64:
      return std::to_string(rep ? r->GetRepeatedInt64(m, f, index) : r->GetInt64(m, f));
    case FieldDescriptor::CPPTYPE_UINT32:
      return std::to_string(rep ? r->GetRepeatedUInt32(m, f, index) : r->GetUInt32(m, f));
    case FieldDescriptor::CPPTYPE_UINT64:
      return std::to_string(rep ? r->GetRepeatedUInt64(m, f, index) : r->GetUInt64(m, f));
    case FieldDescriptor::CPPTYPE_FLOAT:
      return hexFloat(rep ? r->GetRepeatedFloat(m, f, index) : r->GetFloat(m, f));
    case FieldDescriptor::CPPTYPE_DOUBLE:
      return hexFloat(rep ? r->GetRepeatedDouble(m, f, index) : r->GetDouble(m, f));
    case FieldDescriptor::CPPTYPE_BOOL:
      return (rep ? r->GetRepeatedBool(m, f, index) : r->GetBool(m, f)) ? "true" : "false";
    case FieldDescriptor::CPPTYPE_STRING:
    {
      std::string quoted(1, '"');
      quoted += rep ? r->GetRepeatedString(m, f, index) : r->GetString(m, f);
      quoted += '"';
      return quoted;
    }
    case FieldDescriptor::CPPTYPE_ENUM: {
      const auto* v = rep ? r->GetRepeatedEnum(m, f, index) : r->GetEnum(m, f);
      return v->name() + "(" + std::to_string(v->number()) + ")";
    }
    case FieldDescriptor::CPPTYPE_MESSAGE:
      break;
  }
  return "<message>";
}

std::string typeName(const FieldDescriptor* f) {
  if (f->message_type()) return f->message_type()->name();
  if (f->enum_type()) return f->enum_type()->name();
  return f->type_name();
}

const char* labelName(const FieldDescriptor* f) {
  return f->is_required() ? "required" : f->is_repeated() ? "repeated" : "optional";
}

std::string defaultText(const FieldDescriptor* f) {
  if (!f->has_default_value()) return "";
  switch (f->cpp_type()) {
    case FieldDescriptor::CPPTYPE_INT32: return std::to_string(f->default_value_int32());
    case FieldDescriptor::CPPTYPE_INT64: return std::to_string(f->default_value_int64());
    case FieldDescriptor::CPPTYPE_UINT32: return std::to_string(f->default_value_uint32());
    case FieldDescriptor::CPPTYPE_UINT64: return std::to_string(f->default_value_uint64());
    case FieldDescriptor::CPPTYPE_FLOAT: return hexFloat(f->default_value_float());
    case FieldDescriptor::CPPTYPE_DOUBLE: return hexFloat(f->default_value_double());
    case FieldDescriptor::CPPTYPE_BOOL: return f->default_value_bool() ? "true" : "false";
    case FieldDescriptor::CPPTYPE_STRING: return f->default_value_string();
    case FieldDescriptor::CPPTYPE_ENUM: return f->default_value_enum()->name();
    case FieldDescriptor::CPPTYPE_MESSAGE: break;
  }
  return "";
}

void collectUnset(const Message& m, const std::string& path, std::vector<std::string>& out) {
  const Descriptor* d = m.GetDescriptor();
  const Reflection* r = m.GetReflection();
  for (int i = 0; i < d->field_count(); ++i) {
    const FieldDescriptor* f = d->field(i);
    const std::string here = path + "." + f->name();
    if (f->is_repeated()) {
      const int n = r->FieldSize(m, f);
      if (n < 2) out.push_back(here + " has " + std::to_string(n) + " entries");
      if (f->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE) {
        for (int k = 0; k < n; ++k) {
          collectUnset(r->GetRepeatedMessage(m, f, k), here + "[" + std::to_string(k) + "]", out);
        }
      }
    } else if (!r->HasField(m, f)) {
      out.push_back(here + " unset");
    } else if (f->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE) {
      collectUnset(r->GetMessage(m, f), here, out);
    }
  }
}

void collectUnknown(const Message& m, const std::string& path, std::vector<std::string>& out) {
  const Reflection* r = m.GetReflection();
  if (!r->GetUnknownFields(m).empty()) {
    out.push_back(path + " holds " + std::to_string(r->GetUnknownFields(m).field_count()) +
                  " unknown field(s)");
  }
  std::vector<const FieldDescriptor*> fields;
  r->ListFields(m, &fields);
  for (const FieldDescriptor* f : fields) {
    if (f->cpp_type() != FieldDescriptor::CPPTYPE_MESSAGE) continue;
    const std::string here = path + "." + f->name();
    if (f->is_repeated()) {
      for (int k = 0; k < r->FieldSize(m, f); ++k) {
        collectUnknown(r->GetRepeatedMessage(m, f, k), here + "[" + std::to_string(k) + "]", out);
      }
    } else {
      collectUnknown(r->GetMessage(m, f), here, out);
    }
  }
}

// Shape of a field pair: name, wire type, label, referenced type name.
void compareFieldShape(const FieldDescriptor* fa, const FieldDescriptor* fb,
                       const std::string& here, std::vector<std::string>& out) {
  if (fa->name() != fb->name()) out.push_back(here + ": name " + fa->name() + " vs " + fb->name());
  if (fa->type() != fb->type()) {
    out.push_back(here + ": type " + fa->type_name() + " vs " + fb->type_name());
  }
  if (fa->is_required() != fb->is_required() || fa->is_repeated() != fb->is_repeated()) {
    out.push_back(here + ": label " + labelName(fa) + " vs " + labelName(fb));
  }
  if ((fa->message_type() || fa->enum_type()) && typeName(fa) != typeName(fb)) {
    out.push_back(here + ": type name " + typeName(fa) + " vs " + typeName(fb));
  }
  if (fa->is_packed() != fb->is_packed()) out.push_back(here + ": packed differs");
}

// a_is_part: `a`'s schema declares only part of `b`'s fields; fields only
// in `b` are then not differences.
void compareMessages(const Message& a, const Message& b, const std::string& path, bool a_is_part,
                     std::vector<std::string>& out) {
  const Descriptor* da = a.GetDescriptor();
  const Descriptor* db = b.GetDescriptor();
  const Reflection* ra = a.GetReflection();
  const Reflection* rb = b.GetReflection();
  for (int i = 0; i < db->field_count(); ++i) {
    if (!a_is_part && !da->FindFieldByNumber(db->field(i)->number())) {
      out.push_back(path + ": field " + std::to_string(db->field(i)->number()) + " (" +
                    db->field(i)->name() + ") exists only in " + db->full_name());
    }
  }
  for (int i = 0; i < da->field_count(); ++i) {
    const FieldDescriptor* fa = da->field(i);
    const std::string here = path + "." + fa->name();
    const FieldDescriptor* fb = db->FindFieldByNumber(fa->number());
    if (!fb) {
      out.push_back(here + ": field " + std::to_string(fa->number()) + " exists only in " +
                    da->full_name());
      continue;
    }
    const size_t before = out.size();
    compareFieldShape(fa, fb, here, out);
    if (out.size() != before) continue;  // values of different shapes are not comparable

    const bool is_message = fa->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE;
    if (fa->is_repeated()) {
      const int na = ra->FieldSize(a, fa);
      const int nb = rb->FieldSize(b, fb);
      if (na != nb) {
        out.push_back(here + ": " + std::to_string(na) + " vs " + std::to_string(nb) + " entries");
        continue;
      }
      for (int k = 0; k < na; ++k) {
        const std::string item = here + "[" + std::to_string(k) + "]";
        if (is_message) {
          compareMessages(ra->GetRepeatedMessage(a, fa, k), rb->GetRepeatedMessage(b, fb, k), item,
                          a_is_part, out);
        } else if (valueText(a, fa, k) != valueText(b, fb, k)) {
          out.push_back(item + ": " + valueText(a, fa, k) + " vs " + valueText(b, fb, k));
        }
      }
    } else {
      const bool ha = ra->HasField(a, fa);
      const bool hb = rb->HasField(b, fb);
      if (ha != hb) {
        out.push_back(here + std::string(": set on ") + (ha ? "the first" : "the second") +
                      " side only");
        continue;
      }
      if (!ha) continue;
      if (is_message) {
        compareMessages(ra->GetMessage(a, fa), rb->GetMessage(b, fb), here, a_is_part, out);
      } else if (valueText(a, fa, -1) != valueText(b, fb, -1)) {
        out.push_back(here + ": " + valueText(a, fa, -1) + " vs " + valueText(b, fb, -1));
      }
    }
  }
}

void compareEnums(const EnumDescriptor& a, const EnumDescriptor& b, std::vector<std::string>& out) {
  const std::string here = "enum " + a.name();
  if (a.name() != b.name()) out.push_back(here + ": named " + b.name() + " on the other side");
  for (int i = 0; i < a.value_count(); ++i) {
    const auto* va = a.value(i);
    const auto* vb = b.FindValueByName(va->name());
    if (!vb) {
      out.push_back(here + ": value " + va->name() + " missing in " + b.full_name());
    } else if (va->number() != vb->number()) {
      out.push_back(here + ": " + va->name() + " = " + std::to_string(va->number()) + " vs " +
                    std::to_string(vb->number()));
    }
  }
  for (int i = 0; i < b.value_count(); ++i) {
    if (!a.FindValueByName(b.value(i)->name())) {
      out.push_back(here + ": value " + b.value(i)->name() + " missing in " + a.full_name());
    }
  }
  // proto2 decodes the first value as the default of an unset field.
  if (a.value_count() > 0 && b.value_count() > 0 && a.value(0)->name() != b.value(0)->name()) {
    out.push_back(here + ": first (default) value " + a.value(0)->name() + " vs " +
                  b.value(0)->name());
  }
}

// a_is_part: `a` may leave out `b`'s optional and repeated fields, never
// a required one (packets without it would not parse).
void compareDescriptors(const Descriptor& a, const Descriptor& b, bool a_is_part,
                        std::set<std::string>& seen, std::vector<std::string>& out) {
  if (!seen.insert(a.full_name() + "|" + b.full_name()).second) return;
  const std::string path = a.name();
  if (a.name() != b.name()) out.push_back(path + ": named " + b.name() + " on the other side");
  for (int i = 0; i < b.field_count(); ++i) {
    if (a_is_part && !b.field(i)->is_required()) continue;
    if (!a.FindFieldByNumber(b.field(i)->number())) {
      out.push_back(path + ": field " + std::to_string(b.field(i)->number()) + " (" +
                    b.field(i)->name() + ") exists only in " + b.full_name());
    }
  }
  for (int i = 0; i < a.field_count(); ++i) {
    const FieldDescriptor* fa = a.field(i);
    const FieldDescriptor* fb = b.FindFieldByNumber(fa->number());
    const std::string here = path + "." + fa->name();
    if (!fb) {
      out.push_back(here + ": field " + std::to_string(fa->number()) + " exists only in " +
                    a.full_name());
      continue;
    }
    compareFieldShape(fa, fb, here, out);
    if (defaultText(fa) != defaultText(fb)) {
      out.push_back(here + ": default [" + defaultText(fa) + "] vs [" + defaultText(fb) + "]");
    }
    if (fa->message_type() && fb->message_type()) {
      compareDescriptors(*fa->message_type(), *fb->message_type(), a_is_part, seen, out);
    }
    if (fa->enum_type() && fb->enum_type()) compareEnums(*fa->enum_type(), *fb->enum_type(), out);
  }
}

}  // namespace

void fillEveryField(Message& m, int seed, int repeat) {
  Filler filler{seed * 100, repeat, {}};
  filler.fill(m);
}

std::vector<std::string> unsetFields(const Message& m) {
  std::vector<std::string> out;
  collectUnset(m, m.GetDescriptor()->name(), out);
  return out;
}

std::vector<std::string> unknownFields(const Message& m) {
  std::vector<std::string> out;
  collectUnknown(m, m.GetDescriptor()->name(), out);
  return out;
}

std::vector<std::string> messageDifferences(const Message& a, const Message& b) {
  std::vector<std::string> out;
  compareMessages(a, b, a.GetDescriptor()->name(), false, out);
  return out;
}

std::vector<std::string> partMessageDifferences(const Message& part, const Message& whole) {
  std::vector<std::string> out;
  compareMessages(part, whole, part.GetDescriptor()->name(), true, out);
  return out;
}

std::vector<std::string> descriptorDifferences(const Descriptor& a, const Descriptor& b) {
  std::vector<std::string> out;
  std::set<std::string> seen;
  compareDescriptors(a, b, false, seen, out);
  return out;
}

std::vector<std::string> partDescriptorDifferences(const Descriptor& part, const Descriptor& whole) {
  std::vector<std::string> out;
  std::set<std::string> seen;
  compareDescriptors(part, whole, true, seen, out);
  return out;
}

std::vector<std::string> enumDifferences(const EnumDescriptor& a, const EnumDescriptor& b) {
  std::vector<std::string> out;
  compareEnums(a, b, out);
  return out;
}

std::string joined(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& item : items) s += (s.empty() ? "" : "; ") + item;
  return s;
}

}  // namespace dv::conformance

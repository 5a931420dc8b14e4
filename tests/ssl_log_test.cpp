#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "temp_dir.h"
#include "io/ssl_log.h"

namespace dv {
namespace {

namespace fs = std::filesystem;

// A file name unique to this test and process, so parallel ctest runs of
// the same binary do not share files.
std::string tempPath(const std::string& name) {
  static const TempDir root("dv_ssl_log");
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = root.path() / info->name();
  fs::create_directories(dir);
  return (dir / name).string();
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

void appendBigEndian(std::string& out, uint64_t value, int bytes) {
  for (int i = bytes - 1; i >= 0; --i) out.push_back(char((value >> (8 * i)) & 0xff));
}

std::string fileHeader(int32_t version = 1) {
  std::string h = "SSL_LOG_FILE";
  appendBigEndian(h, uint32_t(version), 4);
  return h;
}

std::string recordBytes(int64_t t, int32_t type, const std::string& payload) {
  std::string r;
  appendBigEndian(r, uint64_t(t), 8);
  appendBigEndian(r, uint32_t(type), 4);
  appendBigEndian(r, uint32_t(payload.size()), 4);
  return r + payload;
}

// Expects `fn` to throw InputError whose message contains every `parts`.
template <class Fn>
void expectInputError(Fn fn, const std::vector<std::string>& parts) {
  try {
    fn();
    ADD_FAILURE() << "no InputError thrown";
  } catch (const InputError& e) {
    for (const auto& p : parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos)
        << "message \"" << e.what() << "\" lacks \"" << p << "\"";
  }
}

const std::vector<LogRecord> kSample = {
    {1'700'000'000'123'456'789, LogMessageType::Vision2014, std::string("abc")},
    {1'700'000'000'223'456'789, LogMessageType::Refbox2013, std::string("\0\x01\xff\x80ZZ", 6)},
    {1'700'000'000'323'456'789, LogMessageType::VisionTracker2020, std::string()},
    {-5, LogMessageType::Vision2010, std::string(70000, 'x')},  // larger than any buffer chunk
};

void writeSample(const std::string& path) {
  SslLogWriter w(path);
  for (const auto& r : kSample) w.write(r.timestamp_ns, r.type, r.payload);
  w.close();
}

void expectSample(const std::string& path) {
  SslLogReader reader(path);
  for (const auto& want : kSample) {
    auto got = reader.next();
    ASSERT_TRUE(got.has_value());
    EXPECT_EQ(got->timestamp_ns, want.timestamp_ns);
    EXPECT_EQ(got->type, want.type);
    EXPECT_EQ(got->payload, want.payload);
  }
  EXPECT_FALSE(reader.next().has_value());
  EXPECT_FALSE(reader.next().has_value());  // stays at the end
}

TEST(SslLog, PlainRoundTripHasExactLayout) {
  const auto path = tempPath("a.log");
  writeSample(path);
  std::string expected = fileHeader();
  for (const auto& r : kSample) expected += recordBytes(r.timestamp_ns, int32_t(r.type), r.payload);
  EXPECT_EQ(readFile(path), expected);
  expectSample(path);
}

TEST(SslLog, GzipRoundTripIsOneGzipStream) {
  const auto path = tempPath("a.log.gz");
  writeSample(path);
  const std::string raw = readFile(path);
  ASSERT_GE(raw.size(), 2u);
  EXPECT_EQ(uint8_t(raw[0]), 0x1f);  // gzip magic, header included in the stream
  EXPECT_EQ(uint8_t(raw[1]), 0x8b);
  expectSample(path);

  // Decompressed, it is exactly the plain layout.
  gzFile f = gzopen(path.c_str(), "rb");
  ASSERT_NE(f, nullptr);
  std::string plain;
  char buf[4096];
  int n;
  while ((n = gzread(f, buf, sizeof buf)) > 0) plain.append(buf, size_t(n));
  gzclose(f);
  std::string expected = fileHeader();
  for (const auto& r : kSample) expected += recordBytes(r.timestamp_ns, int32_t(r.type), r.payload);
  EXPECT_EQ(plain, expected);
}

TEST(SslLog, DecodesHandBuiltBytes) {
  const auto path = tempPath("hand.log");
  writeFile(path, fileHeader() + recordBytes(42, 4, "hello") + recordBytes(0x0102030405060708, 1, "") +
                      recordBytes(7, 99, "z"));
  SslLogReader reader(path);
  auto a = reader.next();
  ASSERT_TRUE(a);
  EXPECT_EQ(a->timestamp_ns, 42);
  EXPECT_EQ(a->type, LogMessageType::Vision2014);
  EXPECT_EQ(a->payload, "hello");
  EXPECT_EQ(reader.offset(), 16 + 16 + 5);
  auto b = reader.next();
  ASSERT_TRUE(b);
  EXPECT_EQ(b->timestamp_ns, 0x0102030405060708);
  EXPECT_EQ(b->type, LogMessageType::Unknown);
  EXPECT_TRUE(b->payload.empty());
  auto c = reader.next();  // unknown types pass through for the caller to ignore
  ASSERT_TRUE(c);
  EXPECT_EQ(int32_t(c->type), 99);
  EXPECT_FALSE(reader.next());
}

TEST(SslLog, IndexMatchesTheReferenceExample) {
  const auto path = tempPath("indexed.log");
  {
    SslLogWriter w(path);
    w.write(1, LogMessageType::Vision2014, "abc");
    w.write(2, LogMessageType::Vision2014, "defghi");
    w.write(3, LogMessageType::Refbox2013, "");
    EXPECT_EQ(w.bytesWritten(), 73);
    w.writeIndex();
    w.close();
  }
  const std::string bytes = readFile(path);
  // ssl-facts §6: records at 16, 35, 57; index at 73 with B = 55.
  ASSERT_EQ(bytes.size(), 73u + 55u);
  std::string expected_index = recordBytes(0, 6, "");
  expected_index.resize(12);
  appendBigEndian(expected_index, 8 * 3 + 15, 4);
  for (uint64_t off : {16, 35, 57}) appendBigEndian(expected_index, off, 8);
  appendBigEndian(expected_index, 55, 8);
  expected_index += "INDEXED";
  EXPECT_EQ(bytes.substr(73), expected_index);

  auto offsets = readSslLogIndex(path);
  ASSERT_TRUE(offsets);
  EXPECT_EQ(*offsets, (std::vector<int64_t>{16, 35, 57}));

  // Sequential readers skip the index record.
  SslLogReader reader(path);
  int count = 0;
  while (auto r = reader.next()) {
    EXPECT_NE(r->type, LogMessageType::Index2021);
    ++count;
  }
  EXPECT_EQ(count, 3);
}

TEST(SslLog, NoIndexAndInconsistentIndex) {
  const auto plain = tempPath("plain.log");
  writeSample(plain);
  EXPECT_FALSE(readSslLogIndex(plain).has_value());

  // A back-pointer that points before the first record.
  const auto bad = tempPath("bad_index.log");
  std::string bytes = fileHeader() + recordBytes(1, 4, "abc");
  appendBigEndian(bytes, 9999, 8);
  bytes += "INDEXED";
  writeFile(bad, bytes);
  expectInputError([&] { readSslLogIndex(bad); }, {bad, "back-pointer 9999"});
}

// Found by fuzz_ssl_log: the stored back-pointer and offsets are any 64 bits;
// the extremes are refused by name instead of overflowing the arithmetic
// (UBSan in the fuzz and sanitizer builds stops on that).
TEST(SslLog, IndexWithExtremeValuesIsRefused) {
  const auto negative = tempPath("negative_back.log");
  std::string bytes = fileHeader() + recordBytes(1, 4, "abc");
  appendBigEndian(bytes, uint64_t(INT64_MIN) + 47, 8);
  bytes += "INDEXED";
  writeFile(negative, bytes);
  expectInputError([&] { readSslLogIndex(negative); }, {negative, "back-pointer -9223372036854775761"});

  const auto far = tempPath("far_entry.log");
  bytes = fileHeader() + recordBytes(1, 4, "abc");
  std::string index = recordBytes(0, 6, "");
  index.resize(12);
  appendBigEndian(index, 8 + 15, 4);
  appendBigEndian(index, uint64_t(INT64_MAX), 8);
  appendBigEndian(index, 16 + 8 + 15, 8);
  index += "INDEXED";
  writeFile(far, bytes + index);
  expectInputError([&] { readSslLogIndex(far); }, {far, "index entry 0", "outside the records"});
}

TEST(SslLog, IndexRefusedForCompressedLog) {
  const auto path = tempPath("x.log.gz");
  SslLogWriter w(path);
  w.write(1, LogMessageType::Vision2014, "abc");
  expectInputError([&] { w.writeIndex(); }, {path, "uncompressed"});
}

TEST(SslLog, BadHeaderIsNamed) {
  const auto path = tempPath("bad.log");
  writeFile(path, std::string("NOT_A_LOGFIL") + std::string("\0\0\0\x01", 4));
  expectInputError([&] { SslLogReader r(path); }, {path, "SSL_LOG_FILE"});
}

TEST(SslLog, WrongVersionIsNamed) {
  const auto path = tempPath("v2.log");
  writeFile(path, fileHeader(2) + recordBytes(1, 4, "abc"));
  expectInputError([&] { SslLogReader r(path); }, {path, "version 2"});
}

TEST(SslLog, TruncatedHeader) {
  const auto path = tempPath("short.log");
  writeFile(path, "SSL_LOG");
  expectInputError([&] { SslLogReader r(path); }, {path, "truncated header", "7 of 16"});
  const auto empty = tempPath("empty.log");
  writeFile(empty, "");
  expectInputError([&] { SslLogReader r(empty); }, {empty, "0 of 16"});
}

TEST(SslLog, MissingFileIsNamed) {
  const auto path = tempPath("does_not_exist.log");
  expectInputError([&] { SslLogReader r(path); }, {path, "cannot open"});
}

TEST(SslLog, UnwritablePathIsNamed) {
  const auto path = tempPath("no_such_dir") + "/x.log";
  expectInputError([&] { SslLogWriter w(path); }, {path, "cannot open"});
}

// Reads records until the reader throws; returns how many came first.
int recordsBeforeError(const std::string& path, const std::vector<std::string>& parts) {
  SslLogReader reader(path);
  int count = 0;
  try {
    while (reader.next()) ++count;
    ADD_FAILURE() << "no InputError thrown";
  } catch (const InputError& e) {
    for (const auto& p : parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos)
        << "message \"" << e.what() << "\" lacks \"" << p << "\"";
  }
  return count;
}

TEST(SslLog, TruncatedRecordHeaderKeepsEarlierRecords) {
  const auto path = tempPath("cut_header.log");
  std::string full = fileHeader() + recordBytes(1, 4, "abc") + recordBytes(2, 4, "defghi");
  writeFile(path, full.substr(0, 35 + 10));
  EXPECT_EQ(recordsBeforeError(path, {path, "byte 35", "truncated record header", "10 of 16"}), 1);
}

TEST(SslLog, TruncatedPayloadKeepsEarlierRecords) {
  const auto path = tempPath("cut_payload.log");
  std::string full = fileHeader() + recordBytes(1, 4, "abc") + recordBytes(2, 4, "defghi");
  writeFile(path, full.substr(0, full.size() - 2));
  EXPECT_EQ(recordsBeforeError(path, {path, "byte 35", "truncated payload", "4 of 6"}), 1);
}

TEST(SslLog, TruncatedGzipStreamKeepsEarlierRecords) {
  const auto path = tempPath("cut.log.gz");
  {
    SslLogWriter w(path);
    // Incompressible-ish payloads so the cut lands inside the last record.
    std::string payload(4000, '\0');
    uint32_t x = 12345;
    for (int i = 0; i < 20; ++i) {
      for (auto& c : payload) c = char((x = x * 1103515245u + 12345u) >> 24);
      w.write(i, LogMessageType::Vision2014, payload);
    }
  }
  std::string raw = readFile(path);
  writeFile(path, raw.substr(0, raw.size() - 3000));
  int count = recordsBeforeError(path, {path, "byte "});
  EXPECT_GT(count, 10);
  EXPECT_LT(count, 20);
}

TEST(SslLog, CorruptGzipDataIsNamed) {
  const auto path = tempPath("crc.log.gz");
  writeSample(path);
  std::string raw = readFile(path);
  raw[raw.size() - 6] ^= 1;  // inside the CRC-32 trailer
  writeFile(path, raw);
  expectInputError(
      [&] {
        SslLogReader reader(path);
        for (int i = 0; i < 100 && reader.next(); ++i) {
        }
      },
      {path, "corrupt gzip data"});
}

TEST(SslLog, NegativeSize) {
  const auto path = tempPath("negative.log");
  std::string bytes = fileHeader() + recordBytes(1, 4, "abc") + recordBytes(2, 4, "");
  bytes[35 + 12] = char(0xff);  // size field of the second record = -16777216
  writeFile(path, bytes);
  EXPECT_EQ(recordsBeforeError(path, {path, "byte 35", "negative record size"}), 1);
}

TEST(SslLog, ErrorIsStickyRatherThanDecodingGarbage) {
  const auto path = tempPath("sticky.log");
  std::string bytes = fileHeader() + recordBytes(1, 4, "abc") + recordBytes(2, 4, "") +
                      recordBytes(3, 4, "xyz");
  bytes[35 + 12] = char(0xff);
  writeFile(path, bytes);
  SslLogReader reader(path);
  ASSERT_TRUE(reader.next());
  EXPECT_THROW(reader.next(), InputError);
  expectInputError([&] { reader.next(); }, {path, "byte 35", "negative record size"});
}

TEST(SslLog, AbsurdSize) {
  const auto path = tempPath("absurd.log");
  std::string bytes = fileHeader() + recordBytes(1, 4, "abc") + recordBytes(2, 4, "");
  bytes[35 + 12] = char(0x7f);  // about 2 GB
  writeFile(path, bytes);
  EXPECT_EQ(recordsBeforeError(path, {path, "byte 35", "implausible"}), 1);
}

// Records are single datagrams: a size above the 1 MiB limit is refused with
// the file and the record's offset, before a buffer of that size exists.
TEST(SslLog, SizeAboveTheLimitIsNamed) {
  const auto path = tempPath("over_limit.log");
  std::string bytes = fileHeader() + recordBytes(1, 4, "abc") + recordBytes(2, 4, "");
  const uint32_t claimed = uint32_t(kSslLogMaxPayloadBytes) + 1;
  for (int i = 0; i < 4; ++i) bytes[35 + 12 + i] = char(claimed >> (24 - 8 * i));
  bytes += std::string(100, 'p');
  writeFile(path, bytes);
  EXPECT_EQ(recordsBeforeError(path, {path, "byte 35", "record size 1048577", "implausible",
                                      "limit 1048576"}),
            1);
  SslLogWriter w(tempPath("over_limit_write.log"));
  EXPECT_THROW(w.write(1, LogMessageType::Vision2014, std::string(size_t(claimed), 'x')), InputError);
}

// A size within the limit on a short file is a truncated payload, counted
// in the bytes that are there.
TEST(SslLog, LargeClaimOnShortFileIsTruncation) {
  const auto path = tempPath("large_claim.log");
  std::string bytes = fileHeader() + recordBytes(1, 4, "abc") + recordBytes(2, 4, "");
  const uint32_t claimed = uint32_t(kSslLogMaxPayloadBytes);
  for (int i = 0; i < 4; ++i) bytes[35 + 12 + i] = char(claimed >> (24 - 8 * i));
  bytes += std::string(70000, 'p');
  writeFile(path, bytes);
  EXPECT_EQ(recordsBeforeError(path, {path, "byte 35", "truncated payload", "70000 of 1048576"}), 1);
}

}  // namespace
}  // namespace dv

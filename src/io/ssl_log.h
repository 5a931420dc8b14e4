#pragma once
// The league's log file format (ssl-log-recorder / ssl-logtools): a 16-byte
// header "SSL_LOG_FILE" + int32 version 1, then records of int64 timestamp
// (ns), int32 type, int32 size and the raw UDP payload, all big-endian.
// A file whose name ends in "gz" is one gzip stream around all of it.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace dv {

enum class LogMessageType : int32_t {
  Blank = 0,
  Unknown = 1,
  Vision2010 = 2,
  Refbox2013 = 3,
  Vision2014 = 4,
  VisionTracker2020 = 5,
  Index2021 = 6
};

struct LogRecord {
  int64_t timestamp_ns = 0;
  LogMessageType type = LogMessageType::Blank;
  std::string payload;
};

// Sizes that describe the format, shared by the writer, reader and tests.
inline constexpr int kSslLogHeaderBytes = 16;
inline constexpr int kSslLogRecordHeaderBytes = 16;
// Larger payloads are treated as corruption: every record the league logs is
// one UDP datagram (below 64 KiB), so a record claiming more than 1 MiB is a
// damaged size field, refused before anything is allocated for it.
inline constexpr int32_t kSslLogMaxPayloadBytes = 1024 * 1024;
// The index record lists 8 bytes per record; readers skip it unread.
inline constexpr int32_t kSslLogMaxIndexBytes = 64 * 1024 * 1024;

// True when `head`, a file's first bytes, is the SSL log header or close to
// it (at least 8 of the 12 magic bytes in place): a damaged header is then
// reported as one rather than taken for another format.
bool looksLikeSslLogHeader(const std::string& head);

// True when the log at `path` is (or will be) one gzip stream: the name
// ends in "gz", the rule the league's tools use.
bool isCompressedLogPath(const std::string& path);

class SslLogWriter {
 public:
  // Creates (truncates) the file and writes the header. Throws InputError
  // naming the path if it cannot be opened.
  explicit SslLogWriter(const std::string& path);
  SslLogWriter(const SslLogWriter&) = delete;
  SslLogWriter& operator=(const SslLogWriter&) = delete;
  ~SslLogWriter();  // closes; never throws

  // Appends one record. Throws InputError on a write failure or a payload
  // larger than kSslLogMaxPayloadBytes.
  void write(int64_t timestamp_ns, LogMessageType type, const std::string& payload);
  // Appends the ssl-log-indexer index record listing every record written so
  // far. Only for uncompressed files (one cannot seek in a gzip stream);
  // throws InputError for a compressed one.
  void writeIndex();
  // Flushes and closes; later writes throw. Throws InputError if the final
  // flush fails. Safe to call twice.
  void close();

  // Bytes of the uncompressed stream written so far (header included).
  int64_t bytesWritten() const { return offset_; }

 private:
  void writeBytes(const void* data, size_t n);

  std::string path_;
  void* file_ = nullptr;  // gzFile; void* keeps zlib.h out of this header
  bool compressed_ = false;
  int64_t offset_ = 0;
  std::vector<int64_t> record_offsets_;
};

class SslLogReader {
 public:
  // Opens the file (plain or gzip, detected from the content) and checks
  // the header. Throws InputError(path, ...) if it cannot be opened, is
  // shorter than the header, lacks "SSL_LOG_FILE" or has a version other
  // than 1.
  explicit SslLogReader(const std::string& path);
  SslLogReader(const SslLogReader&) = delete;
  SslLogReader& operator=(const SslLogReader&) = delete;
  ~SslLogReader();

  // The next record, or nullopt at a clean end of file. Index records are
  // recognised and skipped. Throws InputError naming the file, the byte
  // offset of the damaged record and what is wrong (truncated record header
  // or payload, negative or absurd size, corrupt gzip data); after that,
  // every further call throws the same error.
  std::optional<LogRecord> next();
  // The same, reusing `out`'s payload buffer; false at a clean end.
  bool next(LogRecord& out);

  // Offset (in the uncompressed stream) of the next record to be read.
  int64_t offset() const { return offset_; }
  const std::string& path() const { return path_; }

 private:
  // Reads up to n bytes; stream_offset only labels errors.
  size_t readBytes(void* data, size_t n, int64_t stream_offset);
  void skipBytes(int64_t n, int64_t record_offset);
  bool readRecord(LogRecord& out);

  std::string path_;
  void* file_ = nullptr;  // gzFile
  int64_t offset_ = 0;
  std::string failure_;  // set once a record could not be read
};

// Record offsets stored in the index at the end of an uncompressed log, or
// nullopt if the file carries no index (its last 7 bytes are not
// "INDEXED"). Throws InputError if the file cannot be read or the index
// is inconsistent with the file size.
std::optional<std::vector<int64_t>> readSslLogIndex(const std::string& path);

}  // namespace dv

#include "io/ssl_log.h"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "core/error.h"

namespace dv {
namespace {

constexpr char kMagic[] = "SSL_LOG_FILE";  // 12 bytes, no terminator on disk
constexpr int32_t kVersion = 1;
constexpr char kIndexMarker[] = "INDEXED";  // 7 bytes, no terminator on disk
constexpr int kIndexMarkerBytes = 7;
// Bytes after the offsets: int64 back-pointer + marker.
constexpr int kIndexTailBytes = 8 + kIndexMarkerBytes;

gzFile asGz(void* f) { return static_cast<gzFile>(f); }

void putBigEndian(uint8_t* out, uint64_t value, int bytes) {
  for (int i = bytes - 1; i >= 0; --i) {
    out[i] = uint8_t(value & 0xff);
    value >>= 8;
  }
}

uint64_t getBigEndian(const uint8_t* in, int bytes) {
  uint64_t value = 0;
  for (int i = 0; i < bytes; ++i) value = (value << 8) | in[i];
  return value;
}

// Bytes as text for a message, non-printable ones as \xNN.
std::string printable(const std::string& bytes) {
  std::string out;
  for (unsigned char c : bytes) {
    if (c >= 0x20 && c < 0x7f && c != '"' && c != '\\') {
      out += char(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    }
  }
  return out;
}

std::string at(int64_t offset) { return "byte " + std::to_string(offset) + ": "; }

}  // namespace

bool looksLikeSslLogHeader(const std::string& head) {
  if (head.size() < 12) return false;
  int same = 0;
  for (int i = 0; i < 12; ++i) same += head[size_t(i)] == kMagic[i];
  return same >= 8;
}

bool isCompressedLogPath(const std::string& path) {
  return path.size() >= 2 && path.compare(path.size() - 2, 2, "gz") == 0;
}

// ---------------------------------------------------------------- writer

SslLogWriter::SslLogWriter(const std::string& path)
    : path_(path), compressed_(isCompressedLogPath(path)) {
  // "T" asks zlib for transparent (uncompressed) output, so both kinds of
  // file go through the same gz* calls.
  file_ = gzopen(path.c_str(), compressed_ ? "wb6" : "wbT");
  if (!file_) {
    throw InputError(path, std::string("cannot open for writing: ") +
                               (errno ? std::strerror(errno) : "out of memory"));
  }
  gzbuffer(asGz(file_), 1 << 17);
  uint8_t header[kSslLogHeaderBytes];
  std::memcpy(header, kMagic, 12);
  putBigEndian(header + 12, uint32_t(kVersion), 4);
  writeBytes(header, sizeof header);
}

SslLogWriter::~SslLogWriter() {
  try {
    close();
  } catch (...) {
    // A destructor cannot report; callers who care call close() themselves.
  }
}

void SslLogWriter::writeBytes(const void* data, size_t n) {
  if (!file_) throw InputError(path_, "write after close");
  if (n == 0) return;
  int written = gzwrite(asGz(file_), data, unsigned(n));
  if (written != int(n)) {
    int errnum = 0;
    const char* msg = gzerror(asGz(file_), &errnum);
    throw InputError(path_, at(offset_) + "write failed: " +
                                (errnum == Z_ERRNO ? std::strerror(errno) : msg));
  }
  offset_ += int64_t(n);
}

void SslLogWriter::write(int64_t timestamp_ns, LogMessageType type,
                         const std::string& payload) {
  if (payload.size() > size_t(kSslLogMaxPayloadBytes)) {
    throw InputError(path_, at(offset_) + "payload of " + std::to_string(payload.size()) +
                                " bytes exceeds the " +
                                std::to_string(kSslLogMaxPayloadBytes) + "-byte record limit");
  }
  uint8_t header[kSslLogRecordHeaderBytes];
  putBigEndian(header, uint64_t(timestamp_ns), 8);
  putBigEndian(header + 8, uint32_t(int32_t(type)), 4);
  putBigEndian(header + 12, uint32_t(payload.size()), 4);
  int64_t record_offset = offset_;
  writeBytes(header, sizeof header);
  writeBytes(payload.data(), payload.size());
  record_offsets_.push_back(record_offset);
}

void SslLogWriter::writeIndex() {
  if (compressed_) {
    throw InputError(path_, "an index needs an uncompressed log (the name ends in gz)");
  }
  const int64_t n = int64_t(record_offsets_.size());
  const int64_t payload_bytes = 8 * n + kIndexTailBytes;
  if (payload_bytes > kSslLogMaxIndexBytes) {
    throw InputError(path_, "too many records (" + std::to_string(n) + ") for one index");
  }
  std::string payload(size_t(payload_bytes), '\0');
  auto* p = reinterpret_cast<uint8_t*>(payload.data());
  for (int64_t i = 0; i < n; ++i) putBigEndian(p + 8 * i, uint64_t(record_offsets_[i]), 8);
  putBigEndian(p + 8 * n, uint64_t(kSslLogRecordHeaderBytes + payload_bytes), 8);
  std::memcpy(p + 8 * n + 8, kIndexMarker, kIndexMarkerBytes);
  // write() would list the index among the records; keep the list as it was.
  auto offsets = record_offsets_;
  write(0, LogMessageType::Index2021, payload);
  record_offsets_ = std::move(offsets);
}

void SslLogWriter::close() {
  if (!file_) return;
  gzFile f = asGz(file_);
  file_ = nullptr;
  errno = 0;
  int rc = gzclose(f);
  if (rc == Z_ERRNO && errno != 0) {  // the final flush: a full disk, an I/O error
    throw InputError(path_, at(offset_) + "write failed at close: " + std::strerror(errno));
  }
  if (rc != Z_OK) {
    throw InputError(path_, "closing failed (zlib error " + std::to_string(rc) + ")");
  }
}

// ---------------------------------------------------------------- reader

SslLogReader::SslLogReader(const std::string& path) : path_(path) {
  errno = 0;
  file_ = gzopen(path.c_str(), "rb");
  if (!file_) {
    throw InputError(path, std::string("cannot open: ") +
                               (errno ? std::strerror(errno) : "out of memory"));
  }
  gzbuffer(asGz(file_), 1 << 17);
  uint8_t header[kSslLogHeaderBytes];
  size_t got = 0;
  try {
    got = readBytes(header, sizeof header, 0);
  } catch (...) {
    gzclose(asGz(file_));
    file_ = nullptr;
    throw;
  }
  std::string problem;
  if (got < sizeof header) {
    problem = "truncated header: " + std::to_string(got) + " of " +
              std::to_string(kSslLogHeaderBytes) + " bytes";
  } else if (std::memcmp(header, kMagic, 12) != 0) {
    const std::string head(reinterpret_cast<const char*>(header), 12);
    problem = looksLikeSslLogHeader(head) ? "damaged SSL log header: the file starts with \"" +
                                                printable(head) + "\", not \"SSL_LOG_FILE\""
                                          : "not an SSL log file (does not start with \"SSL_LOG_FILE\")";
  } else if (int32_t version = int32_t(getBigEndian(header + 12, 4)); version != kVersion) {
    problem = "byte 12: unsupported log version " + std::to_string(version) +
              " (only version 1 exists)";
  }
  if (!problem.empty()) {
    gzclose(asGz(file_));
    file_ = nullptr;
    throw InputError(path, problem);
  }
  offset_ = kSslLogHeaderBytes;
}

SslLogReader::~SslLogReader() {
  if (file_) gzclose(asGz(file_));
}

size_t SslLogReader::readBytes(void* data, size_t n, int64_t stream_offset) {
  size_t total = 0;
  auto* out = static_cast<uint8_t*>(data);
  while (total < n) {
    unsigned chunk = unsigned(std::min<size_t>(n - total, 1u << 30));
    int got = gzread(asGz(file_), out + total, chunk);
    if (got > 0) {
      total += size_t(got);
      continue;
    }
    int errnum = Z_OK;
    const char* msg = gzerror(asGz(file_), &errnum);
    if (got < 0 || (errnum != Z_OK && errnum != Z_STREAM_END)) {
      // A cut-off gzip stream shows up here as Z_BUF_ERROR. zlib inflates
      // ahead in large blocks, so for damaged data the offset only says how
      // far the caller had read when the damage was found.
      const std::string where = at(stream_offset + int64_t(total));
      if (errnum == Z_ERRNO) throw InputError(path_, where + std::strerror(errno));
      if (errnum == Z_BUF_ERROR) {
        throw InputError(path_, where + "gzip stream ends early (file truncated)");
      }
      std::string detail = msg ? msg : "unknown zlib error";
      // gzerror prefixes the path; the InputError already names it.
      if (detail.rfind(path_ + ": ", 0) == 0) detail.erase(0, path_.size() + 2);
      throw InputError(path_, where + "corrupt gzip data (" + detail + ")");
    }
    break;  // clean end of data
  }
  return total;
}

void SslLogReader::skipBytes(int64_t n, int64_t record_offset) {
  char scratch[4096];
  int64_t position = record_offset + kSslLogRecordHeaderBytes;
  while (n > 0) {
    size_t want = size_t(std::min<int64_t>(n, sizeof scratch));
    size_t got = readBytes(scratch, want, position);
    position += int64_t(got);
    n -= int64_t(got);
    if (got < want) {
      throw InputError(path_, at(record_offset) + "index record truncated");
    }
  }
}

bool SslLogReader::next(LogRecord& out) {
  if (!failure_.empty()) throw InputError(path_, failure_);
  if (!file_) return false;
  try {
    return readRecord(out);
  } catch (const InputError& e) {
    // The stream position is lost; later calls repeat the same error
    // instead of decoding garbage.
    failure_ = std::string(e.what()).substr(path_.size() + 2);
    throw;
  }
}

bool SslLogReader::readRecord(LogRecord& out) {
  for (;;) {
    const int64_t record_offset = offset_;
    uint8_t header[kSslLogRecordHeaderBytes];
    size_t got = readBytes(header, sizeof header, record_offset);
    if (got == 0) return false;
    if (got < sizeof header) {
      throw InputError(path_, at(record_offset) + "truncated record header: " +
                                  std::to_string(got) + " of " +
                                  std::to_string(kSslLogRecordHeaderBytes) + " bytes");
    }
    const int64_t timestamp = int64_t(getBigEndian(header, 8));
    const int32_t type = int32_t(getBigEndian(header + 8, 4));
    const int32_t size = int32_t(getBigEndian(header + 12, 4));
    if (size < 0) {
      throw InputError(path_, at(record_offset) + "negative record size " + std::to_string(size));
    }
    if (type == int32_t(LogMessageType::Index2021)) {
      // The index only helps seeking; readers going front to back skip it.
      skipBytes(size, record_offset);
      offset_ = record_offset + kSslLogRecordHeaderBytes + size;
      continue;
    }
    if (size > kSslLogMaxPayloadBytes) {
      throw InputError(path_, at(record_offset) + "record size " + std::to_string(size) +
                                  " bytes is implausible (limit " +
                                  std::to_string(kSslLogMaxPayloadBytes) + ")");
    }
    out.timestamp_ns = timestamp;
    out.type = LogMessageType(type);
    // The buffer grows with the bytes actually there, so a size field that
    // promises more than the file holds costs no more than the file.
    constexpr size_t kStep = 64 * 1024;
    size_t payload_got = 0;
    out.payload.clear();
    while (payload_got < size_t(size)) {
      const size_t want = std::min(size_t(size) - payload_got, kStep);
      out.payload.resize(payload_got + want);
      const size_t got = readBytes(out.payload.data() + payload_got, want,
                                   record_offset + kSslLogRecordHeaderBytes + int64_t(payload_got));
      payload_got += got;
      if (got < want) break;
    }
    if (payload_got < size_t(size)) {
      throw InputError(path_, at(record_offset) + "truncated payload: " +
                                  std::to_string(payload_got) + " of " + std::to_string(size) +
                                  " bytes");
    }
    offset_ = record_offset + kSslLogRecordHeaderBytes + size;
    return true;
  }
}

std::optional<LogRecord> SslLogReader::next() {
  LogRecord record;
  if (!next(record)) return std::nullopt;
  return record;
}

// ---------------------------------------------------------------- index

std::optional<std::vector<int64_t>> readSslLogIndex(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  struct Closer {
    std::FILE* f;
    ~Closer() { std::fclose(f); }
  } closer{f};
  auto readAt = [&](int64_t pos, void* data, size_t n) {
    return fseeko(f, off_t(pos), SEEK_SET) == 0 && std::fread(data, 1, n, f) == n;
  };
  if (fseeko(f, 0, SEEK_END) != 0) throw InputError(path, "cannot seek");
  const int64_t file_size = int64_t(ftello(f));
  const int64_t smallest = kSslLogHeaderBytes + kSslLogRecordHeaderBytes + kIndexTailBytes;
  if (file_size < smallest) return std::nullopt;

  uint8_t tail[kIndexTailBytes];
  if (!readAt(file_size - kIndexTailBytes, tail, sizeof tail)) {
    throw InputError(path, "cannot read the last bytes");
  }
  if (std::memcmp(tail + 8, kIndexMarker, kIndexMarkerBytes) != 0) return std::nullopt;

  // Range-checked before any arithmetic: the stored value is any 64 bits.
  const int64_t back = int64_t(getBigEndian(tail, 8));
  const bool back_fits =
      back >= kSslLogRecordHeaderBytes + kIndexTailBytes && back <= file_size - kSslLogHeaderBytes;
  const int64_t index_start = back_fits ? file_size - back : 0;
  const int64_t first_offset = index_start + kSslLogRecordHeaderBytes;
  const int64_t offsets_bytes = file_size - kIndexTailBytes - first_offset;
  if (!back_fits || offsets_bytes % 8 != 0) {
    throw InputError(path, at(file_size - kIndexTailBytes) + "index back-pointer " +
                               std::to_string(back) + " does not fit a file of " +
                               std::to_string(file_size) + " bytes");
  }
  uint8_t header[kSslLogRecordHeaderBytes];
  if (!readAt(index_start, header, sizeof header)) {
    throw InputError(path, at(index_start) + "cannot read the index record header");
  }
  const int32_t type = int32_t(getBigEndian(header + 8, 4));
  const int32_t size = int32_t(getBigEndian(header + 12, 4));
  if (type != int32_t(LogMessageType::Index2021) ||
      int64_t(size) != back - kSslLogRecordHeaderBytes) {
    throw InputError(path, at(index_start) + "index record header (type " +
                               std::to_string(type) + ", size " + std::to_string(size) +
                               ") does not match its back-pointer " + std::to_string(back));
  }
  std::vector<uint8_t> raw(static_cast<size_t>(offsets_bytes));
  if (!raw.empty() && !readAt(first_offset, raw.data(), raw.size())) {
    throw InputError(path, at(first_offset) + "cannot read the index offsets");
  }
  std::vector<int64_t> offsets(raw.size() / 8);
  int64_t previous = kSslLogHeaderBytes - 1;
  for (size_t i = 0; i < offsets.size(); ++i) {
    offsets[i] = int64_t(getBigEndian(raw.data() + 8 * i, 8));
    if (offsets[i] <= previous || offsets[i] > index_start - kSslLogRecordHeaderBytes) {
      throw InputError(path, at(first_offset + int64_t(8 * i)) + "index entry " +
                                 std::to_string(i) + " points to byte " +
                                 std::to_string(offsets[i]) + ", outside the records");
    }
    previous = offsets[i];
  }
  return offsets;
}

}  // namespace dv

#include "colag/sim/mcap/mcap_writer.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>

namespace colag::mcap {

namespace {

constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', 0x30, '\r', '\n'};
enum Op : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

// Little-endian fields, as the spec lays them out.
class Bytes {
 public:
  std::vector<std::uint8_t> out;
  template <class T>
  Bytes& num(T v) {
    for (std::size_t i = 0; i < sizeof(T); ++i)
      out.push_back(static_cast<std::uint8_t>(static_cast<std::uint64_t>(v) >> (8 * i)));
    return *this;
  }
  Bytes& raw(std::span<const std::uint8_t> b) {
    out.insert(out.end(), b.begin(), b.end());
    return *this;
  }
  Bytes& str(std::string_view s) {  // uint32 length, then the bytes
    num(static_cast<std::uint32_t>(s.size()));
    out.insert(out.end(), s.begin(), s.end());
    return *this;
  }
  Bytes& map(const std::map<std::string, std::string>& m) {  // uint32 byte length, then pairs
    Bytes body;
    for (const auto& [k, v] : m)
      body.str(k).str(v);
    num(static_cast<std::uint32_t>(body.out.size()));
    return raw(body.out);
  }
};

// opcode, uint64 length, body.
std::vector<std::uint8_t> record(std::uint8_t op, const std::vector<std::uint8_t>& body) {
  Bytes r;
  r.num(op).num(static_cast<std::uint64_t>(body.size())).raw(body);
  return std::move(r.out);
}

std::uint32_t crc_of(std::uint32_t crc, std::span<const std::uint8_t> b) {
  return static_cast<std::uint32_t>(::crc32(crc, b.data(), static_cast<uInt>(b.size())));
}

}  // namespace

Status McapWriter::fail(const char* what) {
  error_ = std::string(what) + " " + path_ + ": " + std::strerror(errno);
  failed_ = true;
  return {Errc::kIoError, "MCAP file not written"};
}

Status McapWriter::open(const std::string& path, const WriterOptions& options) {
  if (file_ != nullptr) return {Errc::kInvalidArgument, "MCAP writer already open"};
  // A writer is reusable: nothing of an earlier file (or a failed open) carries over.
  path_ = path;
  options_ = options;
  error_.clear();
  failed_ = false;
  offset_ = 0;
  crc_ = 0;
  schemas_.clear();
  channels_.clear();
  chunks_.clear();
  chunk_.clear();
  chunk_index_.clear();
  message_count_ = start_time_ = end_time_ = 0;
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) return fail("cannot create");
  put({std::begin(kMagic), std::end(kMagic)});
  Bytes h;
  h.str(options_.profile).str(options_.library);
  put(record(kHeader, h.out));
  return failed_ ? Status{Errc::kIoError, "MCAP file not written"} : Status::ok();
}

void McapWriter::put(const std::vector<std::uint8_t>& bytes) {
  if (file_ == nullptr || failed_) return;
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) {
    (void)fail("cannot write");
    return;
  }
  crc_ = crc_of(crc_, bytes);
  offset_ += bytes.size();
}

std::vector<std::uint8_t> McapWriter::schema_record(const Schema& s) {
  Bytes b;
  b.num(s.id).str(s.name).str(s.encoding).str(s.data);  // data: uint32-prefixed bytes
  return record(kSchema, b.out);
}

std::vector<std::uint8_t> McapWriter::channel_record(const Channel& c) {
  Bytes b;
  b.num(c.id).num(c.schema_id).str(c.topic).str(c.encoding).map(c.metadata);
  return record(kChannel, b.out);
}

std::uint16_t McapWriter::add_schema(std::string_view name, std::string_view encoding,
                                     std::string_view data) {
  if (file_ == nullptr || schemas_.size() == std::numeric_limits<std::uint16_t>::max()) return 0;
  schemas_.push_back({static_cast<std::uint16_t>(schemas_.size() + 1), std::string(name),
                      std::string(encoding), std::string(data)});
  put(schema_record(schemas_.back()));  // in the data section before any message uses it
  return schemas_.back().id;
}

std::uint16_t McapWriter::add_channel(std::uint16_t schema_id, std::string_view topic,
                                      std::string_view message_encoding,
                                      const std::map<std::string, std::string>& metadata) {
  if (file_ == nullptr || schema_id > schemas_.size() ||
      channels_.size() == std::numeric_limits<std::uint16_t>::max())
    return 0;
  Channel c;
  c.id = static_cast<std::uint16_t>(channels_.size() + 1);
  c.schema_id = schema_id;
  c.topic = topic;
  c.encoding = message_encoding;
  c.metadata = metadata;
  channels_.push_back(std::move(c));
  put(channel_record(channels_.back()));
  return channels_.back().id;
}

Status McapWriter::write(std::uint16_t channel_id, std::uint64_t log_time_ns,
                         std::uint64_t publish_time_ns, std::span<const std::uint8_t> data) {
  if (file_ == nullptr) return {Errc::kNotReady, "MCAP writer not open"};
  if (channel_id == 0 || channel_id > channels_.size())
    return {Errc::kInvalidArgument, "MCAP: unknown channel"};
  Channel& c = channels_[channel_id - 1];
  Bytes m;
  m.num(c.id).num(c.sequence++).num(log_time_ns).num(publish_time_ns).raw(data);
  if (chunk_.empty() && chunk_index_.empty()) chunk_start_ = chunk_end_ = log_time_ns;
  chunk_start_ = std::min(chunk_start_, log_time_ns);
  chunk_end_ = std::max(chunk_end_, log_time_ns);
  chunk_index_[c.id].emplace_back(log_time_ns, chunk_.size());
  const std::vector<std::uint8_t> r = record(kMessage, m.out);
  chunk_.insert(chunk_.end(), r.begin(), r.end());
  if (message_count_ == 0) start_time_ = end_time_ = log_time_ns;
  start_time_ = std::min(start_time_, log_time_ns);
  end_time_ = std::max(end_time_, log_time_ns);
  ++message_count_;
  ++c.messages;
  if (chunk_.size() >= options_.chunk_bytes) return flush_chunk();
  return failed_ ? Status{Errc::kIoError, "MCAP file not written"} : Status::ok();
}

// The chunk, then one message index per channel that has messages in it.
Status McapWriter::flush_chunk() {
  if (chunk_.empty()) return Status::ok();
  ChunkIndex ci{};
  ci.start_time = chunk_start_;
  ci.end_time = chunk_end_;
  ci.offset = offset_;
  ci.size = chunk_.size();
  Bytes b;
  b.num(chunk_start_).num(chunk_end_).num(static_cast<std::uint64_t>(chunk_.size()));
  b.num(crc_of(0, chunk_)).str("");  // no compression
  b.num(static_cast<std::uint64_t>(chunk_.size())).raw(chunk_);
  const std::vector<std::uint8_t> r = record(kChunk, b.out);
  ci.length = r.size();
  put(r);
  const std::uint64_t index_start = offset_;
  for (const auto& [channel, entries] : chunk_index_) {
    Bytes idx;
    idx.num(channel).num(static_cast<std::uint32_t>(entries.size() * 16));
    for (const auto& [time, at] : entries)
      idx.num(time).num(at);
    ci.index_offsets[channel] = offset_;
    put(record(kMessageIndex, idx.out));
  }
  ci.index_length = offset_ - index_start;
  chunks_.push_back(std::move(ci));
  chunk_.clear();
  chunk_index_.clear();
  return failed_ ? Status{Errc::kIoError, "MCAP file not written"} : Status::ok();
}

Status McapWriter::close() {
  if (file_ == nullptr) return Status::ok();
  (void)flush_chunk();
  Bytes end;
  end.num(crc_);
  put(record(kDataEnd, end.out));

  // The summary: every schema, every channel, the statistics, the chunk indexes; then where
  // each of those groups starts.
  const std::uint64_t summary_start = offset_;
  crc_ = 0;  // the summary CRC starts here
  struct Group {
    std::uint8_t op;
    std::uint64_t start = 0, length = 0;
  };
  std::vector<Group> groups;
  auto group = [&](std::uint8_t op, auto&& write_all) {
    Group g{op, offset_};
    write_all();
    g.length = offset_ - g.start;
    if (g.length > 0) groups.push_back(g);
  };
  group(kSchema, [&] {
    for (const Schema& s : schemas_)
      put(schema_record(s));
  });
  group(kChannel, [&] {
    for (const Channel& c : channels_)
      put(channel_record(c));
  });
  group(kStatistics, [&] {
    Bytes st;
    st.num(message_count_)
        .num(static_cast<std::uint16_t>(schemas_.size()))
        .num(static_cast<std::uint32_t>(channels_.size()))
        .num(std::uint32_t{0})  // attachments
        .num(std::uint32_t{0})  // metadata
        .num(static_cast<std::uint32_t>(chunks_.size()))
        .num(start_time_)
        .num(end_time_);
    Bytes counts;
    for (const Channel& c : channels_)
      counts.num(c.id).num(c.messages);
    st.num(static_cast<std::uint32_t>(counts.out.size())).raw(counts.out);
    put(record(kStatistics, st.out));
  });
  group(kChunkIndex, [&] {
    for (const ChunkIndex& ci : chunks_) {
      Bytes b;
      b.num(ci.start_time).num(ci.end_time).num(ci.offset).num(ci.length);
      Bytes offsets;
      for (const auto& [channel, at] : ci.index_offsets)
        offsets.num(channel).num(at);
      b.num(static_cast<std::uint32_t>(offsets.out.size())).raw(offsets.out);
      b.num(ci.index_length).str("").num(ci.size).num(ci.size);
      put(record(kChunkIndex, b.out));
    }
  });
  const std::uint64_t summary_offset_start = offset_;
  for (const Group& g : groups) {
    Bytes so;
    so.num(g.op).num(g.start).num(g.length);
    put(record(kSummaryOffset, so.out));
  }
  // The footer: its CRC covers the summary up to and including summary_offset_start.
  Bytes footer;
  footer.num(kFooter).num(std::uint64_t{8 + 8 + 4});
  footer.num(summary_start).num(summary_offset_start);
  const std::uint32_t summary_crc = crc_of(crc_, footer.out);
  footer.num(summary_crc);
  put(footer.out);
  put({std::begin(kMagic), std::end(kMagic)});

  const bool ok = !failed_;
  if (std::fclose(file_) != 0 && ok) (void)fail("cannot close");
  file_ = nullptr;
  return failed_ ? Status{Errc::kIoError, "MCAP file not written"} : Status::ok();
}

}  // namespace colag::mcap

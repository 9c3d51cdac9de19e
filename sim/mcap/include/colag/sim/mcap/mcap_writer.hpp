#pragma once
// An MCAP file writer (https://mcap.dev/spec, major version 0): schemas, channels and messages,
// messages in chunks (uncompressed) each followed by its message indexes, then a summary
// (schemas, channels, statistics, chunk indexes) with its offsets, so that viewers (Foxglove,
// Lichtblick, `ros2 bag`) seek without reading the whole file. CRCs: each chunk's, the data
// section's and the summary's. Written by hand: Debian packages no MCAP library; it is checked
// against the reference reader (@mcap/core) by the `mcap` tests.
#include <cstdint>
#include <cstdio>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "colag/common/status.hpp"

namespace colag::mcap {

struct WriterOptions {
  std::string profile = "ros2";  // the header's profile: `ros2` = cdr messages, ros2msg schemas
  std::string library = "colag-fw";
  std::size_t chunk_bytes = 1 << 20;  // a chunk is closed when its records reach this size
};

class McapWriter {
 public:
  McapWriter() = default;
  ~McapWriter() { (void)close(); }
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  // Creates (or replaces) `path` and writes the magic and the header.
  Status open(const std::string& path, const WriterOptions& options = {});
  // Ids start at 1; 0 when the file is not open.
  std::uint16_t add_schema(std::string_view name, std::string_view encoding, std::string_view data);
  std::uint16_t add_channel(std::uint16_t schema_id, std::string_view topic,
                            std::string_view message_encoding,
                            const std::map<std::string, std::string>& metadata = {});
  // One message; times in ns (log time: when it was recorded, publish time: its stamp).
  Status write(std::uint16_t channel_id, std::uint64_t log_time_ns, std::uint64_t publish_time_ns,
               std::span<const std::uint8_t> data);
  // Closes the last chunk, writes the summary and the footer. Idempotent.
  Status close();

  bool is_open() const { return file_ != nullptr; }
  // What failed last, with the path and the system's reason.
  const std::string& error() const { return error_; }
  std::uint64_t messages() const { return message_count_; }
  std::uint64_t bytes() const { return offset_; }

 private:
  struct Schema {
    std::uint16_t id;
    std::string name, encoding, data;
  };
  struct Channel {
    std::uint16_t id, schema_id;
    std::string topic, encoding;
    std::map<std::string, std::string> metadata;
    std::uint32_t sequence = 0;
    std::uint64_t messages = 0;
  };
  struct ChunkIndex {
    std::uint64_t start_time, end_time, offset, length;
    std::map<std::uint16_t, std::uint64_t> index_offsets;
    std::uint64_t index_length, size;
  };

  void put(const std::vector<std::uint8_t>& bytes);  // to the file, counted and CRC'd
  Status flush_chunk();
  static std::vector<std::uint8_t> schema_record(const Schema& s);
  static std::vector<std::uint8_t> channel_record(const Channel& c);

  Status fail(const char* what);

  std::FILE* file_ = nullptr;
  std::string path_, error_;
  WriterOptions options_;
  std::uint64_t offset_ = 0;
  std::uint32_t crc_ = 0;  // of everything written so far (the data section, then the summary)
  bool failed_ = false;
  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  std::vector<ChunkIndex> chunks_;
  // The open chunk: its records, and per channel (time, offset in `chunk_`) of each message.
  std::vector<std::uint8_t> chunk_;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;
  std::uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::uint64_t message_count_ = 0, start_time_ = 0, end_time_ = 0;
};

}  // namespace colag::mcap

#include "logs/ros1_bag_reader.hpp"

#include <algorithm>
#include <map>
#include <utility>

#include "core/errors.hpp"
#include "logs/internal/ros1_bag_file.hpp"

namespace retrace::logs {
namespace {

using internal::Ros1ChunkInfo;
using internal::Ros1MessageEntry;

// A chunk whose messages are due: its records and its messages in time order.
struct OpenChunk {
  std::uint64_t pos = 0;
  std::vector<std::uint8_t> data;
  std::vector<Ros1MessageEntry> messages;
  std::size_t next = 0;
  bool done() const { return next == messages.size(); }
  std::int64_t head_ns() const { return messages[next].time_ns; }
};

// Earlier time first, then the chunk stored first.
bool EarlierHead(const OpenChunk& a, const OpenChunk& b) {
  return a.head_ns() != b.head_ns() ? a.head_ns() < b.head_ns() : a.pos < b.pos;
}

}  // namespace

struct Ros1BagReader::State {
  explicit State(const std::filesystem::path& path) : file(path), layout(file.ReadLayout()) {
    // Chunks open in the order of their first message (storage order for equal times).
    std::stable_sort(
        layout.chunks.begin(), layout.chunks.end(),
        [](const Ros1ChunkInfo& a, const Ros1ChunkInfo& b) { return a.start_ns < b.start_ns; });
  }

  internal::Ros1BagFile file;
  internal::Ros1BagLayout layout;
  std::size_t next_chunk = 0;
  std::vector<std::unique_ptr<OpenChunk>> open;  // few: the chunks overlapping in time
  std::size_t held_bytes = 0;                    // their records

  // Reads the next chunk (by first message) and keeps it unless it holds no message.
  void OpenNextChunk() {
    const Ros1ChunkInfo& info = layout.chunks[next_chunk++];
    auto chunk = std::make_unique<OpenChunk>();
    chunk->pos = info.pos;
    file.LoadChunk(info.pos, layout.connections, chunk->data, chunk->messages);
    if (layout.indexed) file.CheckChunk(info, chunk->messages);
    // A recorder writes messages as they come; a chunk out of time order is sorted, equal times
    // keeping their storage order.
    const auto by_time = [](const Ros1MessageEntry& a, const Ros1MessageEntry& b) {
      return a.time_ns < b.time_ns;
    };
    if (!std::is_sorted(chunk->messages.begin(), chunk->messages.end(), by_time)) {
      std::stable_sort(chunk->messages.begin(), chunk->messages.end(), by_time);
    }
    if (chunk->messages.empty()) return;
    held_bytes += chunk->data.size();
    if (held_bytes > kRos1BagMaxChunkBytes) {
      throw core::IoError(file.name() + ": the chunks that overlap in time up to the one at byte " +
                          std::to_string(info.pos) + " hold more than " +
                          std::to_string(kRos1BagMaxChunkBytes) +
                          " bytes, too many to merge in time order");
    }
    open.push_back(std::move(chunk));
  }

  // Drops the chunks whose messages have all been handed out.
  void DropDoneChunks() {
    std::erase_if(open, [this](const std::unique_ptr<OpenChunk>& c) {
      if (!c->done()) return false;
      held_bytes -= c->data.size();
      return true;
    });
  }

  // The open chunk with the earliest next message, or none.
  OpenChunk* Earliest() const {
    OpenChunk* best = nullptr;
    for (const std::unique_ptr<OpenChunk>& c : open) {
      if (best == nullptr || EarlierHead(*c, *best)) best = c.get();
    }
    return best;
  }
};

Ros1BagReader::Ros1BagReader(const std::filesystem::path& file)
    : state_(std::make_unique<State>(file)) {}

Ros1BagReader::~Ros1BagReader() = default;

const std::string& Ros1BagReader::name() const { return state_->file.name(); }

std::vector<std::string> Ros1BagReader::notes() const { return state_->layout.notes; }

bool Ros1BagReader::indexed() const { return state_->layout.indexed; }

std::size_t Ros1BagReader::chunk_count() const { return state_->layout.chunks.size(); }

bool Ros1BagReader::Next(RawMessage& message) {
  State& s = *state_;
  // The message handed out last is no longer viewed: its chunk may go if it is done.
  s.DropDoneChunks();
  for (;;) {
    OpenChunk* best = s.Earliest();
    // A chunk whose first message is not later than the earliest due one may hold earlier ones.
    if (s.next_chunk < s.layout.chunks.size() &&
        (best == nullptr || s.layout.chunks[s.next_chunk].start_ns <= best->head_ns())) {
      s.OpenNextChunk();
      continue;
    }
    if (best == nullptr) return false;
    const Ros1MessageEntry& m = best->messages[best->next++];
    const internal::Ros1Connection& c = s.layout.connections.at(m.conn);
    message.topic = c.topic;
    message.type = c.type;
    message.md5sum = c.md5sum;
    message.encoding = "ros1";
    message.log_time_ns = m.time_ns;
    message.data = std::span<const std::uint8_t>(best->data).subspan(m.offset, m.size);
    return true;
  }
}

}  // namespace retrace::logs

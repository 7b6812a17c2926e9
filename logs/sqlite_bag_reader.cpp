#include "logs/sqlite_bag_reader.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>

#include "core/errors.hpp"

namespace retrace::logs {
namespace {

// The first 16 bytes of every SQLite 3 database file.
constexpr std::array<char, 16> kSqliteMagic = {'S', 'Q', 'L', 'i', 't', 'e', ' ', 'f',
                                               'o', 'r', 'm', 'a', 't', ' ', '3', '\0'};

}  // namespace

struct SqliteBagReader::Impl {
  std::string name;
  sqlite3* db = nullptr;
  sqlite3_stmt* messages = nullptr;
  std::vector<Topic> topics;
  std::unordered_map<std::int64_t, std::size_t> topic_index;
  int schema_version = 0;
  bool done = false;
  std::int64_t rows = 0;

  ~Impl() {
    sqlite3_finalize(messages);  // a no-op on nullptr
    sqlite3_close(db);
  }

  [[noreturn]] void Fail(const std::string& what) const { throw core::IoError(name + ": " + what); }

  [[noreturn]] void FailSqlite(const std::string& what) const {
    Fail(what + ": " + (db != nullptr ? sqlite3_errmsg(db) : "out of memory"));
  }

  // A prepared statement, finalized when it goes.
  struct Statement {
    sqlite3_stmt* stmt = nullptr;
    ~Statement() { sqlite3_finalize(stmt); }
  };

  void Prepare(const char* sql, sqlite3_stmt** stmt) const {
    if (sqlite3_prepare_v2(db, sql, -1, stmt, nullptr) != SQLITE_OK) {
      FailSqlite("cannot read the rosbag2 database");
    }
  }

  bool HasTable(const char* table) const {
    Statement s;
    Prepare("SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?1", &s.stmt);
    sqlite3_bind_text(s.stmt, 1, table, -1, SQLITE_STATIC);
    const int rc = sqlite3_step(s.stmt);
    if (rc != SQLITE_ROW && rc != SQLITE_DONE) FailSqlite("cannot read the database's tables");
    return rc == SQLITE_ROW;
  }

  std::string Text(sqlite3_stmt* stmt, int column, const char* what) const {
    const unsigned char* text = sqlite3_column_text(stmt, column);
    if (text == nullptr) Fail(std::string("a topic's ") + what + " is NULL");
    return std::string(reinterpret_cast<const char*>(text),
                       static_cast<std::size_t>(sqlite3_column_bytes(stmt, column)));
  }

  void ReadTopics() {
    Statement s;
    Prepare("SELECT id, name, type, serialization_format FROM topics ORDER BY id", &s.stmt);
    int rc = 0;
    while ((rc = sqlite3_step(s.stmt)) == SQLITE_ROW) {
      Topic t;
      t.id = sqlite3_column_int64(s.stmt, 0);
      t.name = Text(s.stmt, 1, "name");
      t.type = Text(s.stmt, 2, "type");
      t.serialization_format = Text(s.stmt, 3, "serialization_format");
      topic_index[t.id] = topics.size();
      topics.push_back(std::move(t));
    }
    if (rc != SQLITE_DONE) FailSqlite("cannot read the topics table");
  }

  void ReadSchemaVersion() {
    if (!HasTable("schema")) return;
    Statement s;
    Prepare("SELECT MAX(schema_version) FROM schema", &s.stmt);
    if (sqlite3_step(s.stmt) == SQLITE_ROW) schema_version = sqlite3_column_int(s.stmt, 0);
  }
};

SqliteBagReader::SqliteBagReader(const std::filesystem::path& db3)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.name = db3.string();
  std::error_code ec;
  if (std::filesystem::is_directory(db3, ec)) {
    m.Fail("cannot open file: it is a folder (a rosbag2 bag's folder? open its .db3 file)");
  }
  {
    // SQLite would create an empty database for a missing file and report any other file only
    // at the first query; checking the magic first gives the clear message.
    std::ifstream in(db3, std::ios::binary);
    if (!in) m.Fail("cannot open file");
    std::array<char, 16> head{};
    in.read(head.data(), head.size());
    if (in.gcount() != static_cast<std::streamsize>(head.size()) || head != kSqliteMagic) {
      m.Fail("not a SQLite database (a rosbag2 .db3 file starts with \"SQLite format 3\")");
    }
  }
  if (sqlite3_open_v2(m.name.c_str(), &m.db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    m.FailSqlite("cannot open the SQLite database");
  }
  for (const char* table : {"topics", "messages"}) {
    if (!m.HasTable(table)) {
      m.Fail(std::string("not a rosbag2 SQLite bag: it has no '") + table + "' table");
    }
  }
  m.ReadTopics();
  m.ReadSchemaVersion();
  // rosbag2's timestamp index (timestamp, then rowid = id) delivers this order without sorting,
  // so rows are streamed from the file; only a bag without the index has SQLite sort first.
  m.Prepare("SELECT topic_id, timestamp, data FROM messages ORDER BY timestamp, id", &m.messages);
}

SqliteBagReader::~SqliteBagReader() = default;

bool SqliteBagReader::Next(RawMessage& message) {
  Impl& m = *impl_;
  if (m.done) return false;
  const int rc = sqlite3_step(m.messages);
  if (rc == SQLITE_DONE) {
    m.done = true;  // stepping again would restart the query
    return false;
  }
  if (rc != SQLITE_ROW) m.FailSqlite("cannot read the messages table");
  ++m.rows;
  const std::int64_t topic_id = sqlite3_column_int64(m.messages, 0);
  const auto it = m.topic_index.find(topic_id);
  if (it == m.topic_index.end()) {
    m.Fail("message " + std::to_string(m.rows) + " refers to topic_id " + std::to_string(topic_id) +
           ", which the topics table does not have");
  }
  if (sqlite3_column_type(m.messages, 1) != SQLITE_INTEGER) {
    m.Fail("message " + std::to_string(m.rows) + " has no integer timestamp");
  }
  if (sqlite3_column_type(m.messages, 2) == SQLITE_NULL) {
    m.Fail("message " + std::to_string(m.rows) + " (topic " + m.topics[it->second].name +
           ") has NULL data");
  }
  const Topic& topic = m.topics[it->second];
  const void* blob = sqlite3_column_blob(m.messages, 2);
  const int bytes = sqlite3_column_bytes(m.messages, 2);
  message.topic = topic.name;
  message.type = topic.type;
  message.encoding = topic.serialization_format;
  message.log_time_ns = sqlite3_column_int64(m.messages, 1);
  message.data = blob == nullptr
                     ? std::span<const std::uint8_t>()
                     : std::span<const std::uint8_t>(static_cast<const std::uint8_t*>(blob),
                                                     static_cast<std::size_t>(bytes));
  return true;
}

const std::string& SqliteBagReader::name() const { return impl_->name; }

const std::vector<SqliteBagReader::Topic>& SqliteBagReader::topics() const { return impl_->topics; }

int SqliteBagReader::schema_version() const { return impl_->schema_version; }

}  // namespace retrace::logs

#include "perinom/io/checkpoint.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "perinom/core/error.hpp"

namespace perinom::io {
namespace {

constexpr char kMagic[8] = {'P', 'E', 'R', 'I', 'N', 'O', 'M', 'C'};
enum Kind : std::uint8_t { kReals = 1, kIntegers = 2, kText = 3 };

// Little-endian by shifts: the same bytes on any machine.
void put_u(std::string& out, std::uint64_t v, int bytes) {
  for (int b = 0; b < bytes; ++b) out += static_cast<char>((v >> (8 * b)) & 0xff);
}

void put_header(std::string& out, Kind kind, const std::string& name, std::uint64_t count) {
  out += static_cast<char>(kind);
  put_u(out, name.size(), 4);
  out += name;
  put_u(out, count, 8);
}

/// Reads from the bytes in order; every read checks the bytes are there.
struct Reader {
  const std::string& bytes;
  const std::string& source;
  std::size_t at = 0;
  std::uint64_t u(int n) {
    need(n);
    std::uint64_t v = 0;
    for (int b = 0; b < n; ++b) v |= std::uint64_t(static_cast<unsigned char>(bytes[at + b])) << (8 * b);
    at += n;
    return v;
  }
  std::string text(std::uint64_t n) {
    need(n);
    std::string s = bytes.substr(at, n);
    at += n;
    return s;
  }
  /// `count` items of `size` bytes are left to read.
  void need(std::uint64_t count, std::uint64_t size = 1) const {
    if (count > (bytes.size() - at) / size)
      throw InputError(source + ": the checkpoint is truncated (" + std::to_string(bytes.size()) + " bytes)");
  }
};

const char* kind_name(Kind k) { return k == kReals ? "reals" : k == kIntegers ? "whole numbers" : "text"; }

}  // namespace

std::uint64_t fnv1a64(const void* data, std::size_t n) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  std::uint64_t h = 14695981039346656037ull;
  for (std::size_t k = 0; k < n; ++k) h = (h ^ bytes[k]) * 1099511628211ull;
  return h;
}

void Checkpoint::put(const std::string& name, std::vector<double> values) { reals_[name] = std::move(values); }
void Checkpoint::put(const std::string& name, std::vector<std::int64_t> values) { integers_[name] = std::move(values); }
void Checkpoint::put(const std::string& name, std::string text) { texts_[name] = std::move(text); }

bool Checkpoint::has(const std::string& name) const {
  return reals_.count(name) || integers_.count(name) || texts_.count(name);
}

template <class Map>
static const typename Map::mapped_type& record_of(const Map& map, const Checkpoint& c, const std::string& name,
                                             const char* kind, std::size_t expected) {
  const auto it = map.find(name);
  if (it == map.end())
    throw InputError(c.source + ": the checkpoint has no record '" + name + "' (of " + kind + ")" +
                     (c.has(name) ? ", only one of another kind" : ""));
  if (expected != Checkpoint::npos && it->second.size() != expected)
    throw InputError(c.source + ": the checkpoint's record '" + name + "' holds " + std::to_string(it->second.size()) +
                     " values, not " + std::to_string(expected));
  return it->second;
}

const std::vector<double>& Checkpoint::reals(const std::string& name, std::size_t expected) const {
  return record_of(reals_, *this, name, kind_name(kReals), expected);
}
const std::vector<std::int64_t>& Checkpoint::integers(const std::string& name, std::size_t expected) const {
  return record_of(integers_, *this, name, kind_name(kIntegers), expected);
}
const std::string& Checkpoint::text(const std::string& name) const {
  return record_of(texts_, *this, name, kind_name(kText), npos);
}

std::string encode(const Checkpoint& c) {
  std::string out(kMagic, sizeof kMagic);
  put_u(out, checkpoint_format_version, 4);
  put_u(out, c.reals_.size() + c.integers_.size() + c.texts_.size(), 4);
  for (const auto& [name, values] : c.reals_) {
    put_header(out, kReals, name, values.size());
    for (const double v : values) {
      std::uint64_t bits;
      std::memcpy(&bits, &v, sizeof bits);
      put_u(out, bits, 8);
    }
  }
  for (const auto& [name, values] : c.integers_) {
    put_header(out, kIntegers, name, values.size());
    for (const std::int64_t v : values) put_u(out, static_cast<std::uint64_t>(v), 8);
  }
  for (const auto& [name, text] : c.texts_) {
    put_header(out, kText, name, text.size());
    out += text;
  }
  put_u(out, fnv1a64(out.data(), out.size()), 8);
  return out;
}

Checkpoint decode(const std::string& bytes, const std::string& source) {
  if (bytes.size() < sizeof kMagic || bytes.compare(0, sizeof kMagic, kMagic, sizeof kMagic) != 0)
    throw InputError(source + ": not a perinom checkpoint (it does not start with PERINOMC)");
  Reader in{bytes, source, sizeof kMagic};
  const std::uint64_t version = in.u(4);
  if (version != checkpoint_format_version)
    throw InputError(source + ": a checkpoint of format version " + std::to_string(version) + "; this perinom reads version " +
                     std::to_string(checkpoint_format_version));
  in.need(4 + 8);  // the record count and the checksum
  Reader tail{bytes, source, bytes.size() - 8};
  if (tail.u(8) != fnv1a64(bytes.data(), bytes.size() - 8))
    throw InputError(source + ": the checkpoint is damaged or truncated (its checksum does not match)");
  const std::string body = bytes.substr(0, bytes.size() - 8);
  Reader r{body, source, in.at};
  Checkpoint c;
  c.source = source;
  for (std::uint64_t records = r.u(4); records > 0; --records) {
    const auto kind = static_cast<Kind>(r.u(1));
    const std::string name = r.text(r.u(4));
    const std::uint64_t count = r.u(8);
    if (kind == kText) {
      c.texts_[name] = r.text(count);
    } else if (kind == kReals || kind == kIntegers) {
      r.need(count, 8);
      if (kind == kReals) {
        auto& v = c.reals_[name];
        v.resize(count);
        for (auto& x : v) {
          const std::uint64_t bits = r.u(8);
          std::memcpy(&x, &bits, sizeof x);
        }
      } else {
        auto& v = c.integers_[name];
        v.resize(count);
        for (auto& x : v) x = static_cast<std::int64_t>(r.u(8));
      }
    } else {
      throw InputError(source + ": the checkpoint's record '" + name + "' has an unknown kind " + std::to_string(kind));
    }
  }
  if (r.at != body.size()) throw InputError(source + ": the checkpoint has bytes after its last record");
  return c;
}

void write_checkpoint(const std::string& path, const Checkpoint& c) {
  const std::string bytes = encode(c), tmp = path + ".tmp";
  const auto fail = [&](const std::string& what) {
    const std::string reason = std::strerror(errno);
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    return InputError("cannot write checkpoint '" + path + "': " + what + " '" + tmp + "' failed: " + reason);
  };
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw fail("opening");
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ::close(fd);
      throw fail("writing");
    }
    done += static_cast<std::size_t>(n);
  }
  // On disk before the rename: after a crash the name holds the old checkpoint or the new one.
  if (::fsync(fd) != 0) {
    ::close(fd);
    throw fail("syncing");
  }
  if (::close(fd) != 0) throw fail("closing");
  if (::rename(tmp.c_str(), path.c_str()) != 0) throw fail("renaming");
  const std::string folder = std::filesystem::path(path).parent_path().string();
  const int dir = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) {
    ::fsync(dir);  // the rename itself; a folder that cannot be synced still holds a whole file
    ::close(dir);
  }
}

Checkpoint read_checkpoint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the checkpoint");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) throw InputError(path + ": cannot read the checkpoint");
  return decode(bytes.str(), path);
}

}  // namespace perinom::io

#pragma once
/// @file A checkpoint file: named records of reals, whole numbers and texts, written
/// atomically and read back bit for bit. What the records mean is the writer's business
/// (a solver state: io/solver_states.hpp; the run command adds its own: drivers/run_checkpoint.hpp);
/// this is only the format.
///
/// Layout, every number little-endian whatever the machine:
///   8 bytes   magic "PERINOMC"
///   u32       format version (checkpoint_format_version)
///   u32       number of records
///   records   u8 kind (1 reals: IEEE 754 doubles, 2 whole numbers: int64, 3 text: bytes),
///             u32 name length, the name, u64 count, then count * 8 bytes (reals, whole
///             numbers) or count bytes (text)
///   u64       FNV-1a 64 checksum of every byte before it
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace perinom::io {

constexpr std::uint32_t checkpoint_format_version = 1;

class Checkpoint {
 public:
  void put(const std::string& name, std::vector<double> values);
  void put(const std::string& name, std::vector<std::int64_t> values);
  void put(const std::string& name, std::string text);
  /// A record of one number, for counters and scalars.
  void put_real(const std::string& name, double value) { put(name, std::vector<double>{value}); }
  void put_integer(const std::string& name, std::int64_t value) { put(name, std::vector<std::int64_t>{value}); }

  bool has(const std::string& name) const;
  /// The record `name`; throws InputError naming the record and the file (source) when it is
  /// missing, of another kind, or (expected_size given) of another length.
  const std::vector<double>& reals(const std::string& name, std::size_t expected_size = npos) const;
  const std::vector<std::int64_t>& integers(const std::string& name, std::size_t expected_size = npos) const;
  const std::string& text(const std::string& name) const;
  double real(const std::string& name) const { return reals(name, 1)[0]; }
  std::int64_t integer(const std::string& name) const { return integers(name, 1)[0]; }

  /// The file it was read from, for messages ("" when built in memory).
  std::string source;
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);

 private:
  friend std::string encode(const Checkpoint& c);
  friend Checkpoint decode(const std::string& bytes, const std::string& source);
  std::map<std::string, std::vector<double>> reals_;
  std::map<std::string, std::vector<std::int64_t>> integers_;
  std::map<std::string, std::string> texts_;
};

/// FNV-1a 64 of `bytes` bytes at `data`: the file's checksum, and a fingerprint of arrays
/// a checkpoint must match (the particles' positions).
std::uint64_t fnv1a64(const void* data, std::size_t bytes);

/// The file's bytes, and back. decode throws InputError naming `source` for a file that is
/// not a checkpoint, of another format version, truncated, or whose checksum fails.
std::string encode(const Checkpoint& c);
Checkpoint decode(const std::string& bytes, const std::string& source);

/// Writes path + ".tmp", flushes it to disk (fsync), and renames it to path, so path always
/// holds a complete checkpoint, the old one until the new one is whole.
/// @throws perinom::InputError naming the path if it cannot be written.
void write_checkpoint(const std::string& path, const Checkpoint& c);
/// Reads a checkpoint; throws InputError naming the path if it cannot be read or decoded.
Checkpoint read_checkpoint(const std::string& path);

}  // namespace perinom::io

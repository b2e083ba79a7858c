#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "../support/cli.hpp"
#include "perinom/core/error.hpp"
#include "perinom/io/checkpoint.hpp"

using perinom::InputError;
using namespace perinom::io;

namespace {

/// The bits of a double, so -0.0, NaN payloads and denormals compare exactly.
std::uint64_t bits(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

Checkpoint sample() {
  Checkpoint c;
  double nan_payload;
  const std::uint64_t payload = 0x7ff8000000000123ull;
  std::memcpy(&nan_payload, &payload, sizeof nan_payload);
  c.put("u", std::vector<double>{0.1, -0.0, 1e-310, std::numeric_limits<double>::infinity(), nan_payload, 1.0 / 3.0});
  c.put("flags", std::vector<std::int64_t>{0, 1, -7, std::numeric_limits<std::int64_t>::max()});
  c.put("scene", std::string("name: a\nline two\n\0with a zero byte", 35));
  c.put_integer("step", 42);
  c.put("empty", std::vector<double>{});
  return c;
}

std::string read_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("a checkpoint reads back bit for bit", "[io][checkpoint]") {
  const Checkpoint c = sample();
  const Checkpoint back = decode(encode(c), "mem");
  const auto& u = back.reals("u", 6);
  for (std::size_t k = 0; k < u.size(); ++k) CHECK(bits(u[k]) == bits(c.reals("u")[k]));
  CHECK(back.integers("flags") == c.integers("flags"));
  CHECK(back.text("scene") == c.text("scene"));
  CHECK(back.integer("step") == 42);
  CHECK(back.reals("empty").empty());
  // The same records give the same bytes, whatever order they were put in.
  Checkpoint reordered;
  reordered.put("empty", std::vector<double>{});
  reordered.put_integer("step", 42);
  reordered.put("scene", c.text("scene"));
  reordered.put("flags", c.integers("flags"));
  reordered.put("u", c.reals("u"));
  CHECK(encode(reordered) == encode(c));
}

TEST_CASE("a missing or misfit record is named with the file", "[io][checkpoint]") {
  const Checkpoint c = decode(encode(sample()), "run/checkpoint.bin");
  CHECK_THROWS_WITH(c.reals("v"), Catch::Contains("run/checkpoint.bin") && Catch::Contains("no record 'v'"));
  CHECK_THROWS_WITH(c.reals("u", 7), Catch::Contains("'u' holds 6 values, not 7"));
  CHECK_THROWS_WITH(c.reals("step"), Catch::Contains("only one of another kind"));
}

TEST_CASE("a damaged, truncated or foreign checkpoint is refused", "[io][checkpoint]") {
  const std::string bytes = encode(sample());
  SECTION("every truncation") {
    for (std::size_t n = 0; n < bytes.size(); ++n) {
      INFO("first " << n << " bytes");
      CHECK_THROWS_AS(decode(bytes.substr(0, n), "c"), InputError);
    }
  }
  SECTION("every single flipped byte") {
    for (std::size_t k = 0; k < bytes.size(); ++k) {
      std::string bad = bytes;
      bad[k] = static_cast<char>(bad[k] ^ 0x10);
      INFO("byte " << k);
      CHECK_THROWS_AS(decode(bad, "c"), InputError);
    }
  }
  SECTION("the messages say why") {
    std::string flipped = bytes;
    flipped[bytes.size() / 2] ^= 1;
    CHECK_THROWS_WITH(decode(flipped, "c"), Catch::Contains("checksum does not match"));
    CHECK_THROWS_WITH(decode(bytes.substr(0, bytes.size() - 1), "c"), Catch::Contains("damaged or truncated"));
    CHECK_THROWS_WITH(decode("name: a scene\n", "c"), Catch::Contains("not a perinom checkpoint"));
    std::string future = bytes;
    future[8] = 2;  // the format version's low byte
    CHECK_THROWS_WITH(decode(future, "c"), Catch::Contains("format version 2; this perinom reads version 1"));
  }
}

TEST_CASE("writing a checkpoint replaces the old one whole and leaves no .tmp", "[io][checkpoint]") {
  cli_test::ScratchDir dir;
  const std::string path = (dir.path / "checkpoint.bin").string();
  Checkpoint first;
  first.put_integer("step", 1);
  write_checkpoint(path, first);
  write_checkpoint(path, sample());
  CHECK(read_bytes(path) == encode(sample()));
  CHECK(read_checkpoint(path).integer("step") == 42);
  CHECK_FALSE(std::filesystem::exists(path + ".tmp"));
  CHECK_THROWS_WITH(write_checkpoint((dir.path / "no" / "such" / "c.bin").string(), first),
                    Catch::Contains("cannot write checkpoint") && Catch::Contains("opening"));
  CHECK_THROWS_WITH(read_checkpoint((dir.path / "none.bin").string()), Catch::Contains("cannot open the checkpoint"));
}
